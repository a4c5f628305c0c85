// The baseline side of the side-by-side benchmarks: Cyclone DDS used directly through its C API,
// with the QoS hubrt uses (ROS 2 default: reliable, volatile, keep-last 10, XCDR1), so that the
// only difference to a hub is the hub.
#pragma once

#include <cstdint>
#include <string>

#include <dds/dds.h>

#include "hubrt/base/status.h"

namespace hubrt::bench {

// Domain id from ROS_DOMAIN_ID (0 when unset). Cyclone itself reads CYCLONEDDS_URI.
std::uint32_t domain_from_environment() noexcept;

// A participant in `domain`. Errors: Cyclone's refusal.
Expected<dds_entity_t> raw_participant(std::uint32_t domain);

// The QoS of every raw reader and writer; the caller deletes it (dds_delete_qos).
dds_qos_t* raw_qos();

// A reader or writer of `descriptor` on DDS topic `dds_name` (e.g. "rt/bench/ping").
// Errors: Cyclone's refusal naming the topic.
Expected<dds_entity_t> raw_reader(dds_entity_t participant, const dds_topic_descriptor_t& descriptor,
                                  const std::string& dds_name);
Expected<dds_entity_t> raw_writer(dds_entity_t participant, const dds_topic_descriptor_t& descriptor,
                                  const std::string& dds_name);

// A waitset with a read condition on `reader` attached. Errors: Cyclone's refusal.
Expected<dds_entity_t> raw_waitset(dds_entity_t participant, dds_entity_t reader);

// Blocks until `count` readers match `writer` or `timeout_s` passes. Returns whether they did.
bool wait_for_readers(dds_entity_t writer, std::uint32_t count, double timeout_s);

// CLOCK_MONOTONIC in seconds.
double mono_now() noexcept;

}  // namespace hubrt::bench
