#include "board_parse.h"

#include <algorithm>
#include <map>

#include <fmt/format.h>

namespace hubrt::hal::board_detail {
namespace {

bool lower_or_digit(char c) noexcept {
  return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
}

Expected<void> check_node(const YAML::Node& node, const std::string& file, const std::string& path) {
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      auto checked = check_node(node[i], file, fmt::format("{}[{}]", path, i));
      if (!checked) return checked;
    }
    return {};
  }
  if (!node.IsMap()) return {};
  std::map<std::string, YAML::Mark> seen;
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();
    const std::string key_path = path.empty() ? key : fmt::format("{}.{}", path, key);
    const YAML::Mark mark = item.first.Mark();
    const auto [first, inserted] = seen.emplace(key, mark);
    if (!inserted) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}:{}:{}: {}: declared twice (first at line {})", file, mark.line + 1,
                                    mark.column + 1, key_path, first->second.line + 1));
    }
    auto checked = check_node(item.second, file, key_path);
    if (!checked) return checked;
  }
  return {};
}

}  // namespace

SourceLocation where(const YAML::Mark& mark) {
  if (mark.is_null()) return {};
  return SourceLocation{mark.line + 1, mark.column + 1};
}

SourceLocation where(const YamlMap& map) {
  return where(map.node().Mark());
}

bool valid_signal_name(std::string_view name) noexcept {
  if (name.empty() || name.front() < 'a' || name.front() > 'z' || name.back() == '.') return false;
  char previous = ' ';
  for (const char c : name) {
    if (c == '.' && previous == '.') return false;
    if (c != '.' && c != '_' && !lower_or_digit(c)) return false;
    previous = c;
  }
  return true;
}

bool valid_identifier(std::string_view name) noexcept {
  if (name.empty() || name.front() < 'a' || name.front() > 'z') return false;
  return std::all_of(name.begin(), name.end(),
                     [](char c) { return lower_or_digit(c) || c == '_' || c == '-'; });
}

std::string declared_at(std::string_view what, std::string_view name, SourceLocation where) {
  return fmt::format("{} '{}' (line {})", what, name, where.line);
}

Expected<void> check_no_duplicate_keys(const YamlMap& root) {
  return check_node(root.node(), root.file(), "");
}

}  // namespace hubrt::hal::board_detail
