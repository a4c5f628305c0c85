#include "byte_io.h"

#include <fmt/format.h>

#include "hubrt/base/utf8.h"

namespace hubrt::mcap::detail {

bool ByteReader::string(std::string& v, const char* field) {
  Bytes text;
  if (!sized_bytes32(text, field)) return false;
  const std::string_view view(reinterpret_cast<const char*>(text.data()), text.size());
  // Strings "must be valid UTF-8" (spec, "String"); a topic or schema name that is not would
  // reach a terminal, JSON output and the Foxglove protocol.
  if (!is_valid_utf8(view)) {
    failed_field_ = field;
    bad_utf8_ = true;
    return false;
  }
  v.assign(view);
  return true;
}

bool ByteReader::sized_bytes32(Bytes& v, const char* field) {
  return sized_bytes<std::uint32_t>(v, field, 4);
}

bool ByteReader::sized_bytes64(Bytes& v, const char* field) {
  return sized_bytes<std::uint64_t>(v, field, 8);
}

template <class Length>
bool ByteReader::sized_bytes(Bytes& v, const char* field, int length_bytes) {
  const std::size_t start = pos_;
  Length length = 0;
  if (!fixed(length, length_bytes, field)) return false;
  if (remaining() < length) {
    pos_ = start;
    return fail(field, length);
  }
  v = bytes_.subspan(pos_, static_cast<std::size_t>(length));
  pos_ += static_cast<std::size_t>(length);
  return true;
}

bool ByteReader::fail(const char* field, std::uint64_t wanted) {
  failed_field_ = field;
  wanted_ = wanted;
  return false;
}

Error ByteReader::failure() const {
  const char* field = failed_field_ != nullptr ? failed_field_ : "?";
  if (bad_utf8_)
    return make_error(ErrorCode::kProtocol, fmt::format("{}: {}: not valid UTF-8", record_, field));
  return make_error(ErrorCode::kProtocol,
                    fmt::format("{}: {}: {} byte(s) beyond the record's {} (at byte {})", record_, field,
                                wanted_, bytes_.size(), pos_));
}

}  // namespace hubrt::mcap::detail
