#include "hubrt/dds/guid.h"

#include <cstring>

namespace hubrt::dds {

Guid Guid::from(const dds_guid_t& guid) noexcept {
  Guid out;
  static_assert(sizeof(guid.v) == sizeof(out.bytes));
  std::memcpy(out.bytes.data(), guid.v, sizeof(guid.v));
  return out;
}

std::string Guid::to_string() const {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string text;
  text.reserve(35);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    if (i > 0 && i % 4 == 0) text += ':';
    text += kHex[bytes[i] >> 4];
    text += kHex[bytes[i] & 0xf];
  }
  return text;
}

}  // namespace hubrt::dds
