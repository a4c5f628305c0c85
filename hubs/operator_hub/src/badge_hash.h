// Salted SHA-256 of a badge ID through OpenSSL's libcrypto: the one way badges are compared and
// shown. create() checks once, through the EVP interface, that libcrypto has SHA-256; hash() then
// uses libcrypto's SHA256_Init/Update/Final on a context on the stack
// (https://www.openssl.org/docs/man3.0/man3/SHA256_Init.html). Why not EVP for every hash: OpenSSL
// 3.0's EVP_DigestInit_ex2 frees and makes the provider's context again on every init, one heap
// allocation per badge (measured here: allow_list_test, HashingAgainAllocatesNothing), and the
// cycle allocates nothing. Those functions are deprecated in 3.0 in favour of EVP but present and
// unchanged; badge_hash.cc alone uses them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "hubrt/base/status.h"

namespace hubrt::operator_hub {

using BadgeDigest = std::array<std::uint8_t, 32>;
using BadgeSalt = std::array<std::uint8_t, 16>;

class BadgeHasher {
 public:
  // Errors: kInternal when libcrypto has no SHA-256 (a broken installation).
  static Expected<BadgeHasher> create();

  // SHA-256(salt || badge). Never allocates. False only if libcrypto fails.
  bool hash(const BadgeSalt& salt, std::string_view badge, BadgeDigest& out) const noexcept;

 private:
  BadgeHasher() = default;
};

// Lower-case hex of `bytes` into `out` (2 characters per byte; `out` must have room).
void to_hex(std::span<const std::uint8_t> bytes, std::span<char> out) noexcept;
// Parses exactly 2 * out.size() hex digits. False for anything else.
bool from_hex(std::string_view text, std::span<std::uint8_t> out) noexcept;
// Constant-time comparison (the time does not tell how many bytes matched).
bool same_digest(const BadgeDigest& a, const BadgeDigest& b) noexcept;

}  // namespace hubrt::operator_hub
