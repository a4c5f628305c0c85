// Reading .msg text: ROS 1 files and definitions, and ROS 2 files turned into their ROS 1 form.
#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "hubrt/ros1/definition.h"

namespace hubrt::ros1 {
namespace {

constexpr std::string_view kBuiltins[] = {"bool",    "byte",   "char",   "int8",    "uint8",  "int16",
                                          "uint16",  "int32",  "uint32", "int64",   "uint64", "float32",
                                          "float64", "string", "time",   "duration"};

bool is_builtin(std::string_view t) {
  return std::find(std::begin(kBuiltins), std::end(kBuiltins), t) != std::end(kBuiltins);
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())) != 0) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())) != 0) s.remove_suffix(1);
  return s;
}

bool identifier(std::string_view s) {
  return !s.empty() && std::isalpha(static_cast<unsigned char>(s.front())) != 0 &&
         std::all_of(s.begin(), s.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; });
}

std::string package_of(std::string_view full_name) {
  return std::string(full_name.substr(0, full_name.find('/')));
}

// Which grammar a line is read with.
enum class Dialect : std::uint8_t { kRos1, kRos2 };

class MsgReader {
 public:
  MsgReader(std::string_view full_name, Dialect dialect) : dialect_(dialect) {
    message_.full_name = std::string(full_name);
    package_ = package_of(full_name);
  }

  Expected<Message> read(std::string_view text) {
    int line_no = 0;
    std::size_t pos = 0;
    while (pos <= text.size()) {
      const std::size_t end = std::min(text.find('\n', pos), text.size());
      const std::string_view raw = text.substr(pos, end - pos);
      pos = end + 1;
      ++line_no;
      if (auto ok = line(raw, line_no); !ok) return std::move(ok).error();
    }
    return std::move(message_);
  }

 private:
  Error error(int line_no, std::string_view what) const {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{} line {}: {}", message_.full_name, line_no, what));
  }

  // "hub_msgs/DockSlot[<=16]" -> type "hub_msgs/DockSlot", array "[]" (bounds dropped in ROS 1).
  Expected<Field> type_of(std::string_view token, int line_no) const {
    Field field;
    std::string_view base = token;
    if (const auto open = token.find('['); open != std::string_view::npos) {
      if (token.back() != ']') return error(line_no, fmt::format("malformed array type '{}'", token));
      base = token.substr(0, open);
      const std::string_view inside = token.substr(open + 1, token.size() - open - 2);
      const bool digits = !inside.empty() && std::all_of(inside.begin(), inside.end(), [](char c) {
        return std::isdigit(static_cast<unsigned char>(c)) != 0;
      });
      if (inside.empty() || (dialect_ == Dialect::kRos2 && inside.starts_with("<="))) {
        field.array = "[]";
      } else if (digits) {
        field.array = fmt::format("[{}]", inside);
      } else {
        return error(line_no, fmt::format("bad array size in '{}'", token));
      }
    }
    if (dialect_ == Dialect::kRos2) {
      if (const auto le = base.find("<="); le != std::string_view::npos) base = base.substr(0, le);
      if (base == "builtin_interfaces/Time") base = "time";
      if (base == "builtin_interfaces/Duration") base = "duration";
    }
    if (is_builtin(base)) {
      field.type = std::string(base);
    } else if (dialect_ == Dialect::kRos1 && base == "Header") {
      field.type = "std_msgs/Header";  // ROS 1's one special bare name (genmsg HEADER_FULL_NAME)
    } else {
      const auto slash = base.find('/');
      const std::string_view pkg =
          slash == std::string_view::npos ? std::string_view(package_) : base.substr(0, slash);
      const std::string_view name = slash == std::string_view::npos ? base : base.substr(slash + 1);
      if (!identifier(pkg) || !identifier(name)) {
        return error(line_no, fmt::format("'{}' is neither a primitive type nor a message type", base));
      }
      field.type = fmt::format("{}/{}", pkg, name);
    }
    return field;
  }

  Expected<void> line(std::string_view raw, int line_no) {
    const std::string_view head = trim(raw);
    if (head.empty() || head.front() == '#') return {};
    const auto space = std::find_if(head.begin(), head.end(),
                                    [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; });
    const std::string_view type_token = head.substr(0, static_cast<std::size_t>(space - head.begin()));
    const std::string_view rest = trim(head.substr(type_token.size()));
    const auto eq = rest.find('=');
    const bool is_string = type_token == "string" || type_token.starts_with("string<=");
    if (eq != std::string_view::npos && rest.find('#') > eq) {  // a '=' in a comment is no constant
      const std::string_view name = trim(rest.substr(0, eq));
      std::string_view value = rest.substr(eq + 1);
      // ROS 1: a string constant is everything right of '=' (comments included, genmsg
      // _load_constant_line); other constants and every ROS 2 value end at a '#'.
      if (!(dialect_ == Dialect::kRos1 && is_string)) value = value.substr(0, value.find('#'));
      value = trim(value);
      if (dialect_ == Dialect::kRos2 && is_string && value.size() >= 2 &&
          (value.front() == '"' || value.front() == '\'') && value.back() == value.front()) {
        value = value.substr(1, value.size() - 2);
      }
      if (!identifier(name)) return error(line_no, fmt::format("bad constant name '{}'", name));
      const std::string type = is_string ? "string" : std::string(type_token);
      if (!is_builtin(type)) return error(line_no, fmt::format("constant of non-primitive type '{}'", type));
      message_.constants.push_back(Constant{type, std::string(name), std::string(value)});
      return {};
    }
    std::string_view name = rest.substr(0, rest.find('#'));
    name = trim(name);
    // A ROS 2 field may carry a default value after its name; ROS 1 has none.
    if (dialect_ == Dialect::kRos2) name = name.substr(0, name.find_first_of(" \t"));
    if (!identifier(name)) return error(line_no, fmt::format("expected a field name after '{}'", type_token));
    auto field = type_of(type_token, line_no);
    if (!field) return std::move(field).error();
    field->name = std::string(name);
    message_.fields.push_back(std::move(*field));
    return {};
  }

  Dialect dialect_;
  std::string package_;
  Message message_;
};

}  // namespace

bool Field::builtin() const {
  return is_builtin(type);
}

std::string ros1_name_of(const msgs::TypeInfo& type) {
  const std::string_view ros = type.ros_name;
  if (ros == "builtin_interfaces/msg/Time") return "time";
  if (ros == "builtin_interfaces/msg/Duration") return "duration";
  const auto first = ros.find('/');
  const auto last = ros.rfind('/');
  if (first == std::string_view::npos || first == last) return std::string(ros.empty() ? type.dds_name : ros);
  return fmt::format("{}/{}", ros.substr(0, first), ros.substr(last + 1));
}

Expected<Message> parse_ros1_msg(std::string_view text, std::string_view full_name) {
  return MsgReader(full_name, Dialect::kRos1).read(text);
}

Expected<Message> ros1_from_ros2_msg(std::string_view text, std::string_view full_name) {
  return MsgReader(full_name, Dialect::kRos2).read(text);
}

Expected<Messages> parse_full_definition(std::string_view text, std::string_view full_name) {
  static const std::string kSeparator(80, '=');
  Messages out;
  std::string current(full_name);
  std::size_t pos = 0;
  while (true) {
    std::size_t sep = text.find(kSeparator, pos);
    // A separator counts only at the start of a line.
    while (sep != std::string_view::npos && sep != 0 && text[sep - 1] != '\n')
      sep = text.find(kSeparator, sep + 1);
    const std::string_view section =
        text.substr(pos, sep == std::string_view::npos ? std::string_view::npos : sep - pos);
    auto message = parse_ros1_msg(section, current);
    if (!message) return std::move(message).error();
    out.insert_or_assign(current, std::move(*message));
    if (sep == std::string_view::npos) break;
    pos = std::min(text.size(),
                   text.find('\n', sep) == std::string_view::npos ? text.size() : text.find('\n', sep) + 1);
    const std::size_t eol = std::min(text.find('\n', pos), text.size());
    const std::string_view header = trim(text.substr(pos, eol - pos));
    if (!header.starts_with("MSG:")) {
      return make_error(
          ErrorCode::kInvalidArgument,
          fmt::format("definition of {}: a section does not start with 'MSG: pkg/Type'", full_name));
    }
    current = std::string(trim(header.substr(4)));
    if (current.find('/') == std::string::npos)
      current = fmt::format("{}/{}", package_of(full_name), current);
    pos = std::min(eol + 1, text.size());
  }
  return out;
}

Expected<Messages> load_ros2_tree_as_ros1(const std::filesystem::path& root) {
  std::error_code ec;
  if (!std::filesystem::is_directory(root, ec)) {
    return make_error(ErrorCode::kNotFound, fmt::format("{}: no such directory", root.string()));
  }
  Messages out;
  for (const auto& pkg : std::filesystem::directory_iterator(root, ec)) {
    const auto dir = pkg.path() / "msg";
    if (!std::filesystem::is_directory(dir, ec)) continue;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
      if (entry.path().extension() != ".msg") continue;
      std::ifstream in(entry.path(), std::ios::binary);
      std::ostringstream text;
      text << in.rdbuf();
      if (!in) return make_error(ErrorCode::kIo, fmt::format("{}: cannot read", entry.path().string()));
      const std::string name =
          fmt::format("{}/{}", pkg.path().filename().string(), entry.path().stem().string());
      auto message = ros1_from_ros2_msg(text.str(), name);
      if (!message) {
        return make_error(ErrorCode::kInvalidArgument,
                          fmt::format("{}: {}", entry.path().string(), message.error().message));
      }
      out.insert_or_assign(name, std::move(*message));
    }
  }
  if (ec) return make_error(ErrorCode::kIo, fmt::format("{}: {}", root.string(), ec.message()));
  return out;
}

Expected<Messages> load_definitions_as_ros1(std::span<const msgs::MsgDefinition> definitions) {
  constexpr std::string_view kPackage = "hub_msgs/msg/";
  Messages out;
  for (const msgs::MsgDefinition& definition : definitions) {
    if (!definition.ros_name.starts_with(kPackage)) continue;
    const std::string name = fmt::format("hub_msgs/{}", definition.ros_name.substr(kPackage.size()));
    auto message = ros1_from_ros2_msg(definition.text, name);
    if (!message) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}.msg: {}", definition.ros_name, message.error().message));
    }
    out.insert_or_assign(name, std::move(*message));
  }
  return out;
}

std::string msg_text(const Message& message) {
  std::string out;
  for (const Constant& c : message.constants) out += fmt::format("{} {}={}\n", c.type, c.name, c.value);
  for (const Field& f : message.fields) out += f.text() + "\n";
  return out;
}

}  // namespace hubrt::ros1
