#include "hubrt/ros1/codec.h"

#include <bit>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include <fmt/format.h>

#include "hubrt/base/utf8.h"
#include "hubrt/msgs/sample_memory.h"

namespace hubrt::ros1 {
namespace {

using msgs::FieldInfo;
using msgs::FieldKind;
using msgs::TypeInfo;

std::size_t scalar_size(FieldKind kind) {
  switch (kind) {
    case FieldKind::kBool:
    case FieldKind::kOctet:
    case FieldKind::kInt8:
    case FieldKind::kUInt8:
      return 1;
    case FieldKind::kInt16:
    case FieldKind::kUInt16:
      return 2;
    case FieldKind::kInt32:
    case FieldKind::kUInt32:
    case FieldKind::kFloat32:
      return 4;
    case FieldKind::kInt64:
    case FieldKind::kUInt64:
    case FieldKind::kFloat64:
      return 8;
    default:
      return 0;
  }
}

// Little-endian byte order (ROS 1 and every hub CPU: x86-64, arm64); a big-endian host would need
// byte swaps here.
static_assert(std::endian::native == std::endian::little, "ROS 1 is little-endian; add byte swaps");

// ---- encoding -----------------------------------------------------------------------------------

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
  out.insert(out.end(), p, p + 4);
}

void encode_struct(const TypeInfo& type, const void* sample, std::vector<std::uint8_t>& out);

void encode_element(const FieldInfo& field, FieldKind kind, const void* addr,
                    std::vector<std::uint8_t>& out) {
  if (kind == FieldKind::kString) {
    const std::string_view text = msgs::string_at(field, addr);
    put_u32(out, static_cast<std::uint32_t>(text.size()));
    out.insert(out.end(), text.begin(), text.end());
  } else if (kind == FieldKind::kStruct) {
    encode_struct(*field.nested, addr, out);
  } else {
    const auto* p = static_cast<const std::uint8_t*>(addr);
    out.insert(out.end(), p, p + scalar_size(kind));
  }
}

void encode_struct(const TypeInfo& type, const void* sample, std::vector<std::uint8_t>& out) {
  for (const FieldInfo& field : type.fields) {
    const auto* addr = static_cast<const std::uint8_t*>(sample) + field.offset;
    if (field.kind == FieldKind::kSequence) {
      const auto* seq = reinterpret_cast<const dds_sequence_t*>(addr);
      put_u32(out, seq->_length);
      for (std::uint32_t i = 0; i < seq->_length; ++i) {
        encode_element(field, field.element_kind, seq->_buffer + i * field.element_size, out);
      }
    } else if (field.kind == FieldKind::kArray) {
      for (std::uint32_t i = 0; i < field.bound; ++i) {
        encode_element(field, field.element_kind, addr + i * field.element_size, out);
      }
    } else {
      encode_element(field, field.kind, addr, out);
    }
  }
}

// ---- decoding -----------------------------------------------------------------------------------

// The fewest bytes one element of this kind takes on the ROS 1 wire: a count that needs more than
// the bytes left is refused before anything is allocated.
std::size_t min_wire_size(FieldKind kind, const TypeInfo* nested, std::uint32_t bound);

std::size_t min_struct_size(const TypeInfo& type) {
  std::size_t total = 0;
  for (const FieldInfo& f : type.fields) {
    if (f.kind == FieldKind::kArray) {
      total += f.bound * min_wire_size(f.element_kind, f.nested, 0);
    } else {
      total += min_wire_size(f.kind, f.nested, 0);
    }
  }
  return total;
}

std::size_t min_wire_size(FieldKind kind, const TypeInfo* nested, std::uint32_t /*bound*/) {
  if (kind == FieldKind::kString || kind == FieldKind::kSequence) return 4;
  if (kind == FieldKind::kStruct) return min_struct_size(*nested);
  return scalar_size(kind);
}

class Decoder {
 public:
  explicit Decoder(std::span<const std::uint8_t> wire) : wire_(wire) {}

  std::optional<DecodeError> struct_at(const TypeInfo& type, std::uint8_t* sample, const std::string& path) {
    for (const FieldInfo& field : type.fields) {
      const std::string where =
          path.empty() ? std::string(field.name) : fmt::format("{}.{}", path, field.name);
      std::uint8_t* addr = sample + field.offset;
      std::optional<DecodeError> error;
      if (field.kind == FieldKind::kSequence) {
        error = sequence_at(field, addr, where);
      } else if (field.kind == FieldKind::kArray) {
        for (std::uint32_t i = 0; i < field.bound && !error; ++i) {
          error = element_at(field, field.element_kind, addr + i * field.element_size,
                             fmt::format("{}[{}]", where, i));
        }
      } else {
        error = element_at(field, field.kind, addr, where);
      }
      if (error) return error;
    }
    return std::nullopt;
  }

  [[nodiscard]] std::size_t left() const { return wire_.size() - pos_; }

 private:
  static DecodeError fail(DecodeProblem problem, const std::string& field, std::string what) {
    return DecodeError{problem, field, field.empty() ? what : fmt::format("{}: {}", field, what)};
  }

  std::optional<DecodeError> u32_at(std::uint32_t* value, const std::string& where) {
    if (left() < 4) return fail(DecodeProblem::kMalformed, where, "message ends inside a length");
    std::memcpy(value, wire_.data() + pos_, 4);
    pos_ += 4;
    return std::nullopt;
  }

  std::optional<DecodeError> sequence_at(const FieldInfo& field, std::uint8_t* addr,
                                         const std::string& where) {
    std::uint32_t count = 0;
    if (auto e = u32_at(&count, where)) return e;
    if (field.bound != 0 && count > field.bound) {
      return fail(DecodeProblem::kOverBound, where,
                  fmt::format("{} elements, over the bound of {} (dropped, not cut)", count, field.bound));
    }
    const std::size_t least = min_wire_size(field.element_kind, field.nested, 0);
    if (least != 0 && count > left() / least) {
      return fail(DecodeProblem::kMalformed, where,
                  fmt::format("{} elements announced but only {} bytes follow", count, left()));
    }
    auto* seq = reinterpret_cast<dds_sequence_t*>(addr);
    if (count > 0) {
      void* buffer = dds_alloc(std::size_t{count} * field.element_size);
      if (buffer == nullptr) std::abort();  // out of memory: as an uncaught bad_alloc
      std::memset(buffer, 0, std::size_t{count} * field.element_size);
      seq->_buffer = static_cast<std::uint8_t*>(buffer);
    }
    seq->_length = count;
    seq->_maximum = count;
    seq->_release = true;
    for (std::uint32_t i = 0; i < count; ++i) {
      if (auto e = element_at(field, field.element_kind, seq->_buffer + i * field.element_size,
                              fmt::format("{}[{}]", where, i))) {
        return e;
      }
    }
    return std::nullopt;
  }

  std::optional<DecodeError> element_at(const FieldInfo& field, FieldKind kind, std::uint8_t* addr,
                                        const std::string& where) {
    if (kind == FieldKind::kStruct) return struct_at(*field.nested, addr, where);
    if (kind == FieldKind::kString) return string_at(field, addr, where);
    const std::size_t n = scalar_size(kind);
    if (left() < n) return fail(DecodeProblem::kMalformed, where, "message ends inside the field");
    std::memcpy(addr, wire_.data() + pos_, n);
    if (kind == FieldKind::kBool && *addr > 1) {
      return fail(DecodeProblem::kMalformed, where, fmt::format("bool byte {} is neither 0 nor 1", *addr));
    }
    pos_ += n;
    return std::nullopt;
  }

  std::optional<DecodeError> string_at(const FieldInfo& field, std::uint8_t* addr, const std::string& where) {
    std::uint32_t size = 0;
    if (auto e = u32_at(&size, where)) return e;
    if (size > left()) {
      return fail(DecodeProblem::kMalformed, where,
                  fmt::format("string of {} bytes announced but only {} follow", size, left()));
    }
    const std::string_view text(reinterpret_cast<const char*>(wire_.data() + pos_), size);
    if (field.string_bound != 0 && size > field.string_bound) {
      return fail(DecodeProblem::kOverBound, where,
                  fmt::format("{} bytes, over the bound of {} (dropped, not cut)", size, field.string_bound));
    }
    if (text.find('\0') != std::string_view::npos) {
      return fail(DecodeProblem::kBadText, where, "text holds a NUL byte");
    }
    if (!is_valid_utf8(text)) return fail(DecodeProblem::kBadText, where, "text is not valid UTF-8");
    pos_ += size;
    if (field.string_bound != 0) {
      std::memcpy(addr, text.data(), text.size());
      addr[text.size()] = 0;
      return std::nullopt;
    }
    char* copy = dds_string_alloc(text.size());
    if (copy == nullptr) std::abort();  // out of memory: as an uncaught bad_alloc
    std::memcpy(copy, text.data(), text.size());
    copy[text.size()] = '\0';
    std::memcpy(addr, &copy, sizeof copy);
    return std::nullopt;
  }

  std::span<const std::uint8_t> wire_;
  std::size_t pos_ = 0;
};

}  // namespace

void encode(const TypeInfo& type, const void* sample, std::vector<std::uint8_t>& out) {
  encode_struct(type, sample, out);
}

std::optional<DecodeError> decode(const TypeInfo& type, std::span<const std::uint8_t> wire, void* sample) {
  msgs::free_contents(type, sample);
  Decoder decoder(wire);
  auto error = decoder.struct_at(type, static_cast<std::uint8_t*>(sample), std::string());
  if (!error && decoder.left() != 0) {
    error = DecodeError{DecodeProblem::kMalformed, std::string(),
                        fmt::format("{} bytes after the end of the message", decoder.left())};
  }
  if (error) msgs::free_contents(type, sample);
  return error;
}

}  // namespace hubrt::ros1
