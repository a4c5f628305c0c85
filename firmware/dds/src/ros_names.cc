#include "hubrt/dds/ros_names.h"

#include <array>

namespace hubrt::dds {
namespace {

constexpr std::string_view kTopicPrefix = "rt";

bool is_alpha(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

Error bad_topic(std::string_view name, std::string_view rule) {
  return make_error(ErrorCode::kInvalidArgument,
                    "ROS topic name '" + std::string(name) + "' " + std::string(rule));
}

// A ROS package or type name: starts with a letter, then letters, digits and '_'.
bool is_identifier(std::string_view s) {
  if (s.empty() || !is_alpha(s.front())) return false;
  for (const char c : s) {
    if (!is_alpha(c) && !is_digit(c) && c != '_') return false;
  }
  return true;
}

bool is_interface_kind(std::string_view s) {
  return s == "msg" || s == "srv" || s == "action";
}

// Splits "a<sep>b<sep>c" into exactly three parts; false if there are more or fewer.
bool split3(std::string_view s, std::string_view sep, std::array<std::string_view, 3>& out) {
  for (std::size_t i = 0; i < 2; ++i) {
    const std::size_t pos = s.find(sep);
    if (pos == std::string_view::npos) return false;
    out[i] = s.substr(0, pos);
    s.remove_prefix(pos + sep.size());
  }
  if (s.find(sep) != std::string_view::npos) return false;
  out[2] = s;
  return true;
}

}  // namespace

Expected<void> validate_ros_topic_name(std::string_view name) {
  if (name.empty()) return bad_topic(name, "is empty");
  if (name.front() != '/') return bad_topic(name, "must start with '/' (fully qualified)");
  if (name.size() == 1) return bad_topic(name, "names no topic (only '/')");
  if (name.back() == '/') return bad_topic(name, "must not end with '/'");
  for (std::size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    if (c == '/') {
      if (i + 1 < name.size() && name[i + 1] == '/') {
        return bad_topic(name, "contains an empty segment ('//') at offset " + std::to_string(i));
      }
      if (i + 1 < name.size() && is_digit(name[i + 1])) {
        return bad_topic(name, "has a segment starting with a digit at offset " + std::to_string(i + 1));
      }
      continue;
    }
    if (!is_alpha(c) && !is_digit(c) && c != '_') {
      return bad_topic(name, "contains '" + std::string(1, c) + "' at offset " + std::to_string(i) +
                                 "; allowed are letters, digits, '_' and '/'");
    }
  }
  return {};
}

Expected<std::string> ros_to_dds_topic(std::string_view ros_name) {
  if (auto valid = validate_ros_topic_name(ros_name); !valid) return std::move(valid).error();
  std::string dds_name(kTopicPrefix);
  dds_name += ros_name;
  return dds_name;
}

std::optional<std::string> dds_to_ros_topic(std::string_view dds_name) {
  if (dds_name.size() <= kTopicPrefix.size() + 1 || !dds_name.starts_with(kTopicPrefix) ||
      dds_name[kTopicPrefix.size()] != '/') {
    return std::nullopt;
  }
  return std::string(dds_name.substr(kTopicPrefix.size()));
}

Expected<std::string> dds_to_ros_type(std::string_view dds_type_name) {
  // <pkg>::<kind>::dds_::<Type>_
  const auto fail = [&] {
    return make_error(ErrorCode::kInvalidArgument,
                      "DDS type name '" + std::string(dds_type_name) +
                          "' is not a ROS 2 type (expected <pkg>::msg::dds_::<Type>_)");
  };
  constexpr std::string_view kSep = "::";
  constexpr std::string_view kDdsModule = "::dds_::";
  const std::size_t dds_pos = dds_type_name.rfind(kDdsModule);
  if (dds_pos == std::string_view::npos) return fail();
  const std::string_view scope = dds_type_name.substr(0, dds_pos);
  std::string_view type = dds_type_name.substr(dds_pos + kDdsModule.size());
  if (type.size() < 2 || type.back() != '_') return fail();
  type.remove_suffix(1);
  const std::size_t sep = scope.find(kSep);
  if (sep == std::string_view::npos) return fail();
  const std::string_view pkg = scope.substr(0, sep);
  const std::string_view kind = scope.substr(sep + kSep.size());
  if (!is_identifier(pkg) || !is_interface_kind(kind) || !is_identifier(type)) return fail();
  return std::string(pkg) + "/" + std::string(kind) + "/" + std::string(type);
}

Expected<std::string> ros_to_dds_type(std::string_view ros_type_name) {
  std::array<std::string_view, 3> parts;
  if (!split3(ros_type_name, "/", parts) || !is_identifier(parts[0]) || !is_interface_kind(parts[1]) ||
      !is_identifier(parts[2])) {
    return make_error(ErrorCode::kInvalidArgument,
                      "ROS type name '" + std::string(ros_type_name) +
                          "' is not of the form <pkg>/msg/<Type> (letters, digits, '_')");
  }
  return std::string(parts[0]) + "::" + std::string(parts[1]) + "::dds_::" + std::string(parts[2]) + "_";
}

}  // namespace hubrt::dds
