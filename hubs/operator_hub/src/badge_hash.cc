// The deprecated SHA256_* functions on purpose: see badge_hash.h.
#define OPENSSL_SUPPRESS_DEPRECATED
#include "badge_hash.h"

#include <openssl/evp.h>
#include <openssl/sha.h>

namespace hubrt::operator_hub {

Expected<BadgeHasher> BadgeHasher::create() {
  EVP_MD* md = EVP_MD_fetch(nullptr, "SHA256", nullptr);
  if (md == nullptr) {
    return make_error(ErrorCode::kInternal, "libcrypto has no SHA-256 digest (EVP_MD_fetch failed)");
  }
  EVP_MD_free(md);
  return BadgeHasher();
}

bool BadgeHasher::hash(const BadgeSalt& salt, std::string_view badge, BadgeDigest& out) const noexcept {
  SHA256_CTX ctx;
  return SHA256_Init(&ctx) == 1 && SHA256_Update(&ctx, salt.data(), salt.size()) == 1 &&
         SHA256_Update(&ctx, badge.data(), badge.size()) == 1 && SHA256_Final(out.data(), &ctx) == 1;
}

void to_hex(std::span<const std::uint8_t> bytes, std::span<char> out) noexcept {
  constexpr std::string_view kDigits = "0123456789abcdef";
  for (std::size_t i = 0; i < bytes.size() && 2 * i + 1 < out.size(); ++i) {
    out[2 * i] = kDigits[bytes[i] >> 4];
    out[2 * i + 1] = kDigits[bytes[i] & 0x0F];
  }
}

namespace {
int hex_value(char c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}
}  // namespace

bool from_hex(std::string_view text, std::span<std::uint8_t> out) noexcept {
  if (text.size() != 2 * out.size()) return false;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const int high = hex_value(text[2 * i]);
    const int low = hex_value(text[2 * i + 1]);
    if (high < 0 || low < 0) return false;
    out[i] = static_cast<std::uint8_t>(high * 16 + low);
  }
  return true;
}

bool same_digest(const BadgeDigest& a, const BadgeDigest& b) noexcept {
  std::uint8_t difference = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    difference = static_cast<std::uint8_t>(difference | (a[i] ^ b[i]));
  return difference == 0;
}

}  // namespace hubrt::operator_hub
