#include "document_checks.h"

#include <map>

#include <fmt/format.h>

#include "hubrt/base/utf8.h"

namespace hubrt::config::detail {
namespace {

bool is_continuation_byte(char c) noexcept {
  return (static_cast<unsigned char>(c) & 0xC0U) == 0x80U;
}

Expected<void> check_node(const YAML::Node& node, const std::string& name, const std::string& path) {
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      if (auto checked = check_node(node[i], name, fmt::format("{}[{}]", path, i)); !checked) return checked;
    }
    return {};
  }
  if (!node.IsMap()) return {};
  std::map<std::string, YAML::Mark> seen;
  for (const auto& item : node) {
    // Scalar() is "" for a key that is itself a list or mapping; such keys are refused later, by
    // the reader of the section, with a message that says so.
    const std::string& key = item.first.Scalar();
    const std::string key_path = path.empty() ? key : fmt::format("{}.{}", path, key);
    const YAML::Mark mark = item.first.Mark();
    const auto [first, inserted] = seen.emplace(key, mark);
    if (!inserted) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}:{}:{}: {}: declared twice (first at line {})", name, mark.line + 1,
                                    mark.column + 1, key_path, first->second.line + 1));
    }
    if (auto checked = check_node(item.second, name, key_path); !checked) return checked;
  }
  return {};
}

}  // namespace

Expected<void> check_utf8(std::string_view text, const std::string& name) {
  const std::size_t bad = valid_utf8_prefix(text);
  if (bad == text.size()) return {};
  const std::size_t newline = bad == 0 ? std::string_view::npos : text.rfind('\n', bad - 1);
  const std::size_t from = newline == std::string_view::npos ? 0 : newline + 1;
  std::size_t line = 1;
  for (std::size_t i = 0; i < from; ++i) line += text[i] == '\n' ? 1 : 0;
  std::size_t column = 1;
  for (std::size_t i = from; i < bad; ++i) column += is_continuation_byte(text[i]) ? 0 : 1;
  return make_error(ErrorCode::kInvalidArgument,
                    fmt::format("{}:{}:{}: not valid UTF-8 (byte 0x{:02X}): configuration files are UTF-8 "
                                "text (RFC 3629)",
                                name, line, column, static_cast<unsigned char>(text[bad])));
}

Expected<void> check_unique_keys(const YAML::Node& root, const std::string& name) {
  return check_node(root, name, "");
}

}  // namespace hubrt::config::detail
