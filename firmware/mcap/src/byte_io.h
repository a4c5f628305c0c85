// Little-endian fields in and out of byte buffers (MCAP spec, "Serialization"), independent of
// the host's byte order.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/mcap/records.h"

namespace hubrt::mcap::detail {

// Appends fields to a buffer. Not thread-safe.
class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>& out) noexcept : out_(out) {}

  void u8(std::uint8_t v) { out_.push_back(v); }
  void u16(std::uint16_t v) { little(v, 2); }
  void u32(std::uint32_t v) { little(v, 4); }
  void u64(std::uint64_t v) { little(v, 8); }
  void bytes(Bytes b) { out_.insert(out_.end(), b.begin(), b.end()); }
  void string(std::string_view s) {
    u32(static_cast<std::uint32_t>(s.size()));
    out_.insert(out_.end(), s.begin(), s.end());
  }
  // A uint32 byte length to be filled in later (Map, Array): returns where it is.
  std::size_t reserve_u32() {
    const std::size_t at = out_.size();
    u32(0);
    return at;
  }
  void fill_u32(std::size_t at, std::uint32_t v) noexcept {
    for (int i = 0; i < 4; ++i)
      out_[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
  }
  [[nodiscard]] std::size_t size() const noexcept { return out_.size(); }

 private:
  void little(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  std::vector<std::uint8_t>& out_;
};

inline std::uint64_t load_le(const std::uint8_t* p, int n) noexcept {
  std::uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

// Reads fields from a record's content, never past its end. Each read returns false (and reads
// nothing) when the field does not fit or, for strings, is not valid UTF-8; `failure()` then
// says which field. Not thread-safe.
class ByteReader {
 public:
  ByteReader(Bytes bytes, std::string_view record) noexcept : bytes_(bytes), record_(record) {}

  bool u8(std::uint8_t& v, const char* field) { return fixed(v, 1, field); }
  bool u16(std::uint16_t& v, const char* field) { return fixed(v, 2, field); }
  bool u32(std::uint32_t& v, const char* field) { return fixed(v, 4, field); }
  bool u64(std::uint64_t& v, const char* field) { return fixed(v, 8, field); }
  bool string(std::string& v, const char* field);
  // A uint32 (or, for a Chunk's records, uint64) length and that many bytes.
  bool sized_bytes32(Bytes& v, const char* field);
  bool sized_bytes64(Bytes& v, const char* field);
  // The rest of the content (Message data).
  Bytes rest() noexcept {
    Bytes r = bytes_.subspan(pos_);
    pos_ = bytes_.size();
    return r;
  }
  [[nodiscard]] std::size_t remaining() const noexcept { return bytes_.size() - pos_; }
  [[nodiscard]] Error failure() const;

 private:
  template <class T>
  bool fixed(T& v, int n, const char* field) {
    if (remaining() < static_cast<std::size_t>(n)) return fail(field, static_cast<std::uint64_t>(n));
    v = static_cast<T>(load_le(bytes_.data() + pos_, n));
    pos_ += static_cast<std::size_t>(n);
    return true;
  }
  bool fail(const char* field, std::uint64_t wanted);
  template <class Length>
  bool sized_bytes(Bytes& v, const char* field, int length_bytes);

  Bytes bytes_;
  std::string_view record_;
  std::size_t pos_ = 0;
  const char* failed_field_ = nullptr;
  std::uint64_t wanted_ = 0;
  bool bad_utf8_ = false;
};

}  // namespace hubrt::mcap::detail
