// Finds the sertype Cyclone uses for a topic, which the C API does not return (Cyclone 0.10.2
// exports no dds_get_entity_sertype), so that hubrt can make serdata of it (serdata_pool.h).
#pragma once

#include <dds/dds.h>

namespace hubrt::dds::detail {

// The sertype of `topic` (created by dds_create_topic in `participant`'s domain), or nullptr when
// it cannot be found. How: a reader and a writer of `topic` in a partition of their own (no other
// endpoint matches them), one sample written and taken back as serdata (dds_takecdr), whose type
// is the topic's sertype, both deleted again. The pointer stays valid while the topic lives; take a
// reference (ddsi_sertype_ref) to keep it longer. Allocates; for set-up, not for a cycle.
const struct ddsi_sertype* probe_topic_sertype(dds_entity_t participant, dds_entity_t topic,
                                               const dds_topic_descriptor_t& descriptor);

// Whether a discovered endpoint's QoS is a probe's (its partition): a watch of the domain's writers
// skips them, for they exist only for the moment a writer or codec is made, anywhere in the domain
// (a tap that saw one announced a topic with two writers where there was one).
bool is_sertype_probe(const dds_qos_t* qos) noexcept;

}  // namespace hubrt::dds::detail
