// A Cyclone listener held by the code that creates an entity with it (reader.cc, writer.cc,
// builtin_reader.cc): dds_create_reader/_writer take a copy of the listener, so it is deleted when
// the creating scope ends.
#pragma once

#include <memory>

#include <dds/dds.h>

namespace hubrt::dds::detail {

struct ListenerDeleter {
  void operator()(dds_listener_t* listener) const noexcept { dds_delete_listener(listener); }
};
using ListenerPtr = std::unique_ptr<dds_listener_t, ListenerDeleter>;

}  // namespace hubrt::dds::detail
