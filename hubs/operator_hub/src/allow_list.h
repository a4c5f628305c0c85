// The operator allow-list: who may be verified by a badge. Badge IDs are never stored: each
// operator's line holds SHA-256(salt || badge ID) in hex, with one random salt per file, so the
// file (and a copy of it) does not give the badges away to someone reading it. Enrolling a badge
// is `operator-enrol add <file> <name>` (README.md), which reads the badge from the reader's
// keystrokes or stdin and never takes it as an argument.
//
// Format, one item per line ('#' starts a comment line; blank lines are ignored):
//   salt <32 hex digits>                  exactly once, before the operators
//   <64 hex digits> <name>                one operator: the badge's hash, then the name
// Names are 1 to 64 bytes of printable UTF-8 (no control characters), unique; hashes unique.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"

#include "badge_hash.h"

namespace hubrt::operator_hub {

struct AllowedOperator {
  BadgeDigest digest{};
  std::string name;
  int line = 0;
};

class AllowList {
 public:
  static constexpr std::size_t kMaxNameBytes = 64;
  static constexpr std::size_t kMaxOperators = 1000;
  static constexpr std::size_t kMaxFileBytes = std::size_t{256} * 1024;

  // Reads and checks the file. Errors (kNotFound, kPermissionDenied, kInvalidArgument) name
  // "<file>:<line>: what is wrong", e.g. "ops.list:4: not a SHA-256 hash in hex (64 digits)".
  static Expected<AllowList> load(const std::string& path);
  // The same for text already read; `file` names it in errors.
  static Expected<AllowList> parse(std::string_view text, const std::string& file);

  [[nodiscard]] const BadgeSalt& salt() const noexcept { return salt_; }
  [[nodiscard]] const std::vector<AllowedOperator>& operators() const noexcept { return operators_; }
  [[nodiscard]] const std::string& file() const noexcept { return file_; }

  // The operator whose hash is `digest`, or nullptr. Compares every entry in constant time.
  // Never allocates.
  [[nodiscard]] const AllowedOperator* find(const BadgeDigest& digest) const noexcept;

 private:
  std::string file_;
  BadgeSalt salt_{};
  std::vector<AllowedOperator> operators_;
};

// One line of the file for a new operator ("<hash> <name>\n"). Errors: a name the file refuses.
Expected<std::string> allow_list_line(const BadgeDigest& digest, std::string_view name);
// Why `name` is not allowed; empty when it is.
std::string_view name_problem(std::string_view name) noexcept;

}  // namespace hubrt::operator_hub
