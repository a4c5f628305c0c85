// The 16-byte DDS GUID that names participants and endpoints on the wire.
#pragma once

#include <array>
#include <compare>
#include <cstdint>
#include <string>

#include <dds/dds.h>

namespace hubrt::dds {

// A plain value: copy it freely, read it from any thread.
struct Guid {
  std::array<std::uint8_t, 16> bytes{};

  static Guid from(const dds_guid_t& guid) noexcept;
  // Four groups of 8 hex digits separated by ':' (prefix words, then entity id), as Cyclone's
  // own traces print GUIDs, e.g. "0110a3c2:5b8e01a4:c40f8f1e:000001c1".
  [[nodiscard]] std::string to_string() const;

  // NOLINTNEXTLINE(modernize-use-nullptr): clang-tidy 14 misreads the defaulted comparison.
  friend auto operator<=>(const Guid&, const Guid&) = default;
};

}  // namespace hubrt::dds
