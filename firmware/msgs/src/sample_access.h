// Reading and writing the fields of a sample through its TypeInfo: the one place that knows the C
// layout idlc generates (scalars in place, char* strings, dds_sequence_t-shaped sequences).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>

#include "hubrt/msgs/type_info.h"

namespace hubrt::msgs::detail {

inline void* field_address(void* sample, const FieldInfo& field) {
  return static_cast<char*>(sample) + field.offset;
}
inline const void* field_address(const void* sample, const FieldInfo& field) {
  return static_cast<const char*>(sample) + field.offset;
}

// Every idlc sequence struct has the layout of dds_sequence_t; only the _buffer type differs.
inline dds_sequence_t* as_sequence(void* field) {
  return static_cast<dds_sequence_t*>(field);
}
inline const dds_sequence_t* as_sequence(const void* field) {
  return static_cast<const dds_sequence_t*>(field);
}

// Number of elements of a kSequence (its _length) or kArray (its bound) field.
std::size_t element_count(const FieldInfo& field, const void* field_addr);
// Address of element i of a kSequence or kArray field. Precondition: i < element_count().
void* element_address(const FieldInfo& field, void* field_addr, std::size_t i);
const void* element_address(const FieldInfo& field, const void* field_addr, std::size_t i);

bool is_scalar(FieldKind kind);
bool is_integer(FieldKind kind);

// A scalar value before it is stored: bool, signed integer, unsigned integer or floating point.
using Scalar = std::variant<bool, std::int64_t, std::uint64_t, double>;

// The accepted range of an integer kind, e.g. "-128..127", for messages.
std::string integer_range(FieldKind kind);
// Empty when `value` fits `kind`, else why not ("300 is out of range for uint8 (0..255)").
// Precondition: is_scalar(kind) and the alternative matches the kind's family.
std::string range_problem(FieldKind kind, const Scalar& value);

// Stores a value that range_problem() accepted.
void store_scalar(FieldKind kind, void* addr, const Scalar& value);
Scalar load_scalar(FieldKind kind, const void* addr);

// Replaces the string of `slot` at `addr`: a char* by a dds_string_dup'ed copy of `text`
// (freeing the old), a bounded char[N+1] by a copy in place. Precondition: a bounded string's
// `text` has at most N bytes (callers check and say so).
void store_string(const FieldInfo& slot, void* addr, std::string_view text);

// Resizes a sequence the sample owns to `length` elements: kept elements move over, new ones are
// zero, dropped ones are released. Afterwards _maximum == _length and _release is set.
void resize_sequence(const FieldInfo& field, void* field_addr, std::size_t length);

// Releases what one element of `kind` (string or struct) owns; nothing for scalars and bounded
// strings (`string_bound` != 0: inline).
void free_element(FieldKind kind, const TypeInfo* nested, void* addr, std::uint32_t string_bound) noexcept;

}  // namespace hubrt::msgs::detail
