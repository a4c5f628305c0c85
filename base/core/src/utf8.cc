#include "hubrt/base/utf8.h"

#include <array>
#include <cstdint>

namespace hubrt {
namespace {

// The second byte's range for each lead byte, from RFC 3629 §4 (the ABNF of UTF8-2..UTF8-4):
// E0 needs A0..BF (else overlong), ED needs 80..9F (else a surrogate), F0 needs 90..BF (else
// overlong), F4 needs 80..8F (else above U+10FFFF). Every other continuation byte is 80..BF.
struct LeadRule {
  std::size_t length;
  unsigned char second_min;
  unsigned char second_max;
};

LeadRule rule_for(unsigned char lead) noexcept {
  if (lead < 0x80) return {1, 0, 0};
  if (lead < 0xc2) return {0, 0, 0};  // continuation byte, or C0/C1 (overlong 2-byte forms)
  if (lead < 0xe0) return {2, 0x80, 0xbf};
  if (lead == 0xe0) return {3, 0xa0, 0xbf};
  if (lead == 0xed) return {3, 0x80, 0x9f};
  if (lead < 0xf0) return {3, 0x80, 0xbf};
  if (lead == 0xf0) return {4, 0x90, 0xbf};
  if (lead < 0xf4) return {4, 0x80, 0xbf};
  if (lead == 0xf4) return {4, 0x80, 0x8f};
  return {0, 0, 0};  // F5..FF: would encode beyond U+10FFFF
}

bool is_control(unsigned char c) noexcept {
  return c < 0x20 || c == 0x7f;
}

}  // namespace

std::size_t utf8_sequence_length(std::string_view text) noexcept {
  if (text.empty()) return 0;
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const LeadRule rule = rule_for(byte(0));
  if (rule.length <= 1) return rule.length;
  if (text.size() < rule.length) return 0;
  if (byte(1) < rule.second_min || byte(1) > rule.second_max) return 0;
  for (std::size_t i = 2; i < rule.length; ++i) {
    if ((byte(i) & 0xc0) != 0x80) return 0;
  }
  return rule.length;
}

std::size_t valid_utf8_prefix(std::string_view text) noexcept {
  std::size_t offset = 0;
  while (offset < text.size()) {
    const std::size_t n = utf8_sequence_length(text.substr(offset));
    if (n == 0) return offset;
    offset += n;
  }
  return offset;
}

bool is_valid_utf8(std::string_view text) noexcept {
  return valid_utf8_prefix(text) == text.size();
}

EscapedUtf8 append_escaped_utf8(std::string_view text, std::span<char> out) noexcept {
  static constexpr char kHex[] = "0123456789ABCDEF";
  EscapedUtf8 result;
  while (!text.empty()) {
    const auto first = static_cast<unsigned char>(text[0]);
    std::size_t n = utf8_sequence_length(text);
    std::array<char, 4> escape{};
    std::string_view piece;
    if (n == 1 && first == '\\') {
      piece = "\\\\";
    } else if (n == 0 || (n == 1 && is_control(first))) {
      escape = {'\\', 'x', kHex[first >> 4], kHex[first & 0x0f]};
      piece = std::string_view(escape.data(), escape.size());
      n = 1;
    } else {
      piece = text.substr(0, n);
    }
    if (out.size() - result.written < piece.size()) return result;
    piece.copy(out.data() + result.written, piece.size());
    result.written += piece.size();
    text.remove_prefix(n);
  }
  result.complete = true;
  return result;
}

}  // namespace hubrt
