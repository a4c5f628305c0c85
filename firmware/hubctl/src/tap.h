// One tap, many views (docs/DESIGN §6): what `hubctl record`, `echo`, `watch` and `serve` (and the
// Foxglove bridge, issue 31) consume — the station's topics as they come and go, each with its
// type, its ros2msg schema text and the QoS its writers offer, and their samples as the bytes that
// were on the wire (the encapsulation header and the CDR payload) with their receive and source
// times, never decoded and encoded again.
//
// THE CONTRACT WITH CONSUMERS: the tap's thread is never held by a consumer. Each consumer reads
// from a queue of its own (TapQueue), bounded in samples; when it is full because the consumer is
// slow, the tap drops that consumer's sample (counted: dropped()) and goes on — it never blocks,
// and never waits on a lock a consumer holds longer than a push. Events are immutable and shared
// (shared_ptr<const ...>): a consumer may keep them as long as it likes, on any thread. Topic
// events are never dropped (there are few: one per topic and QoS change).
//
// The same interface reads a recording (RecordingSource, `--from FILE.mcap`): a view does not know
// whether its events come from the domain or from a file.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "hubrt/base/time.h"
#include "hubrt/dds/qos.h"
#include "hubrt/msgs/type_info.h"

namespace hubrt::hubctl {

// A topic as the tap knows it. Immutable once handed out; what changes (a writer with other QoS
// comes or goes) is a new TapTopic of the same id and a higher revision.
struct TapTopic {
  std::uint32_t id = 0;        // the source's number for it: stable while the source lives
  std::uint32_t revision = 0;  // grows with each change of `offered`
  // "/dock_ecu/dock/state"; a plant-wide tap (plant_tap.h) puts the station's name in front,
  // "/cell_a/dock_ecu/dock/state", so that every station's topics stay apart in every view.
  std::string ros_name;
  std::string station;          // that station's name ("" for a tap of one domain)
  std::uint32_t domain_id = 0;  // the DDS domain the topic is on (a recording's: 0)
  // The registered type; nullptr only for a recording's channel of a type this hubctl does not
  // know (its samples can be counted and replayed, not decoded).
  const msgs::TypeInfo* type = nullptr;
  std::string type_name;                 // ROS 2 name, "hub_msgs/msg/DockState": the MCAP schema's name
  std::string schema;                    // its ros2msg text (hubrt/msgs/definitions.h), "" when there is none
  std::vector<dds::OfferedQos> offered;  // what each writer known now offers
};

// One sample as it was on the wire.
struct TapSample {
  std::shared_ptr<const TapTopic> topic;  // the topic's revision when the sample was taken
  WallTime receive_time;                  // when the tap took it (this machine's wall clock)
  WallTime source_time;                   // the writer's DDS source timestamp
  std::uint64_t sequence = 0;             // per topic, 1, 2, ... in the order taken
  std::vector<std::uint8_t> cdr;          // encapsulation header + payload
};

struct TapEvent {
  enum class Kind : std::uint8_t {
    kTopic,      // a topic appeared, or its writers' QoS changed (a new revision)
    kTopicGone,  // its last writer went away (it may come back: another kTopic then)
    kSample,
  };
  Kind kind = Kind::kSample;
  std::shared_ptr<const TapTopic> topic;
  std::shared_ptr<const TapSample> sample;  // kSample only
};

// A consumer's queue. The tap pushes (never blocking), the consumer pops. Thread-safe.
class TapQueue {
 public:
  explicit TapQueue(std::size_t sample_capacity) : capacity_(sample_capacity) {}

  // Producer side. A sample beyond the capacity is dropped and counted; a topic event always goes
  // in. Nothing is pushed after close().
  void push(TapEvent event);
  // One more producer (a plant-wide tap's station taps share one queue): close() then closes the
  // queue only when every producer has called it. A queue starts with one producer.
  void add_producer();
  // This producer is done; once every producer is, no more events will come and pop() returns
  // what is left, then nullopt without waiting.
  void close();

  // Consumer side: the next event, waiting up to `timeout` for one; nullopt when none came (or the
  // queue is closed and empty: closed() then says so).
  std::optional<TapEvent> pop(Duration timeout);
  [[nodiscard]] bool closed_and_empty() const;
  [[nodiscard]] std::uint64_t dropped() const;

 private:
  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<TapEvent> events_;  // guarded by mutex_
  std::size_t samples_ = 0;      // samples in events_; guarded
  std::uint64_t dropped_ = 0;    // guarded
  bool closed_ = false;          // guarded
  std::size_t producers_ = 1;    // guarded: producers that have not closed yet
};

// What a view reads: the live tap or a recording. Not thread-safe: one consumer thread.
class TapSource {
 public:
  virtual ~TapSource() = default;
  // The next event, waiting up to `timeout`; nullopt when none came within it, or when the source
  // has nothing more (finished()).
  virtual std::optional<TapEvent> next(Duration timeout) = 0;
  // True once every event was handed out and no more will come (a recording's end, a closed tap).
  [[nodiscard]] virtual bool finished() const = 0;
  // Samples dropped because this consumer fell behind (live only).
  [[nodiscard]] virtual std::uint64_t dropped() const = 0;
  // Why a recording stopped before its end ("" when it did not; live: ""): shown to the user.
  [[nodiscard]] virtual std::string problem() const = 0;
};

}  // namespace hubrt::hubctl
