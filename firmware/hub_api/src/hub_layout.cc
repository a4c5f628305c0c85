#include "hubrt/hub_api/hub_layout.h"

namespace hubrt::hub_api::detail {

Expected<std::size_t> struct_field_offset(const msgs::TypeInfo& outer, std::string_view name,
                                          const msgs::TypeInfo& inner, std::string_view hub_file) {
  for (const msgs::FieldInfo& field : outer.fields) {
    if (field.name != name) continue;
    if (field.kind == msgs::FieldKind::kStruct && field.nested == &inner) return field.offset;
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("{}: layout 'hub': field '{}' of {} is a {}, but node '{}' needs a {}", hub_file, name,
                    outer.ros_name, msgs::describe_type(field), name, inner.ros_name));
  }
  std::string fields;
  for (const msgs::FieldInfo& field : outer.fields) {
    if (field.kind == msgs::FieldKind::kStruct && field.nested != nullptr &&
        field.nested->ros_name.find("StateHeader") == std::string_view::npos) {
      fields += fmt::format("{}{}", fields.empty() ? "" : ", ", field.name);
    }
  }
  return make_error(
      ErrorCode::kInvalidArgument,
      fmt::format("{}: layout 'hub': {} has no field for node '{}' (in the hub layout node names are "
                  "fixed by the message: {})",
                  hub_file, outer.ros_name, name, fields));
}

}  // namespace hubrt::hub_api::detail
