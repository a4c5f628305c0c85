// DDS quality of service as hubrt uses it: always XCDR1 (the representation ROS 2 and Fast DDS
// peers understand), ROS 2 profiles as starting points.
#pragma once

#include <cstdint>

#include <dds/dds.h>

#include "hubrt/base/time.h"

namespace hubrt::dds {

// What a writer offers, as discovery reports it (DCPSPublication's QoS): the policies ROS 2
// records with a topic (rosbag2's offered_qos_profiles) and needs to offer the same again when it
// plays the topic back. An infinite duration is Duration::max().
struct OfferedQos {
  enum class Reliability : std::uint8_t { kBestEffort, kReliable };
  enum class Durability : std::uint8_t { kVolatile, kTransientLocal, kTransient, kPersistent };
  enum class History : std::uint8_t { kKeepLast, kKeepAll };
  enum class Liveliness : std::uint8_t { kAutomatic, kManualByParticipant, kManualByTopic };

  Reliability reliability = Reliability::kReliable;
  Durability durability = Durability::kVolatile;
  History history = History::kKeepLast;
  std::int32_t depth = 1;  // keep-last only
  Duration deadline = Duration::max();
  Duration lifespan = Duration::max();
  Liveliness liveliness = Liveliness::kAutomatic;
  Duration liveliness_lease = Duration::max();
  bool operator==(const OfferedQos&) const = default;
};

// Reads the policies of `qos` (a discovered endpoint's; a policy it does not set reads as DDS's
// default for a writer: reliable, volatile, keep-last 1, infinite, automatic). Thread-safe.
OfferedQos read_offered_qos(const dds_qos_t* qos) noexcept;

// An owned dds_qos_t. Copyable (deep copy) and movable; a moved-from Qos holds Cyclone defaults
// plus XCDR1 again, never a null pointer. Every Qos sets the data representation to XCDR1 only.
// Thread-safety: not thread-safe; a const Qos may be shared for reading.
class Qos {
 public:
  // Cyclone's defaults with XCDR1 as the only data representation.
  Qos();
  ~Qos();
  Qos(const Qos& other);
  Qos& operator=(const Qos& other);
  Qos(Qos&& other) noexcept;
  Qos& operator=(Qos&& other) noexcept;

  // ROS 2's default profile: reliable, volatile, keep-last `depth` (10 in ROS 2).
  static Qos ros2_default(std::int32_t depth = 10);
  // ROS 2's sensor-data profile: best-effort, volatile, keep-last `depth` (5 in ROS 2).
  static Qos sensor_data(std::int32_t depth = 5);
  // What `offered` describes (XCDR1 as always): a writer offering it again when a recorded topic
  // is played back.
  static Qos from_offered(const OfferedQos& offered);

  // Builder steps; each returns *this. Depth must be >= 1 (Cyclone rejects the QoS at entity
  // creation otherwise, with an error naming the entity).
  Qos& reliable();
  Qos& best_effort();
  Qos& volatile_durability();
  Qos& transient_local();
  Qos& keep_last(std::int32_t depth);
  Qos& keep_all();
  // LIFESPAN (a writer's QoS, announced to its readers): a sample older than `lifespan` is
  // dropped instead of delivered. Cyclone 0.10.2 measures the age on each side's monotonic clock,
  // not from the source timestamp: the writer drops an unacknowledged sample from its history
  // `lifespan` after writing it (src/core/ddsi/src/q_transmit.c, insert_sample_in_whc: expiry =
  // serdata->twrite + lifespan), so it is never retransmitted later (a healed partition); a reader
  // drops a sample not taken `lifespan` after it *received* it (q_receive.c, deliver_user_data ->
  // ddsi_endpoint.c, ddsi_make_writer_info: lifespan_exp = ddsrt_time_monotonic() + lifespan).
  // So it does not protect against a sample that waited in a stopped reader's socket (received
  // only when the reader runs again) nor against skewed clocks: hubd judges the source timestamp
  // itself (runtime/command_age.h). Precondition: lifespan > 0.
  Qos& lifespan(Duration lifespan);
  // WRITER_DATA_LIFECYCLE (local to the writer, not announced): whether unregistering an instance
  // also disposes it. Cyclone's default is yes, so a writer's unregistration of a keyless topic's
  // one instance would mark it disposed at every reader; UntypedWriter::announce needs no.
  Qos& dispose_on_unregister(bool dispose);

  // For Cyclone calls; valid while this Qos lives.
  [[nodiscard]] const dds_qos_t* get() const noexcept { return qos_; }

 private:
  dds_qos_t* qos_;
};

}  // namespace hubrt::dds
