// Static description of an IDL struct as idlc's C generator laid it out: names, size and, per
// field, kind and offset. The tables are emitted by the idlc plugin in firmware/msgs/reflect/ into
// <idl>_reflect.h/.cc next to idlc's own <idl>.h/.c, and are constant-initialised (no dynamic
// initialisation, hence no static-initialisation-order problem across libraries).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string_view>

#include <dds/ddsc/dds_public_impl.h>

namespace hubrt::msgs {

// What a field (or the element of a sequence or array) is, as stored in the generated C struct.
enum class FieldKind : std::uint8_t {
  kBool,      // bool
  kOctet,     // uint8_t (IDL octet, ROS byte)
  kInt8,      // int8_t
  kUInt8,     // uint8_t (IDL uint8, ROS uint8 and char)
  kInt16,     // int16_t
  kUInt16,    // uint16_t
  kInt32,     // int32_t
  kUInt32,    // uint32_t
  kInt64,     // int64_t
  kUInt64,    // uint64_t
  kFloat32,   // float
  kFloat64,   // double
  kString,    // char* (unbounded, owned by the sample: dds_string_dup / dds_free), or, when
              // FieldInfo::string_bound is N > 0 (IDL string<N>), char[N+1] inline
  kStruct,    // an embedded struct, described by FieldInfo::nested
  kSequence,  // dds_sequence_X {_maximum, _length, _buffer, _release} of element_kind
  kArray,     // X[bound], inline, of element_kind
};

struct TypeInfo;

struct FieldInfo {
  std::string_view name;
  FieldKind kind;
  // For kSequence and kArray the kind of one element (never kSequence or kArray); otherwise kind.
  FieldKind element_kind;
  std::size_t offset;        // offsetof the field in the enclosing struct
  std::size_t element_size;  // sizeof one element (of the field itself when not a container)
  // kArray: number of elements; kSequence: maximum length, 0 when unbounded; otherwise 0.
  std::uint32_t bound;
  // The struct type when kind or element_kind is kStruct, else nullptr.
  const TypeInfo* nested;
  // N of IDL string<N> when kind or element_kind is kString and the string is bounded: stored
  // inline as char[N+1], NUL-terminated. 0: unbounded (char*) or not a string.
  std::uint32_t string_bound = 0;
};

struct TypeInfo {
  std::string_view dds_name;  // scoped IDL name, e.g. "hub_msgs::msg::dds_::DockState_"
  // ROS 2 name, e.g. "hub_msgs/msg/DockState"; empty when the IDL does not follow the ROS 2
  // naming (<pkg>::msg::dds_::<Type>_).
  std::string_view ros_name;
  std::string_view c_name;    // the generated C type, e.g. "hub_msgs_msg_dds__DockState_"
  std::string_view idl_file;  // file name (without directories) the type was declared in
  std::size_t size;           // sizeof the generated C struct
  // idlc's topic descriptor; nullptr only for @nested types (idlc emits none for them).
  const dds_topic_descriptor_t* descriptor;
  std::span<const FieldInfo> fields;  // in declaration (= wire) order
};

// TypeInfoOf<C struct>::value is the table of a generated type; specialised in <idl>_reflect.h.
template <class T>
struct TypeInfoOf;

// The table of generated type T, e.g. type_info_of<hub_msgs_msg_dds__DockState_>().
template <class T>
constexpr const TypeInfo& type_info_of() noexcept {
  return TypeInfoOf<T>::value;
}

// The text of the string (element) of `field` stored at `addr`: char* or, bounded, char[N+1]
// (read up to its NUL, at most N+1 bytes). A null char* reads as "". Thread-safe.
inline std::string_view string_at(const FieldInfo& field, const void* addr) noexcept {
  if (field.string_bound != 0) {
    const char* text = static_cast<const char*>(addr);
    return {text, ::strnlen(text, std::size_t{field.string_bound} + 1)};
  }
  const char* text = *static_cast<const char* const*>(addr);
  return text == nullptr ? std::string_view() : std::string_view(text);
}

// Stable lower-case IDL-style name of a kind, e.g. "uint32", "sequence". Thread-safe.
std::string_view to_string(FieldKind kind) noexcept;

// The field's type as a reader would write it: "float32", "string", "hub_msgs/msg/DockSlot",
// "sequence<string>", "string<64>", "int32[3]", "sequence<hub_msgs/msg/DockSlot, 8>". Struct types are given
// by their ROS name, or their DDS name when they have none. Thread-safe.
std::string describe_type(const FieldInfo& field);

}  // namespace hubrt::msgs
