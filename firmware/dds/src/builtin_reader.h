// A reader of one of Cyclone's builtin discovery topics with a data-available listener: what
// WriterWatch and PeerAuthenticationWatch read discovery with.
#pragma once

#include <string>

#include <dds/dds.h>

#include "hubrt/base/status.h"
#include "hubrt/dds/entity.h"
#include "hubrt/dds/participant.h"

namespace hubrt::dds::detail {

// Creates a reader of builtin `topic` (DDS_BUILTIN_TOPIC_DCPS...) on `participant` whose listener
// calls `callback(reader, arg)` on Cyclone's threads. Errors: "<what>: read discovery topic
// <name>: DDS_RETCODE_...".
Expected<EntityHandle> listening_builtin_reader(const Participant& participant, dds_entity_t topic,
                                                const char* name, const std::string& what, void* arg,
                                                dds_on_data_available_fn callback);

}  // namespace hubrt::dds::detail
