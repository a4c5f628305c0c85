// hubctl send's FIELD=VALUE arguments. Input: a message type on the first line
// ("hub_msgs/msg/DockCommand", as --type takes it), then one argument per line, each split at the
// first '=' and set with set_field (paths, indices, JSON values for whole structs and sequences).
// Then the JSON round trip hubctl makes before sending (to_json, from_json).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hubrt/dds/sample.h"
#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/json.h"
#include "hubrt/msgs/set_field.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  const auto newline = rest.find('\n');
  if (newline == std::string_view::npos) return 0;
  const hubrt::msgs::TypeInfo* type = hubrt::msgs::all_types().find(rest.substr(0, newline));
  if (type == nullptr || type->descriptor == nullptr) return 0;
  rest.remove_prefix(newline + 1);
  hubrt::dds::UntypedSample sample(*type->descriptor);
  while (!rest.empty()) {
    const auto end = rest.find('\n');
    const std::string_view assignment = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    const auto eq = assignment.find('=');
    if (eq == std::string_view::npos || eq == 0) continue;  // hubctl: "is not FIELD=VALUE"
    (void)hubrt::msgs::set_field(*type, sample.data(), assignment.substr(0, eq), assignment.substr(eq + 1));
  }
  const auto json = hubrt::msgs::to_json(*type, sample.data());
  (void)hubrt::msgs::from_json(*type, json, sample.data());
  (void)json.dump();
  return 0;
}
