// Strict UTF-8 as RFC 3629 defines it: shortest form only (no overlongs such as C0 AF), no
// UTF-16 surrogates (U+D800..U+DFFF, e.g. ED A0 80), nothing above U+10FFFF (F4 90 80 80 and
// F5..FF), no truncated sequences and no lone continuation bytes. The one validator for every
// text hubrt reads from outside: configuration files and strings arriving over DDS.
#pragma once

#include <cstddef>
#include <string_view>

namespace hubrt {

// Length of the longest prefix of `text` that is valid UTF-8: text.size() when all of it is,
// else the offset of the first byte of the first invalid (or truncated) sequence.
// Never allocates; thread-safe.
[[nodiscard]] std::size_t valid_utf8_prefix(std::string_view text) noexcept;

// True when every byte of `text` belongs to a well-formed UTF-8 sequence (the empty string is).
[[nodiscard]] inline bool is_valid_utf8(std::string_view text) noexcept {
  return valid_utf8_prefix(text) == text.size();
}

}  // namespace hubrt
