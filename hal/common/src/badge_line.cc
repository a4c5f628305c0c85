#include "hubrt/hal/common/badge_line.h"

namespace hubrt::hal {

void BadgeLineAssembler::start(Time now) noexcept {
  if (started_) return;
  current_ = BadgeRead{};
  current_.at = now;
  started_ = true;
}

void BadgeLineAssembler::add(char c, Time now) noexcept {
  start(now);
  current_.at = now;
  const auto byte = static_cast<unsigned char>(c);
  if (byte < 0x20 || byte > 0x7E) {
    if (!current_.malformed) current_.problem = "not printable ASCII";
    current_.malformed = true;
    return;
  }
  if (current_.length >= BadgeRead::kMaxLength) {
    if (!current_.malformed) current_.problem = "too long";
    current_.malformed = true;
    return;
  }
  current_.chars[current_.length++] = c;
}

void BadgeLineAssembler::add_garbage(std::string_view problem, Time now) noexcept {
  start(now);
  current_.at = now;
  if (!current_.malformed) current_.problem = problem;
  current_.malformed = true;
}

void BadgeLineAssembler::finish(BadgeRead& out) noexcept {
  out = current_;
  if (!out.malformed && out.length == 0) {
    out.malformed = true;
    out.problem = "empty";
  }
  // A malformed read keeps no text: nobody needs it, and it may be half a real badge.
  if (out.malformed) {
    out.chars.fill('\0');
    out.length = 0;
  }
  started_ = false;
  current_ = BadgeRead{};
}

bool BadgeLineAssembler::end(BadgeRead& out, Time now) noexcept {
  if (!started_) return false;
  current_.at = now;
  finish(out);
  return true;
}

bool BadgeLineAssembler::expire(BadgeRead& out, Time now) noexcept {
  if (!started_ || now - current_.at <= timeout_) return false;
  if (!current_.malformed) current_.problem = "cut off (no end of badge within the timeout)";
  current_.malformed = true;
  finish(out);
  return true;
}

void BadgeLineAssembler::clear() noexcept {
  started_ = false;
  current_ = BadgeRead{};
}

}  // namespace hubrt::hal
