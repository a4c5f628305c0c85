#include "hubrt/msgs/sample_memory.h"

#include <algorithm>
#include <cstring>

#include "sample_access.h"

namespace hubrt::msgs {

void free_contents(const TypeInfo& type, void* sample) noexcept {
  for (const FieldInfo& field : type.fields) {
    void* addr = detail::field_address(sample, field);
    switch (field.kind) {
      case FieldKind::kString:
      case FieldKind::kStruct:
        detail::free_element(field.kind, field.nested, addr, field.string_bound);
        break;
      case FieldKind::kArray:
        for (std::size_t i = 0; i < field.bound; ++i) {
          detail::free_element(field.element_kind, field.nested, detail::element_address(field, addr, i),
                               field.string_bound);
        }
        break;
      case FieldKind::kSequence: {
        // Mirrors dds_sample_free(): see resize_sequence() for the rules.
        dds_sequence_t* seq = detail::as_sequence(addr);
        const std::size_t held = std::max(seq->_maximum, seq->_length);
        if (seq->_release || field.element_kind == FieldKind::kStruct) {
          for (std::size_t i = 0; i < held; ++i) {
            detail::free_element(field.element_kind, field.nested, seq->_buffer + i * field.element_size,
                                 field.string_bound);
          }
        }
        if (seq->_release) dds_free(seq->_buffer);
        break;
      }
      default:
        break;
    }
  }
  std::memset(sample, 0, type.size);
}

}  // namespace hubrt::msgs
