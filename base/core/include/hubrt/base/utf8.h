// Strict UTF-8 (RFC 3629): what every text that comes from outside — a command string, a
// configuration file — must be before it is used or shown, and an escaped rendering of text that
// is not, so that an error message quoting hostile bytes is itself valid UTF-8 (a ROS 2 client or
// nlohmann::json rejects a message that is not).
#pragma once

#include <cstddef>
#include <span>
#include <string_view>

namespace hubrt {

// True when `text` is well-formed UTF-8 per RFC 3629 §4 (the Unicode "Well-Formed Byte
// Sequences" table): no overlong forms (C0, C1, E0 80..9F, F0 80..8F), no encoded surrogates
// (ED A0..BF = U+D800..U+DFFF), nothing above U+10FFFF (F4 90.., F5..FF), no stray continuation
// byte, no truncated sequence. NUL and control characters are valid UTF-8: callers that refuse
// them check for them themselves. Allocation-free; thread-safe.
bool is_valid_utf8(std::string_view text) noexcept;

// Length of the longest prefix of `text` that is valid UTF-8: text.size() when all of it is,
// else the offset of the first byte of the first invalid (or truncated) sequence (configuration
// files report where the bad text starts). Never allocates; thread-safe.
[[nodiscard]] std::size_t valid_utf8_prefix(std::string_view text) noexcept;

// Length in bytes (1..4) of the well-formed UTF-8 sequence at the start of `text`, or 0 when
// `text` is empty or does not start with one. Allocation-free; thread-safe.
std::size_t utf8_sequence_length(std::string_view text) noexcept;

struct EscapedUtf8 {
  std::size_t written = 0;  // bytes written to the output
  bool complete = false;    // false: the output was too small and the text was cut
};

// Writes `text` to `out`, escaped so that the result is valid UTF-8 free of control characters
// and says exactly which bytes `text` held:
//   - a byte that does not start a well-formed sequence, and every control character
//     (U+0000..U+001F, U+007F), as `\xHH` (two upper-case hex digits), e.g. "\xED\xA0\x80";
//   - a backslash as `\\`, so that an escape can never be mistaken for text;
//   - every other well-formed character as it is.
// Never cuts a character or an escape in two: when the next one does not fit, it stops there
// and reports `complete = false` (callers typically append "..."). Writes no terminating NUL.
// Allocation-free (the cycle formats error messages with it); thread-safe.
EscapedUtf8 append_escaped_utf8(std::string_view text, std::span<char> out) noexcept;

}  // namespace hubrt
