#include "hubrt/msgs/json.h"

#include "json_value.h"

namespace hubrt::msgs {

nlohmann::ordered_json to_json(const TypeInfo& type, const void* sample) {
  return detail::struct_to_json(type, sample);
}

std::vector<std::string> invalid_utf8_fields(const TypeInfo& type, const void* sample) {
  return detail::invalid_utf8_fields(type, sample);
}

Expected<void> from_json(const TypeInfo& type, const nlohmann::ordered_json& value, void* sample) {
  if (auto ok = detail::check_struct_json(type, value, std::string()); !ok) return ok;
  detail::assign_struct_json(type, value, sample);
  return {};
}

}  // namespace hubrt::msgs
