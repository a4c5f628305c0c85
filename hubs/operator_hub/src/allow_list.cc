#include "allow_list.h"

#include <cerrno>
#include <fstream>
#include <optional>
#include <sstream>
#include <system_error>

#include <fmt/format.h>

#include "hubrt/base/utf8.h"
#include "hubrt/config/config_file.h"

namespace hubrt::operator_hub {
namespace {

std::string_view trim(std::string_view text) noexcept {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r'))
    text.remove_suffix(1);
  return text;
}

Error at(const std::string& file, int line, std::string_view what) {
  return make_error(ErrorCode::kInvalidArgument, fmt::format("{}:{}: {}", file, line, what));
}

}  // namespace

std::string_view name_problem(std::string_view name) noexcept {
  if (name.empty()) return "an operator needs a name";
  if (name.size() > AllowList::kMaxNameBytes) return "a name is at most 64 bytes";
  if (!is_valid_utf8(name)) return "a name must be valid UTF-8";
  for (char c : name) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7F) return "a name must not hold control characters";
  }
  return {};
}

Expected<AllowList> AllowList::parse(std::string_view text, const std::string& file) {
  AllowList list;
  list.file_ = file;
  bool have_salt = false;
  int line_number = 0;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
    ++line_number;
    line = trim(line);
    if (line.empty() || line.front() == '#') continue;
    if (!is_valid_utf8(line)) return at(file, line_number, "not valid UTF-8");
    const std::size_t space = line.find_first_of(" \t");
    const std::string_view first = line.substr(0, space);
    const std::string_view rest =
        space == std::string_view::npos ? std::string_view{} : trim(line.substr(space));
    if (first == "salt") {
      if (have_salt) return at(file, line_number, "a second salt line (the file has one salt)");
      if (!list.operators_.empty()) return at(file, line_number, "the salt comes before the operators");
      if (!from_hex(rest, list.salt_)) return at(file, line_number, "the salt is 32 hex digits (16 bytes)");
      have_salt = true;
      continue;
    }
    if (!have_salt) return at(file, line_number, "the file starts with its salt line: salt <32 hex digits>");
    AllowedOperator entry;
    if (!from_hex(first, entry.digest)) {
      return at(file, line_number,
                "expected '<SHA-256 in hex (64 digits)> <name>' (enrol badges with operator-enrol add)");
    }
    if (const std::string_view problem = name_problem(rest); !problem.empty()) {
      return at(file, line_number, problem);
    }
    for (const AllowedOperator& other : list.operators_) {
      if (other.name == rest) {
        return at(file, line_number, fmt::format("operator '{}' is already on line {}", rest, other.line));
      }
      if (same_digest(other.digest, entry.digest)) {
        return at(file, line_number, fmt::format("the same badge is already on line {}", other.line));
      }
    }
    if (list.operators_.size() >= kMaxOperators) {
      return at(file, line_number, fmt::format("more than {} operators", kMaxOperators));
    }
    entry.name = std::string(rest);
    entry.line = line_number;
    list.operators_.push_back(std::move(entry));
  }
  if (!have_salt) return at(file, 1, "no salt line: the file starts with salt <32 hex digits>");
  return list;
}

Expected<AllowList> AllowList::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno;
    return make_error(err == EACCES ? ErrorCode::kPermissionDenied : ErrorCode::kNotFound,
                      fmt::format("{}: cannot read the operator allow-list: {}", path,
                                  std::generic_category().message(err)));
  }
  // Read as it comes rather than into a buffer of kMaxFileBytes made first (config_file.h).
  const std::optional<std::string> text = config::read_at_most(in, kMaxFileBytes);
  if (!text) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: larger than {} bytes: not an allow-list", path, kMaxFileBytes));
  }
  return parse(*text, path);
}

const AllowedOperator* AllowList::find(const BadgeDigest& digest) const noexcept {
  const AllowedOperator* found = nullptr;
  for (const AllowedOperator& entry : operators_) {
    if (same_digest(entry.digest, digest)) found = &entry;
  }
  return found;
}

Expected<std::string> allow_list_line(const BadgeDigest& digest, std::string_view name) {
  if (const std::string_view problem = name_problem(name); !problem.empty()) {
    return make_error(ErrorCode::kInvalidArgument, std::string(problem));
  }
  std::array<char, 64> hex{};
  to_hex(digest, hex);
  return fmt::format("{} {}\n", std::string_view(hex.data(), hex.size()), name);
}

}  // namespace hubrt::operator_hub
