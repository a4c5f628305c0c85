#include "hubrt/msgs/type_info.h"

#include <string>

namespace hubrt::msgs {
namespace {

std::string element_name(const FieldInfo& field) {
  if (field.element_kind == FieldKind::kStruct && field.nested != nullptr) {
    return std::string(field.nested->ros_name.empty() ? field.nested->dds_name : field.nested->ros_name);
  }
  if (field.element_kind == FieldKind::kString && field.string_bound != 0) {
    return "string<" + std::to_string(field.string_bound) + ">";
  }
  return std::string(to_string(field.element_kind));
}

}  // namespace

std::string_view to_string(FieldKind kind) noexcept {
  switch (kind) {
    case FieldKind::kBool:
      return "bool";
    case FieldKind::kOctet:
      return "octet";
    case FieldKind::kInt8:
      return "int8";
    case FieldKind::kUInt8:
      return "uint8";
    case FieldKind::kInt16:
      return "int16";
    case FieldKind::kUInt16:
      return "uint16";
    case FieldKind::kInt32:
      return "int32";
    case FieldKind::kUInt32:
      return "uint32";
    case FieldKind::kInt64:
      return "int64";
    case FieldKind::kUInt64:
      return "uint64";
    case FieldKind::kFloat32:
      return "float32";
    case FieldKind::kFloat64:
      return "float64";
    case FieldKind::kString:
      return "string";
    case FieldKind::kStruct:
      return "struct";
    case FieldKind::kSequence:
      return "sequence";
    case FieldKind::kArray:
      return "array";
  }
  return "unknown";
}

std::string describe_type(const FieldInfo& field) {
  switch (field.kind) {
    case FieldKind::kSequence:
      return "sequence<" + element_name(field) +
             (field.bound != 0 ? ", " + std::to_string(field.bound) : "") + ">";
    case FieldKind::kArray:
      return element_name(field) + "[" + std::to_string(field.bound) + "]";
    default:
      return element_name(field);
  }
}

}  // namespace hubrt::msgs
