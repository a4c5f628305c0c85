#include "hubrt/msgs/ros_msg.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <sstream>
#include <system_error>

#include <fmt/format.h>

#include "msg_values.h"

namespace hubrt::msgs::ros {
namespace {

constexpr std::string_view kPrimitives[] = {"bool",   "byte",  "char",   "float32", "float64",
                                            "int8",   "uint8", "int16",  "uint16",  "int32",
                                            "uint32", "int64", "uint64", "string",  "wstring"};

bool is_primitive(std::string_view t) {
  return std::find(std::begin(kPrimitives), std::end(kPrimitives), t) != std::end(kPrimitives);
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())) != 0) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())) != 0) s.remove_suffix(1);
  return s;
}

// The line without its comment; a '#' inside a quoted constant or default value is kept (inside
// quotes a backslash escapes the next character, as in 'it\'s').
std::string_view strip_comment(std::string_view line) {
  char quote = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote != 0) {
      if (c == '\\') {
        ++i;
      } else if (c == quote) {
        quote = 0;
      }
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '#') {
      return line.substr(0, i);
    }
  }
  return line;
}

bool all_of(std::string_view s, bool (*ok)(char)) {
  return std::all_of(s.begin(), s.end(), [ok](char c) { return ok(c); });
}
bool lower_or_digit(char c) {
  return std::islower(static_cast<unsigned char>(c)) != 0 ||
         std::isdigit(static_cast<unsigned char>(c)) != 0 || c == '_';
}
bool upper_or_digit(char c) {
  return std::isupper(static_cast<unsigned char>(c)) != 0 ||
         std::isdigit(static_cast<unsigned char>(c)) != 0 || c == '_';
}
bool alnum(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0;
}

// ROS 2 field names: lower case, digits and single underscores, starting with a letter.
bool valid_field_name(std::string_view n) {
  return !n.empty() && std::islower(static_cast<unsigned char>(n.front())) != 0 &&
         all_of(n, lower_or_digit) && n.find("__") == std::string_view::npos && n.back() != '_';
}
bool valid_constant_name(std::string_view n) {
  return !n.empty() && std::isupper(static_cast<unsigned char>(n.front())) != 0 && all_of(n, upper_or_digit);
}
bool valid_package_name(std::string_view n) {
  return !n.empty() && std::islower(static_cast<unsigned char>(n.front())) != 0 && all_of(n, lower_or_digit);
}
bool valid_type_name(std::string_view n) {
  return !n.empty() && std::isupper(static_cast<unsigned char>(n.front())) != 0 && all_of(n, alnum);
}

bool parse_u32(std::string_view s, std::uint32_t* out) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return !s.empty() && ec == std::errc() && end == s.data() + s.size();
}

class LineParser {
 public:
  LineParser(const MsgSpec& spec, int line) : spec_(spec), line_(line) {}

  Error error(std::string_view what) const {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}:{}: {}", spec_.file, line_, what));
  }

  // Fills everything but the name from a type token such as "string<=8[]" or "pkg/Type[3]".
  Expected<MsgField> parse_type(std::string_view token) const {
    MsgField field;
    field.line = line_;
    std::string_view base = token;
    if (const auto open = token.find('['); open != std::string_view::npos) {
      if (token.back() != ']') return error(fmt::format("malformed array type '{}'", token));
      base = token.substr(0, open);
      const std::string_view inside = token.substr(open + 1, token.size() - open - 2);
      if (inside.empty()) {
        field.container = Container::kSequence;
      } else if (inside.starts_with("<=")) {
        field.container = Container::kBoundedSequence;
        if (!parse_u32(inside.substr(2), &field.bound) || field.bound == 0) {
          return error(fmt::format("bad sequence bound in '{}'", token));
        }
      } else {
        field.container = Container::kArray;
        if (!parse_u32(inside, &field.bound) || field.bound == 0)
          return error(fmt::format("bad array size in '{}'", token));
      }
    }
    if (const auto le = base.find("<="); le != std::string_view::npos) {
      const std::string_view str = base.substr(0, le);
      if (str != "string" && str != "wstring")
        return error(fmt::format("only strings take a bound, not '{}'", base));
      if (!parse_u32(base.substr(le + 2), &field.string_bound) || field.string_bound == 0) {
        return error(fmt::format("bad string bound in '{}'", base));
      }
      base = str;
    }
    if (is_primitive(base)) {
      field.element_type = std::string(base);
      return field;
    }
    const auto slash = base.find('/');
    const std::string_view pkg =
        slash == std::string_view::npos ? std::string_view(spec_.package) : base.substr(0, slash);
    const std::string_view type = slash == std::string_view::npos ? base : base.substr(slash + 1);
    if (!valid_package_name(pkg) || !valid_type_name(type)) {
      return error(fmt::format("'{}' is neither a primitive type nor a message type (pkg/Type)", base));
    }
    field.element_type = fmt::format("{}/{}", pkg, type);
    return field;
  }

 private:
  const MsgSpec& spec_;
  int line_;
};

}  // namespace

std::string canonical_type(const MsgField& field) {
  std::string out = field.element_type;
  if (field.string_bound != 0) out += fmt::format("<={}", field.string_bound);
  switch (field.container) {
    case Container::kNone:
      break;
    case Container::kSequence:
      out += "[]";
      break;
    case Container::kBoundedSequence:
      out += fmt::format("[<={}]", field.bound);
      break;
    case Container::kArray:
      out += fmt::format("[{}]", field.bound);
      break;
  }
  return out;
}

Expected<MsgSpec> parse_msg(std::string_view text, std::string package, std::string name, std::string file) {
  MsgSpec spec{std::move(package), std::move(name), std::move(file), {}, {}};
  int line_no = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    const std::string_view line = trim(strip_comment(text.substr(pos, end - pos)));
    pos = end + 1;
    ++line_no;
    if (line.empty()) continue;
    const LineParser parser(spec, line_no);

    const auto type_end = std::find_if(
        line.begin(), line.end(), [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; });
    const std::string_view type_token = line.substr(0, static_cast<std::size_t>(type_end - line.begin()));
    const std::string_view rest = trim(line.substr(type_token.size()));
    const auto name_end =
        std::find_if(rest.begin(), rest.end(), [](char c) { return !alnum(c) && c != '_'; });
    const std::string_view field_name = rest.substr(0, static_cast<std::size_t>(name_end - rest.begin()));
    const std::string_view after = trim(rest.substr(field_name.size()));
    if (field_name.empty()) return parser.error(fmt::format("expected a field name after '{}'", type_token));

    auto field = parser.parse_type(type_token);
    if (!field) return std::move(field).error();
    if (after.starts_with("=")) {
      // A constant: part of the generated code, not of the wire layout.
      if (!valid_constant_name(field_name)) {
        return parser.error(fmt::format("constant '{}' must be UPPER_CASE", field_name));
      }
      const std::string_view value = trim(after.substr(1));
      if (value.empty()) return parser.error(fmt::format("constant '{}' has no value", field_name));
      if (!is_primitive(type_token)) {
        return parser.error(
            fmt::format("constant '{}': its type '{}' must be a primitive type without "
                        "bound or array",
                        field_name, type_token));
      }
      MsgConstant constant{std::string(type_token), std::string(field_name), {}, line_no};
      if (const std::string problem = normalise_constant_value(type_token, value, constant.value);
          !problem.empty()) {
        return parser.error(fmt::format("constant '{}' = {}: {}", field_name, value, problem));
      }
      const auto same = std::find_if(spec.constants.begin(), spec.constants.end(),
                                     [&](const MsgConstant& c) { return c.name == field_name; });
      if (same != spec.constants.end()) {
        return parser.error(fmt::format("constant '{}' already declared on line {}", field_name, same->line));
      }
      spec.constants.push_back(std::move(constant));
      continue;
    }
    if (!valid_field_name(field_name)) {
      return parser.error(
          fmt::format("field name '{}' is not a valid ROS 2 name (lower_case, letters, digits, "
                      "single underscores)",
                      field_name));
    }
    const auto duplicate = std::find_if(spec.fields.begin(), spec.fields.end(),
                                        [&](const MsgField& f) { return f.name == field_name; });
    if (duplicate != spec.fields.end()) {
      return parser.error(fmt::format("field '{}' already declared on line {}", field_name, duplicate->line));
    }
    field->name = std::string(field_name);
    field->default_value = std::string(after);
    spec.fields.push_back(std::move(*field));
  }
  return spec;
}

Expected<std::vector<MsgSpec>> load_msg_packages(const std::filesystem::path& root) {
  std::error_code ec;
  if (!std::filesystem::is_directory(root, ec)) {
    return make_error(ErrorCode::kNotFound, fmt::format("{}: no such directory", root.string()));
  }
  std::vector<std::filesystem::path> files;
  for (const auto& pkg : std::filesystem::directory_iterator(root, ec)) {
    const auto msg_dir = pkg.path() / "msg";
    if (!std::filesystem::is_directory(msg_dir, ec)) continue;
    for (const auto& entry : std::filesystem::directory_iterator(msg_dir, ec)) {
      if (entry.path().extension() == ".msg") files.push_back(entry.path());
    }
  }
  if (ec) return make_error(ErrorCode::kIo, fmt::format("{}: {}", root.string(), ec.message()));
  std::sort(files.begin(), files.end());
  std::vector<MsgSpec> specs;
  for (const auto& path : files) {
    std::ifstream in(path, std::ios::binary);
    if (!in.is_open()) return make_error(ErrorCode::kIo, fmt::format("{}: cannot open", path.string()));
    std::ostringstream text;
    text << in.rdbuf();
    auto spec = parse_msg(text.str(), path.parent_path().parent_path().filename().string(),
                          path.stem().string(), path.string());
    if (!spec) return std::move(spec).error();
    specs.push_back(std::move(*spec));
  }
  return specs;
}

}  // namespace hubrt::msgs::ros
