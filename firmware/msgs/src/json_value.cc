#include "json_value.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hubrt/base/utf8.h"

#include "closest_names.h"
#include "sample_access.h"

namespace hubrt::msgs::detail {
namespace {

std::string join_path(const std::string& path, std::string_view name) {
  return path.empty() ? std::string(name) : fmt::format("{}.{}", path, name);
}

Error wrong_type(const std::string& path, std::string_view expected, const Json& value) {
  return make_error(ErrorCode::kInvalidArgument,
                    fmt::format("{}: expected {}, got {}", path, expected, describe_json(value)));
}

// The shortest decimal that reads back as the same float, so 0.8f shows as 0.8, not 0.800000011920929.
double float_as_decimal(float f) {
  char buf[32];
  const auto written = std::to_chars(buf, buf + sizeof buf, f);
  double d = 0.0;
  std::from_chars(buf, written.ptr, d);
  return d;
}

Json scalar_to_json(FieldKind kind, const void* addr) {
  const Scalar v = load_scalar(kind, addr);
  if (const auto* b = std::get_if<bool>(&v)) return *b;
  if (const auto* s = std::get_if<std::int64_t>(&v)) return *s;
  if (const auto* u = std::get_if<std::uint64_t>(&v)) return *u;
  const double d = std::get<double>(v);
  if (!std::isfinite(d)) return nullptr;
  if (kind == FieldKind::kFloat32) return float_as_decimal(static_cast<float>(d));
  return d;
}

Expected<Scalar> scalar_from_json(FieldKind kind, const Json& value, const std::string& path) {
  Scalar out;
  if (kind == FieldKind::kBool) {
    if (!value.is_boolean()) return wrong_type(path, "true or false", value);
    out = value.get<bool>();
  } else if (is_integer(kind)) {
    if (value.is_number_unsigned()) {
      out = value.get<std::uint64_t>();
    } else if (value.is_number_integer()) {
      out = value.get<std::int64_t>();
    } else {
      return wrong_type(path, fmt::format("an integer ({}: {})", to_string(kind), integer_range(kind)),
                        value);
    }
  } else {
    if (value.is_null()) {
      out = std::nan("");
    } else if (value.is_number()) {
      out = value.get<double>();
    } else {
      return wrong_type(path, fmt::format("a number ({})", to_string(kind)), value);
    }
  }
  if (auto problem = range_problem(kind, out); !problem.empty()) {
    return make_error(ErrorCode::kOutOfRange, fmt::format("{}: {}", path, problem));
  }
  return out;
}

// A received string as JSON can hold it: valid UTF-8 as it is; otherwise escaped (hubrt/base/
// utf8.h), because nlohmann::json's dump() throws type_error 316 on invalid UTF-8 and a JSON
// reader would reject it.
std::string shown_text(std::string_view text) {
  if (is_valid_utf8(text)) return std::string(text);
  std::string out(4 * text.size(), '\0');  // every byte escaped (\xHH) at worst
  const EscapedUtf8 escaped = append_escaped_utf8(text, out);
  out.resize(escaped.written);
  return out;
}

void collect_invalid_utf8(const FieldInfo& slot, const void* addr, const std::string& path,
                          std::vector<std::string>& out) {
  switch (slot.kind) {
    case FieldKind::kString:
      if (!is_valid_utf8(string_at(slot, addr))) out.push_back(path);
      return;
    case FieldKind::kStruct:
      for (const FieldInfo& f : slot.nested->fields)
        collect_invalid_utf8(f, field_address(addr, f), join_path(path, f.name), out);
      return;
    case FieldKind::kSequence:
    case FieldKind::kArray: {
      if (slot.element_kind != FieldKind::kString && slot.element_kind != FieldKind::kStruct) return;
      const FieldInfo element = element_slot(slot);
      const std::size_t n = element_count(slot, addr);
      for (std::size_t i = 0; i < n; ++i)
        collect_invalid_utf8(element, element_address(slot, addr, i), fmt::format("{}[{}]", path, i), out);
      return;
    }
    default:
      return;
  }
}

}  // namespace

std::vector<std::string> invalid_utf8_fields(const TypeInfo& type, const void* sample) {
  std::vector<std::string> out;
  for (const FieldInfo& f : type.fields)
    collect_invalid_utf8(f, field_address(sample, f), std::string(f.name), out);
  return out;
}

std::string_view display_name(const TypeInfo& type) {
  return type.ros_name.empty() ? type.dds_name : type.ros_name;
}

FieldInfo element_slot(const FieldInfo& container) {
  return FieldInfo{
      container.name,   container.element_kind, container.element_kind, 0, container.element_size, 0,
      container.nested, container.string_bound};
}

const FieldInfo* find_field(const TypeInfo& type, std::string_view name) {
  for (const FieldInfo& f : type.fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

Error unknown_field(const TypeInfo& type, std::string_view name, std::string_view path) {
  std::vector<std::string_view> names;
  for (const FieldInfo& f : type.fields) names.push_back(f.name);
  const auto close = closest_names(name, names, 3);
  std::string hint;
  if (!close.empty()) hint = fmt::format("; did you mean '{}'?", fmt::join(close, "', '"));
  return make_error(ErrorCode::kInvalidArgument,
                    fmt::format("unknown field '{}': {} has no field '{}'{} (its fields: {})", path,
                                display_name(type), name, hint, fmt::join(names, ", ")));
}

std::string describe_json(const Json& value) {
  switch (value.type()) {
    case Json::value_t::object:
      return "an object";
    case Json::value_t::array:
      return fmt::format("an array of {}", value.size());
    case Json::value_t::null:
      return "null";
    case Json::value_t::string: {
      const auto& s = value.get_ref<const std::string&>();
      return s.size() > 40 ? fmt::format("'{}...'", s.substr(0, 40)) : fmt::format("'{}'", s);
    }
    default:
      return value.dump();
  }
}

Json slot_to_json(const FieldInfo& slot, const void* addr) {
  switch (slot.kind) {
    case FieldKind::kString:
      return shown_text(string_at(slot, addr));
    case FieldKind::kStruct:
      return struct_to_json(*slot.nested, addr);
    case FieldKind::kSequence:
    case FieldKind::kArray: {
      Json out = Json::array();
      const FieldInfo element = element_slot(slot);
      const std::size_t n = element_count(slot, addr);
      for (std::size_t i = 0; i < n; ++i)
        out.push_back(slot_to_json(element, element_address(slot, addr, i)));
      return out;
    }
    default:
      return scalar_to_json(slot.kind, addr);
  }
}

Json struct_to_json(const TypeInfo& type, const void* addr) {
  Json out = Json::object();
  for (const FieldInfo& f : type.fields) out[std::string(f.name)] = slot_to_json(f, field_address(addr, f));
  return out;
}

Expected<void> check_slot_json(const FieldInfo& slot, const Json& value, const std::string& path) {
  switch (slot.kind) {
    case FieldKind::kString:
      if (!value.is_string()) return wrong_type(path, "a string", value);
      if (value.get_ref<const std::string&>().find('\0') != std::string::npos) {
        return make_error(ErrorCode::kInvalidArgument,
                          fmt::format("{}: strings cannot contain a NUL character", path));
      }
      if (slot.string_bound != 0 && value.get_ref<const std::string&>().size() > slot.string_bound) {
        return make_error(ErrorCode::kOutOfRange,
                          fmt::format("{}: at most {} bytes ({}), got {}", path, slot.string_bound,
                                      describe_type(slot), value.get_ref<const std::string&>().size()));
      }
      return {};
    case FieldKind::kStruct:
      return check_struct_json(*slot.nested, value, path);
    case FieldKind::kSequence:
    case FieldKind::kArray: {
      if (!value.is_array())
        return wrong_type(path, fmt::format("an array ({})", describe_type(slot)), value);
      if (slot.kind == FieldKind::kArray && value.size() != slot.bound) {
        return make_error(ErrorCode::kInvalidArgument,
                          fmt::format("{}: expected exactly {} elements ({}), got {}", path, slot.bound,
                                      describe_type(slot), value.size()));
      }
      if (slot.kind == FieldKind::kSequence && slot.bound != 0 && value.size() > slot.bound) {
        return make_error(ErrorCode::kOutOfRange, fmt::format("{}: at most {} elements ({}), got {}", path,
                                                              slot.bound, describe_type(slot), value.size()));
      }
      const FieldInfo element = element_slot(slot);
      for (std::size_t i = 0; i < value.size(); ++i) {
        if (auto ok = check_slot_json(element, value[i], fmt::format("{}[{}]", path, i)); !ok) return ok;
      }
      return {};
    }
    default: {
      auto scalar = scalar_from_json(slot.kind, value, path);
      if (!scalar) return std::move(scalar).error();
      return {};
    }
  }
}

Expected<void> check_struct_json(const TypeInfo& type, const Json& value, const std::string& path) {
  if (!value.is_object()) {
    return wrong_type(path.empty() ? std::string(display_name(type)) : path,
                      fmt::format("an object ({})", display_name(type)), value);
  }
  for (const auto& [key, member] : value.items()) {
    const std::string member_path = join_path(path, key);
    const FieldInfo* f = find_field(type, key);
    if (f == nullptr) return unknown_field(type, key, member_path);
    if (auto ok = check_slot_json(*f, member, member_path); !ok) return ok;
  }
  return {};
}

void assign_slot_json(const FieldInfo& slot, const Json& value, void* addr) {
  switch (slot.kind) {
    case FieldKind::kString:
      store_string(slot, addr, value.get_ref<const std::string&>());
      break;
    case FieldKind::kStruct:
      assign_struct_json(*slot.nested, value, addr);
      break;
    case FieldKind::kSequence:
    case FieldKind::kArray: {
      if (slot.kind == FieldKind::kSequence) {
        // Replaced whole: drop the old elements first so that none of their contents survive.
        resize_sequence(slot, addr, 0);
        resize_sequence(slot, addr, value.size());
      }
      const FieldInfo element = element_slot(slot);
      for (std::size_t i = 0; i < value.size(); ++i)
        assign_slot_json(element, value[i], element_address(slot, addr, i));
      break;
    }
    default: {
      // check_slot_json() accepted the value, so the conversion succeeds.
      auto scalar = scalar_from_json(slot.kind, value, std::string());
      if (scalar) store_scalar(slot.kind, addr, *scalar);
      break;
    }
  }
}

void assign_struct_json(const TypeInfo& type, const Json& value, void* addr) {
  for (const auto& [key, member] : value.items()) {
    const FieldInfo* f = find_field(type, key);
    if (f != nullptr) assign_slot_json(*f, member, field_address(addr, *f));
  }
}

}  // namespace hubrt::msgs::detail
