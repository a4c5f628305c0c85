// Ties an idlc-generated C struct to its topic descriptor, so the typed API can find the
// descriptor from the type alone.
#pragma once

#include <concepts>
#include <type_traits>

#include <dds/dds.h>

namespace hubrt::dds {

// Specialised by HUBRT_DDS_TOPIC_TYPE for each generated type; the primary template is left
// undefined so that using an unregistered type fails to compile.
template <class T>
struct TopicTraits;

// A generated sample type registered with HUBRT_DDS_TOPIC_TYPE. Generated structs are plain C
// structs: trivially copyable, zero-initialised by T{}.
template <class T>
concept TopicType = std::is_trivially_copyable_v<T> && std::is_standard_layout_v<T> && requires {
  { TopicTraits<T>::descriptor() } -> std::same_as<const dds_topic_descriptor_t&>;
};

}  // namespace hubrt::dds

// Registers an idlc-generated type: use at global scope, once per type, in a header that
// includes the generated one, e.g.
//   HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__DockCommand_, hub_msgs_msg_dds__DockCommand__desc)
// Topic<T>::create() checks at run time that sizeof(T) equals the descriptor's m_size.
#define HUBRT_DDS_TOPIC_TYPE(CType, Descriptor)                                         \
  template <>                                                                           \
  struct hubrt::dds::TopicTraits<CType> {                                               \
    static const dds_topic_descriptor_t& descriptor() noexcept { return (Descriptor); } \
  }
