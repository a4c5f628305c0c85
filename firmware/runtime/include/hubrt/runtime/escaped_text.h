// Text from outside (a command string) quoted in an error message that goes on the wire: bytes
// that are not valid UTF-8, control characters and backslashes escaped (hubrt/base/utf8.h), so
// the message stays valid UTF-8 whatever a peer sent, and bounded in length.
#pragma once

#include <algorithm>
#include <array>
#include <string_view>

#include <fmt/format.h>

#include "hubrt/base/utf8.h"

namespace hubrt::runtime {

// Use as a format argument: problem.format("unknown action '{}'", Escaped{action}).
struct Escaped {
  // Longest escaped rendering, in bytes; longer text is cut (at a character) and ends in "...".
  static constexpr std::size_t kMaxBytes = 64;
  std::string_view text;
};

}  // namespace hubrt::runtime

// Allocation-free: escapes into a stack buffer, then copies to fmt's output iterator.
template <>
struct fmt::formatter<hubrt::runtime::Escaped> {
  constexpr auto parse(fmt::format_parse_context& ctx) { return ctx.begin(); }
  template <class FormatContext>
  auto format(const hubrt::runtime::Escaped& value, FormatContext& ctx) const {
    std::array<char, hubrt::runtime::Escaped::kMaxBytes> buffer{};
    const hubrt::EscapedUtf8 escaped = hubrt::append_escaped_utf8(value.text, buffer);
    auto out = std::copy_n(buffer.data(), escaped.written, ctx.out());
    if (!escaped.complete) out = std::copy_n("...", 3, out);
    return out;
  }
};
