#include "hubrt/msgs/definitions.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "hubrt/msgs/ros_msg.h"

namespace hubrt::msgs {

// Defined by the program's message registry over the .msg texts of its message targets
// (hubrt_messages_write_registry_source: hubrt_msgs_all, or a board program's own).
std::span<const MsgDefinition> generated_msg_definitions() noexcept;

namespace {

// "pkg/msg/Type" for "pkg/msg/Type" or "pkg/Type"; empty for anything else.
std::string full_name(std::string_view ros_type) {
  const std::size_t slash = ros_type.find('/');
  if (slash == std::string_view::npos || slash == 0) return {};
  const std::string_view rest = ros_type.substr(slash + 1);
  if (rest.empty()) return {};
  if (rest.find('/') == std::string_view::npos)
    return fmt::format("{}/msg/{}", ros_type.substr(0, slash), rest);
  if (rest.substr(0, 4) != "msg/" || rest.size() == 4 || rest.find('/', 4) != std::string_view::npos)
    return {};
  return std::string(ros_type);
}

constexpr std::string_view kDelimiter =
    "================================================================================\n";
// Deeper than any real message nests: the definitions refer to each other in a cycle.
constexpr int kMaxDepth = 50;

// Appends the text of `ros_type` and, after it, each type it uses that `written` does not hold yet.
Expected<void> append_definition(std::string_view ros_type, int depth, std::set<std::string>& written,
                                 std::string& out) {
  if (depth > kMaxDepth) return make_error(ErrorCode::kInvalidArgument, "the definitions nest in a cycle");
  const std::string name = full_name(ros_type);
  const std::optional<std::string_view> own = msg_text(name);
  if (!own) return make_error(ErrorCode::kNotFound, fmt::format("no .msg definition of '{}'", ros_type));
  const std::string package = name.substr(0, name.find('/'));
  const std::string type = name.substr(name.rfind('/') + 1);
  Expected<ros::MsgSpec> spec = ros::parse_msg(*own, package, type, name + ".msg");
  if (!spec) return make_error(ErrorCode::kInvalidArgument, std::move(spec).error().message);
  out.append(*own);
  std::set<std::string> uses;  // sorted, as rosbag2 orders them
  for (const ros::MsgField& field : spec->fields) {
    if (field.element_type.find('/') != std::string::npos) uses.insert(field.element_type);
  }
  for (const std::string& use : uses) {
    if (!written.insert(use).second) continue;
    out.append("\n").append(kDelimiter).append("MSG: ").append(use).append("\n");
    Expected<void> nested = append_definition(use, depth + 1, written, out);
    if (!nested) return nested;
  }
  return {};
}

}  // namespace

std::span<const MsgDefinition> msg_definitions() noexcept {
  return generated_msg_definitions();
}

std::optional<std::string_view> msg_text(std::string_view ros_type) noexcept {
  std::string name;
  try {
    name = full_name(ros_type);
  } catch (...) {  // out of memory: nothing to find
    return std::nullopt;
  }
  const std::span<const MsgDefinition> all = msg_definitions();
  const auto it = std::lower_bound(all.begin(), all.end(), std::string_view(name),
                                   [](const MsgDefinition& d, std::string_view n) { return d.ros_name < n; });
  if (it == all.end() || it->ros_name != name) return std::nullopt;
  return it->text;
}

Expected<std::string> ros2msg_schema(std::string_view ros_type) {
  std::set<std::string> written;
  std::string text;
  Expected<void> done = append_definition(ros_type, 0, written, text);
  if (!done) {
    Error error = std::move(done).error();
    error.message = fmt::format("schema of '{}': {}", ros_type, error.message);
    return error;
  }
  return text;
}

}  // namespace hubrt::msgs
