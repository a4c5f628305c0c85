// The live tap (tap.h says what consumers can rely on): one thread that follows the domain's
// writers (dds::WriterWatch: DCPSPublication, with each writer's type and offered QoS), keeps a
// reader on every selected topic with a writer — topics that appear later included — and takes
// every sample as the bytes that were on the wire (UntypedReader::take_serialized) into each
// consumer's bounded queue.
#pragma once

#include <atomic>
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/writer_watch.h"
#include "hubrt/msgs/type_info.h"

#include "tap.h"
#include "tap_selection.h"

namespace hubrt::hubctl {

struct TapOptions {
  // Which discovered topics to take (tap_selection.h).
  TapFilter filter = &is_station_traffic;
  // Topics to read from the start, before any writer is discovered (hubctl echo TOPIC): the
  // reader is there when the first writer comes, as a subscriber's would be.
  std::vector<std::pair<std::string, const msgs::TypeInfo*>> fixed;
  // Each reader keeps this many samples between two takes: the tap takes continuously, so this
  // only absorbs a burst while its thread is descheduled. Never applies back-pressure to a writer
  // (keep-last).
  std::int32_t reader_depth = 1000;
  // A plant-wide tap (plant_tap.h) runs one tap per station's domain: each names its topics
  // "/<station>" + their ROS name ("/cell_a/dock/command"; empty: the ROS name alone) and numbers
  // them from `first_topic_id`, so that the stations' topics never share a name or an id. `fixed`
  // topics and the filter see the ROS name as on the wire.
  std::string station;
  std::uint32_t first_topic_id = 0;
};

// Counters of what the tap took, for progress lines. Thread-safe to read.
struct TapCounters {
  std::uint64_t samples = 0;
  std::uint64_t bytes = 0;
  std::uint64_t topics = 0;
};

// The consumer's end of the tap: a TapSource over its own queue.
class TapSubscription final : public TapSource {
 public:
  explicit TapSubscription(std::shared_ptr<TapQueue> queue) : queue_(std::move(queue)) {}
  std::optional<TapEvent> next(Duration timeout) override { return queue_->pop(timeout); }
  [[nodiscard]] bool finished() const override { return queue_->closed_and_empty(); }
  [[nodiscard]] std::uint64_t dropped() const override { return queue_->dropped(); }
  [[nodiscard]] std::string problem() const override { return {}; }

 private:
  std::shared_ptr<TapQueue> queue_;
};

class StationTap {
 public:
  // Starts following `participant`'s domain (the participant must outlive the tap) on a thread of
  // its own. Errors: the discovery watch or the waitset could not be created (Cyclone's reason).
  static Expected<std::unique_ptr<StationTap>> start(const dds::Participant& participant, TapOptions options);
  // Stops the thread, deletes the readers and closes every queue.
  ~StationTap();
  StationTap(const StationTap&) = delete;
  StationTap& operator=(const StationTap&) = delete;

  // A new consumer whose queue holds at most `sample_capacity` samples; it first gets a kTopic
  // event for every topic the tap has now. The tap takes no sample before its first consumer is
  // there: what came since start() waits in the readers (reader_depth). Thread-safe.
  std::unique_ptr<TapSubscription> subscribe(std::size_t sample_capacity);
  // The same into a queue other taps feed too (a plant-wide tap): the caller has counted this tap
  // among its producers (TapQueue::add_producer); the tap closes it once when it ends. Thread-safe.
  void feed(std::shared_ptr<TapQueue> queue);

  // Every topic the tap reads now. Thread-safe.
  [[nodiscard]] std::vector<std::shared_ptr<const TapTopic>> topics() const;
  // Every ROS topic some other participant writes, taken or not, and the discovered topics skipped
  // because this hubctl does not know their type ("topic (type)"). Thread-safe.
  [[nodiscard]] std::vector<std::string> written_topics() const;
  [[nodiscard]] std::vector<std::string> unknown_types() const;
  [[nodiscard]] TapCounters counters() const;

 private:
  struct Reading;      // one topic's reader and what the thread knows of it (station_tap.cc)
  struct ThreadState;  // the readers and the waitset: the tap thread's alone once it runs
  StationTap(const dds::Participant& participant, TapOptions options);
  void run() noexcept;
  void follow_writers(const std::vector<dds::WatchedWriter>& writers);
  // `wire_name`: the ROS name as on the wire (without the station's name).
  void add_topic(const std::string& wire_name, const msgs::TypeInfo& type,
                 std::vector<dds::OfferedQos> offered);
  void update_topic(Reading& reading, std::vector<dds::OfferedQos> offered);
  void publish(const std::shared_ptr<const TapTopic>& topic, TapEvent::Kind kind);
  void take_all();
  // Closes every consumer's queue, once (the thread's end and the destructor both call it).
  void close_queues();

  const dds::Participant* participant_;
  TapOptions options_;
  std::unique_ptr<ThreadState> state_;
  std::unique_ptr<dds::WriterWatch> watch_;
  std::atomic<bool> writers_changed_{true};
  std::atomic<bool> stop_{false};

  mutable std::mutex mutex_;                  // guards what consumers and the thread share:
  std::condition_variable consumer_arrived_;  // the first queue, or stop_: the thread takes only then
  std::vector<std::shared_ptr<TapQueue>> queues_;
  std::map<std::string, std::shared_ptr<const TapTopic>> topics_;
  std::set<std::string> written_;
  std::set<std::string> unknown_;
  TapCounters counters_;
  bool queues_closed_ = false;

  std::thread thread_;  // last: started when everything else is in place, joined first
};

}  // namespace hubrt::hubctl
