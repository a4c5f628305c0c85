#include "sample_access.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

#include <fmt/format.h>

#include "hubrt/msgs/sample_memory.h"

namespace hubrt::msgs::detail {
namespace {

// Out of memory in a tool-side conversion is not recoverable; same as an uncaught bad_alloc.
void* checked(void* p) {
  if (p == nullptr) std::abort();
  return p;
}

template <class T>
T load(const void* addr) {
  T v;
  std::memcpy(&v, addr, sizeof v);
  return v;
}

template <class T>
void store(void* addr, T v) {
  std::memcpy(addr, &v, sizeof v);
}

struct IntegerLimits {
  std::int64_t min;
  std::uint64_t max;
};

IntegerLimits limits_of(FieldKind kind) {
  switch (kind) {
    case FieldKind::kOctet:
    case FieldKind::kUInt8:
      return {0, std::numeric_limits<std::uint8_t>::max()};
    case FieldKind::kInt8:
      return {std::numeric_limits<std::int8_t>::min(), std::numeric_limits<std::int8_t>::max()};
    case FieldKind::kInt16:
      return {std::numeric_limits<std::int16_t>::min(), std::numeric_limits<std::int16_t>::max()};
    case FieldKind::kUInt16:
      return {0, std::numeric_limits<std::uint16_t>::max()};
    case FieldKind::kInt32:
      return {std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max()};
    case FieldKind::kUInt32:
      return {0, std::numeric_limits<std::uint32_t>::max()};
    case FieldKind::kInt64:
      return {std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max()};
    case FieldKind::kUInt64:
      return {0, std::numeric_limits<std::uint64_t>::max()};
    default:
      return {0, 0};
  }
}

std::string to_text(const Scalar& v) {
  return std::visit(
      [](const auto& x) -> std::string {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, bool>) {
          return x ? "true" : "false";
        } else {
          return fmt::format("{}", x);
        }
      },
      v);
}

}  // namespace

std::size_t element_count(const FieldInfo& field, const void* field_addr) {
  if (field.kind == FieldKind::kArray) return field.bound;
  return as_sequence(field_addr)->_length;
}

void* element_address(const FieldInfo& field, void* field_addr, std::size_t i) {
  char* base = field.kind == FieldKind::kArray ? static_cast<char*>(field_addr)
                                               : reinterpret_cast<char*>(as_sequence(field_addr)->_buffer);
  return base + i * field.element_size;
}

const void* element_address(const FieldInfo& field, const void* field_addr, std::size_t i) {
  const char* base = field.kind == FieldKind::kArray
                         ? static_cast<const char*>(field_addr)
                         : reinterpret_cast<const char*>(as_sequence(field_addr)->_buffer);
  return base + i * field.element_size;
}

bool is_integer(FieldKind kind) {
  switch (kind) {
    case FieldKind::kOctet:
    case FieldKind::kInt8:
    case FieldKind::kUInt8:
    case FieldKind::kInt16:
    case FieldKind::kUInt16:
    case FieldKind::kInt32:
    case FieldKind::kUInt32:
    case FieldKind::kInt64:
    case FieldKind::kUInt64:
      return true;
    default:
      return false;
  }
}

bool is_scalar(FieldKind kind) {
  return is_integer(kind) || kind == FieldKind::kBool || kind == FieldKind::kFloat32 ||
         kind == FieldKind::kFloat64;
}

std::string integer_range(FieldKind kind) {
  const auto lim = limits_of(kind);
  return fmt::format("{}..{}", lim.min, lim.max);
}

std::string range_problem(FieldKind kind, const Scalar& value) {
  if (is_integer(kind)) {
    const auto lim = limits_of(kind);
    bool fits = false;
    if (const auto* s = std::get_if<std::int64_t>(&value)) {
      fits = *s >= lim.min && (*s < 0 || static_cast<std::uint64_t>(*s) <= lim.max);
    } else if (const auto* u = std::get_if<std::uint64_t>(&value)) {
      fits = *u <= lim.max;
    }
    if (fits) return {};
    return fmt::format("{} is out of range for {} ({})", to_text(value), to_string(kind),
                       integer_range(kind));
  }
  if (kind == FieldKind::kFloat32) {
    // Anything below FLT_MAX + half an ulp rounds to FLT_MAX (so the 3.4028235e+38 that to_json
    // writes for FLT_MAX reads back); from there on it would become infinity.
    const double limit = static_cast<double>(std::numeric_limits<float>::max()) + std::ldexp(1.0, 103);
    const double d = std::get<double>(value);
    if (std::isfinite(d) && std::fabs(d) >= limit) {
      return fmt::format("{} is out of range for float32 (magnitude at most {})", d,
                         std::numeric_limits<float>::max());
    }
  }
  return {};
}

void store_scalar(FieldKind kind, void* addr, const Scalar& value) {
  const auto as_u64 = [&] {
    if (const auto* s = std::get_if<std::int64_t>(&value)) return static_cast<std::uint64_t>(*s);
    return std::get<std::uint64_t>(value);
  };
  const auto as_i64 = [&] {
    if (const auto* s = std::get_if<std::int64_t>(&value)) return *s;
    return static_cast<std::int64_t>(std::get<std::uint64_t>(value));
  };
  switch (kind) {
    case FieldKind::kBool:
      store(addr, std::get<bool>(value));
      break;
    case FieldKind::kOctet:
    case FieldKind::kUInt8:
      store(addr, static_cast<std::uint8_t>(as_u64()));
      break;
    case FieldKind::kInt8:
      store(addr, static_cast<std::int8_t>(as_i64()));
      break;
    case FieldKind::kInt16:
      store(addr, static_cast<std::int16_t>(as_i64()));
      break;
    case FieldKind::kUInt16:
      store(addr, static_cast<std::uint16_t>(as_u64()));
      break;
    case FieldKind::kInt32:
      store(addr, static_cast<std::int32_t>(as_i64()));
      break;
    case FieldKind::kUInt32:
      store(addr, static_cast<std::uint32_t>(as_u64()));
      break;
    case FieldKind::kInt64:
      store(addr, as_i64());
      break;
    case FieldKind::kUInt64:
      store(addr, as_u64());
      break;
    case FieldKind::kFloat32:
      store(addr, static_cast<float>(std::get<double>(value)));
      break;
    case FieldKind::kFloat64:
      store(addr, std::get<double>(value));
      break;
    default:
      break;
  }
}

Scalar load_scalar(FieldKind kind, const void* addr) {
  switch (kind) {
    case FieldKind::kBool:
      return load<bool>(addr);
    case FieldKind::kOctet:
    case FieldKind::kUInt8:
      return std::uint64_t{load<std::uint8_t>(addr)};
    case FieldKind::kInt8:
      return std::int64_t{load<std::int8_t>(addr)};
    case FieldKind::kInt16:
      return std::int64_t{load<std::int16_t>(addr)};
    case FieldKind::kUInt16:
      return std::uint64_t{load<std::uint16_t>(addr)};
    case FieldKind::kInt32:
      return std::int64_t{load<std::int32_t>(addr)};
    case FieldKind::kUInt32:
      return std::uint64_t{load<std::uint32_t>(addr)};
    case FieldKind::kInt64:
      return load<std::int64_t>(addr);
    case FieldKind::kUInt64:
      return load<std::uint64_t>(addr);
    case FieldKind::kFloat32:
      return double{load<float>(addr)};
    case FieldKind::kFloat64:
      return load<double>(addr);
    default:
      return false;
  }
}

void store_string(const FieldInfo& slot, void* addr, std::string_view text) {
  if (slot.string_bound != 0) {
    const std::size_t n = std::min<std::size_t>(text.size(), slot.string_bound);
    std::memcpy(addr, text.data(), n);
    static_cast<char*>(addr)[n] = '\0';
    return;
  }
  char* copy = static_cast<char*>(checked(dds_string_alloc(text.size())));
  std::memcpy(copy, text.data(), text.size());
  copy[text.size()] = '\0';
  char* old = load<char*>(addr);
  store(addr, copy);
  dds_free(old);
}

void free_element(FieldKind kind, const TypeInfo* nested, void* addr, std::uint32_t string_bound) noexcept {
  if (kind == FieldKind::kString && string_bound == 0) {
    dds_free(load<char*>(addr));
    store<char*>(addr, nullptr);
  } else if (kind == FieldKind::kStruct) {
    free_contents(*nested, addr);
  }
}

void resize_sequence(const FieldInfo& field, void* field_addr, std::size_t length) {
  dds_sequence_t* seq = as_sequence(field_addr);
  const std::size_t es = field.element_size;
  char* fresh = length == 0 ? nullptr : static_cast<char*>(checked(dds_alloc(length * es)));
  if (fresh != nullptr) std::memset(fresh, 0, length * es);
  const std::size_t kept = std::min<std::size_t>(seq->_length, length);
  if (kept > 0) std::memcpy(fresh, seq->_buffer, kept * es);
  // Like dds_sample_free: elements up to max(_maximum, _length) may own memory; string elements
  // only count when the buffer is ours (_release), struct elements always.
  const std::size_t held = std::max(seq->_maximum, seq->_length);
  const bool owns_elements = seq->_release || field.element_kind == FieldKind::kStruct;
  if (owns_elements) {
    for (std::size_t i = kept; i < held; ++i) {
      free_element(field.element_kind, field.nested, seq->_buffer + i * es, field.string_bound);
    }
  }
  if (seq->_release) dds_free(seq->_buffer);
  seq->_buffer = reinterpret_cast<std::uint8_t*>(fresh);
  seq->_length = static_cast<std::uint32_t>(length);
  seq->_maximum = static_cast<std::uint32_t>(length);
  seq->_release = true;
}

}  // namespace hubrt::msgs::detail
