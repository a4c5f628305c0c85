#include "hubrt/config/yaml_map.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <fstream>
#include <system_error>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hubrt/config/config_file.h"

#include "document_checks.h"

namespace hubrt::config {
namespace {

std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return fmt::format("'{}'", node.Scalar());
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Map:
      return "a mapping";
    case YAML::NodeType::Null:
      return "nothing";
    case YAML::NodeType::Undefined:
      break;
  }
  return "nothing";
}

std::string join_choices(std::initializer_list<std::string_view> choices) {
  return fmt::format("{}", fmt::join(choices, ", "));
}

// Nodes a document may have, aliases counted each time they are used: far above any real file,
// low enough that a few nested aliases (each repeating the one before) cannot make the readers
// walk billions of nodes.
constexpr std::size_t kMaxNodes = 100'000;
// Board, hub, station and scenario files are a few kB; a file far larger is not one of them
// (or a link to a device that never ends), and reading it whole would cost memory for nothing.
constexpr std::size_t kMaxFileBytes = std::size_t{1} << 20;

// Every mapping key in the document is a scalar. The readers take keys as names
// (Node::as<std::string>(), which throws YAML::TypedBadConversion for a mapping or list used as a
// key, e.g. "? {a: 1}\n: x"), so such a document is refused here, with where the key is.
// Iterative: nesting depth costs no stack.
Expected<void> check_keys(const YAML::Node& root, const std::string& name) {
  std::vector<YAML::Node> pending{root};
  std::size_t seen = 0;
  while (!pending.empty()) {
    const YAML::Node node = pending.back();
    pending.pop_back();
    if (++seen > kMaxNodes) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: more than {} YAML nodes (aliases count each time they are used)",
                                    name, kMaxNodes));
    }
    if (node.IsMap()) {
      for (const auto& item : node) {
        if (!item.first.IsScalar()) {
          const YAML::Mark mark = item.first.Mark();
          return make_error(ErrorCode::kInvalidArgument,
                            fmt::format("{}:{}:{}: a key must be a plain name, not {}", name, mark.line + 1,
                                        mark.column + 1, describe(item.first)));
        }
        pending.push_back(item.second);
      }
    } else if (node.IsSequence()) {
      for (const auto& item : node) pending.push_back(item);
    }
  }
  return {};
}

}  // namespace

YamlMap::YamlMap(std::shared_ptr<const std::string> file, const YAML::Node& node, std::string path)
    : file_(std::move(file)), node_(node), path_(std::move(path)) {}

Expected<YamlMap> YamlMap::load_string(const std::string& text, const std::string& name) {
  if (auto utf8 = detail::check_utf8(text, name); !utf8) return std::move(utf8).error();
  auto file = std::make_shared<const std::string>(name);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}:{}:{}: YAML syntax error: {}", name,
                                                               e.mark.line + 1, e.mark.column + 1, e.msg));
  }
  if (!root.IsMap()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: expected a mapping at the top level, got {}", name, describe(root)));
  }
  if (auto keys = check_keys(root, name); !keys) return std::move(keys).error();
  if (auto unique = detail::check_unique_keys(root, name); !unique) return std::move(unique).error();
  return YamlMap(file, root, "");
}

Expected<YamlMap> YamlMap::load_file(const std::string& path) {
  // Before opening: std::ifstream opens a directory without complaint (and reads nothing), and
  // a symbolic link loop would otherwise read as a file that cannot be opened.
  if (auto regular = require_regular_file(path); !regular) return std::move(regular).error();
  std::ifstream in(path);
  if (!in) {
    const int err = errno;
    return make_error(err == ENOENT ? ErrorCode::kNotFound : ErrorCode::kIo,
                      fmt::format("{}: cannot open: {}", path, std::generic_category().message(err)));
  }
  const std::optional<std::string> text = read_at_most(in, kMaxFileBytes);
  if (!text) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: larger than {} bytes: not a configuration file", path, kMaxFileBytes));
  }
  return load_string(*text, path);
}

bool YamlMap::has(std::string_view key) const {
  const YAML::Node value = node_[std::string(key)];
  return value.IsDefined() && !value.IsNull();
}

std::vector<std::string> YamlMap::keys() const {
  std::vector<std::string> out;
  for (const auto& item : node_) out.push_back(item.first.as<std::string>());
  return out;
}

std::string YamlMap::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key);
}

Error YamlMap::located(const YAML::Mark& mark, std::string_view what, std::string_view message) const {
  const std::string where =
      mark.is_null() ? *file_ : fmt::format("{}:{}:{}", *file_, mark.line + 1, mark.column + 1);
  if (what.empty()) return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: {}", where, message));
  return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: {}: {}", where, what, message));
}

Error YamlMap::error(std::string_view message) const {
  return located(node_.Mark(), path_, message);
}

Error YamlMap::error_at(std::string_view key, std::string_view message) const {
  const YAML::Node value = node_[std::string(key)];
  const YAML::Mark mark = value.IsDefined() ? value.Mark() : node_.Mark();
  return located(mark, key_path(key), message);
}

Expected<void> YamlMap::only_keys(std::initializer_list<std::string_view> allowed) const {
  for (const auto& item : node_) {
    const auto key = item.first.as<std::string>();
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      return located(item.first.Mark(), key_path(key),
                     fmt::format("unknown key (expected one of: {})", join_choices(allowed)));
    }
  }
  return {};
}

Expected<YAML::Node> YamlMap::scalar(std::string_view key) const {
  const YAML::Node value = node_[std::string(key)];
  if (!value.IsDefined() || value.IsNull()) return error(fmt::format("missing required key '{}'", key));
  if (!value.IsScalar())
    return error_at(key, fmt::format("expected a single value, got {}", describe(value)));
  return value;
}

Expected<std::string> YamlMap::string(std::string_view key) const {
  auto value = scalar(key);
  if (!value) return std::move(value).error();
  if (value->Scalar().empty()) return error_at(key, "must not be empty");
  return value->Scalar();
}

Expected<std::string> YamlMap::string_or(std::string_view key, std::string fallback) const {
  return has(key) ? string(key) : Expected<std::string>(std::move(fallback));
}

Expected<std::int64_t> YamlMap::integer(std::string_view key, std::int64_t min, std::int64_t max) const {
  auto value = scalar(key);
  if (!value) return std::move(value).error();
  const std::string& text = value->Scalar();
  std::int64_t parsed = 0;
  std::size_t used = 0;
  bool ok = !text.empty();
  if (ok) {
    try {
      parsed = std::stoll(text, &used, 0);
    } catch (const std::exception&) {
      ok = false;
    }
  }
  if (!ok || used != text.size()) {
    return error_at(key, fmt::format("expected an integer in [{}, {}], got '{}'", min, max, text));
  }
  if (parsed < min || parsed > max) {
    return error_at(key, fmt::format("{} is out of range [{}, {}]", parsed, min, max));
  }
  return parsed;
}

Expected<std::int64_t> YamlMap::integer_or(std::string_view key, std::int64_t fallback, std::int64_t min,
                                           std::int64_t max) const {
  return has(key) ? integer(key, min, max) : Expected<std::int64_t>(fallback);
}

Expected<double> YamlMap::number(std::string_view key, double min, double max) const {
  auto value = scalar(key);
  if (!value) return std::move(value).error();
  const std::string& text = value->Scalar();
  double parsed = 0;
  std::size_t used = 0;
  bool ok = !text.empty();
  if (ok) {
    try {
      parsed = std::stod(text, &used);
    } catch (const std::exception&) {
      ok = false;
    }
  }
  if (!ok || used != text.size() || !std::isfinite(parsed)) {
    return error_at(key, fmt::format("expected a number in [{}, {}], got '{}'", min, max, text));
  }
  if (parsed < min || parsed > max)
    return error_at(key, fmt::format("{} is out of range [{}, {}]", parsed, min, max));
  return parsed;
}

Expected<double> YamlMap::number_or(std::string_view key, double fallback, double min, double max) const {
  return has(key) ? number(key, min, max) : Expected<double>(fallback);
}

Expected<bool> YamlMap::boolean(std::string_view key) const {
  auto value = scalar(key);
  if (!value) return std::move(value).error();
  bool parsed = false;
  if (!YAML::convert<bool>::decode(*value, parsed)) {
    return error_at(key, fmt::format("expected true or false, got '{}'", value->Scalar()));
  }
  return parsed;
}

Expected<bool> YamlMap::boolean_or(std::string_view key, bool fallback) const {
  return has(key) ? boolean(key) : Expected<bool>(fallback);
}

Expected<std::string> YamlMap::choice(std::string_view key,
                                      std::initializer_list<std::string_view> choices) const {
  auto value = string(key);
  if (!value) return value;
  if (std::find(choices.begin(), choices.end(), *value) == choices.end()) {
    return error_at(key, fmt::format("'{}' is not one of: {}", *value, join_choices(choices)));
  }
  return value;
}

Expected<std::string> YamlMap::choice_or(std::string_view key, std::string fallback,
                                         std::initializer_list<std::string_view> choices) const {
  return has(key) ? choice(key, choices) : Expected<std::string>(std::move(fallback));
}

Expected<YamlMap> YamlMap::map(std::string_view key) const {
  const YAML::Node value = node_[std::string(key)];
  if (!value.IsDefined() || value.IsNull()) return error(fmt::format("missing required key '{}'", key));
  if (!value.IsMap()) return error_at(key, fmt::format("expected a mapping, got {}", describe(value)));
  return YamlMap(file_, value, key_path(key));
}

Expected<std::vector<std::pair<std::string, YamlMap>>> YamlMap::named_maps(std::string_view key) const {
  auto parent = map(key);
  if (!parent) return std::move(parent).error();
  std::vector<std::pair<std::string, YamlMap>> out;
  for (const auto& item : parent->node_) {
    const auto name = item.first.as<std::string>();
    const std::string path = parent->key_path(name);
    if (!item.second.IsMap()) {
      return located(item.second.Mark(), path,
                     fmt::format("expected a mapping, got {}", describe(item.second)));
    }
    out.emplace_back(name, YamlMap(file_, item.second, path));
  }
  return out;
}

Expected<std::vector<YamlMap>> YamlMap::list_of_maps(std::string_view key, bool optional) const {
  const YAML::Node value = node_[std::string(key)];
  std::vector<YamlMap> out;
  if (!value.IsDefined() || value.IsNull()) {
    if (optional) return out;
    return error(fmt::format("missing required key '{}'", key));
  }
  if (!value.IsSequence()) return error_at(key, fmt::format("expected a list, got {}", describe(value)));
  for (std::size_t i = 0; i < value.size(); ++i) {
    const std::string path = fmt::format("{}[{}]", key_path(key), i);
    if (!value[i].IsMap()) {
      return located(value[i].Mark(), path, fmt::format("expected a mapping, got {}", describe(value[i])));
    }
    out.push_back(YamlMap(file_, value[i], path));
  }
  return out;
}

Expected<std::vector<std::string>> YamlMap::list_of_strings(std::string_view key, bool optional) const {
  const YAML::Node value = node_[std::string(key)];
  std::vector<std::string> out;
  if (!value.IsDefined() || value.IsNull()) {
    if (optional) return out;
    return error(fmt::format("missing required key '{}'", key));
  }
  if (!value.IsSequence()) return error_at(key, fmt::format("expected a list, got {}", describe(value)));
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (!value[i].IsScalar() || value[i].Scalar().empty()) {
      return located(value[i].Mark(), fmt::format("{}[{}]", key_path(key), i),
                     fmt::format("expected a non-empty string, got {}", describe(value[i])));
    }
    out.push_back(value[i].Scalar());
  }
  return out;
}

}  // namespace hubrt::config
