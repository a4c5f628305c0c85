#include "hubrt/base/utf8.h"

#include <cstdint>

namespace hubrt {
namespace {

// RFC 3629 section 4 (the UTF8-octets ABNF): after the lead byte, the second byte's range
// depends on the lead (this is what excludes overlongs, surrogates and code points above
// U+10FFFF); every further byte is a plain continuation byte 80..BF.
struct LeadRule {
  std::size_t length = 0;  // 0: this byte cannot start a sequence
  std::uint8_t second_min = 0x80;
  std::uint8_t second_max = 0xBF;
};

constexpr LeadRule rule_for(std::uint8_t lead) noexcept {
  if (lead <= 0x7F) return {1, 0, 0};
  if (lead >= 0xC2 && lead <= 0xDF) return {2, 0x80, 0xBF};  // C0, C1: overlong 2-byte forms
  if (lead == 0xE0) return {3, 0xA0, 0xBF};                  // E0 80..9F: overlong 3-byte forms
  if (lead == 0xED) return {3, 0x80, 0x9F};                  // ED A0..BF: surrogates
  if (lead >= 0xE1 && lead <= 0xEF) return {3, 0x80, 0xBF};
  if (lead == 0xF0) return {4, 0x90, 0xBF};  // F0 80..8F: overlong 4-byte forms
  if (lead == 0xF4) return {4, 0x80, 0x8F};  // F4 90..BF: above U+10FFFF
  if (lead >= 0xF1 && lead <= 0xF3) return {4, 0x80, 0xBF};
  return {};  // 80..BF (lone continuation), C0, C1, F5..FF
}

constexpr bool in(std::uint8_t byte, std::uint8_t min, std::uint8_t max) noexcept {
  return byte >= min && byte <= max;
}

}  // namespace

std::size_t valid_utf8_prefix(std::string_view text) noexcept {
  std::size_t at = 0;
  while (at < text.size()) {
    const auto lead = static_cast<std::uint8_t>(text[at]);
    const LeadRule rule = rule_for(lead);
    if (rule.length == 0 || text.size() - at < rule.length) return at;
    for (std::size_t i = 1; i < rule.length; ++i) {
      const auto byte = static_cast<std::uint8_t>(text[at + i]);
      const bool ok = i == 1 ? in(byte, rule.second_min, rule.second_max) : in(byte, 0x80, 0xBF);
      if (!ok) return at;
    }
    at += rule.length;
  }
  return at;
}

}  // namespace hubrt
