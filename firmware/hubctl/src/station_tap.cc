#include "station_tap.h"

#include <array>
#include <optional>

#include <fmt/format.h>

#include "hubrt/dds/read_condition.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/ros_names.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/waitset.h"
#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/definitions.h"

namespace hubrt::hubctl {
namespace {

// Samples taken from one reader before the next reader's turn: a flooded topic cannot starve the
// others of the tap's attention.
constexpr int kTakesPerTurn = 256;
// The longest the thread sleeps without news: how soon it sees stop().
constexpr auto kWaitBound = std::chrono::milliseconds(200);
// How often the thread looks at the domain's writers while it waits for its first consumer.
constexpr auto kConsumerPoll = std::chrono::milliseconds(20);

WallTime wall_now() noexcept {
  return WallTime{std::chrono::duration_cast<std::chrono::nanoseconds>(
                      std::chrono::system_clock::now().time_since_epoch())
                      .count()};
}

// What the tap's reader asks for so that every writer matches it, as rosbag2 adapts its
// subscription to the offers (rosbag2_storage/qos.cpp, adapt_request_to_offers): reliable only if
// every writer offers it, transient-local only if every writer does (then it gets their history).
struct ReaderChoice {
  bool reliable = true;
  bool transient_local = false;
  bool operator==(const ReaderChoice&) const = default;
};

ReaderChoice choose_reader(const std::vector<dds::OfferedQos>& offered) {
  ReaderChoice choice;
  choice.transient_local = !offered.empty();
  for (const dds::OfferedQos& qos : offered) {
    choice.reliable = choice.reliable && qos.reliability == dds::OfferedQos::Reliability::kReliable;
    choice.transient_local =
        choice.transient_local && qos.durability != dds::OfferedQos::Durability::kVolatile;
  }
  return choice;
}

}  // namespace

struct StationTap::Reading {
  std::string wire_name;  // the ROS name on the wire (topic->ros_name may carry the station's)
  std::shared_ptr<const TapTopic> topic;
  std::optional<dds::UntypedTopic> dds_topic;
  std::optional<dds::UntypedReader> reader;
  std::optional<dds::ReadCondition> condition;
  ReaderChoice choice;
  bool has_writers = false;
  std::uint64_t sequence = 0;
};

struct StationTap::ThreadState {
  std::optional<dds::WaitSet> waitset;
  std::vector<std::unique_ptr<Reading>> readings;  // index = topic id = waitset token
  std::map<std::string, std::size_t, std::less<>> by_name;
  std::map<const msgs::TypeInfo*, std::string> schemas;
  std::vector<std::uint8_t> buffer;
};

StationTap::StationTap(const dds::Participant& participant, TapOptions options)
    : participant_(&participant), options_(std::move(options)), state_(std::make_unique<ThreadState>()) {}

Expected<std::unique_ptr<StationTap>> StationTap::start(const dds::Participant& participant,
                                                        TapOptions options) {
  std::unique_ptr<StationTap> tap(new StationTap(participant, std::move(options)));
  auto waitset = dds::WaitSet::create(participant);
  if (!waitset) return std::move(waitset).error();
  tap->state_->waitset.emplace(std::move(*waitset));
  for (const auto& [name, type] : tap->options_.fixed) tap->add_topic(name, *type, {});
  StationTap* self = tap.get();
  // Called on Cyclone's threads: only note the change and wake the tap's thread.
  auto watch = dds::WriterWatch::start(
      participant, [](std::string_view dds_name) { return dds_name.starts_with("rt/"); },
      [self](const std::vector<dds::WatchedWriter>&) {
        self->writers_changed_ = true;
        (void)self->state_->waitset->wake();
      });
  if (!watch) return std::move(watch).error();
  tap->watch_ = std::move(*watch);
  tap->thread_ = std::thread([self] { self->run(); });
  return tap;
}

StationTap::~StationTap() {
  {
    const std::lock_guard lock(mutex_);  // so that the thread cannot miss it between test and wait
    stop_ = true;
  }
  consumer_arrived_.notify_all();
  if (state_->waitset) (void)state_->waitset->wake();
  if (thread_.joinable()) thread_.join();
  watch_.reset();  // no callback after this (WriterWatch's destructor waits for them)
  close_queues();
}

void StationTap::close_queues() {
  const std::lock_guard lock(mutex_);
  if (queues_closed_) return;  // once: a queue fed by several taps counts each one's close
  queues_closed_ = true;
  for (const auto& queue : queues_) queue->close();
}

std::unique_ptr<TapSubscription> StationTap::subscribe(std::size_t sample_capacity) {
  auto queue = std::make_shared<TapQueue>(sample_capacity);
  feed(queue);
  return std::make_unique<TapSubscription>(std::move(queue));
}

void StationTap::feed(std::shared_ptr<TapQueue> queue) {
  const std::lock_guard lock(mutex_);
  for (const auto& [name, topic] : topics_) queue->push({TapEvent::Kind::kTopic, topic, nullptr});
  if (queues_closed_) {
    queue->close();  // the tap has ended: nothing more will come from it
    return;
  }
  queues_.push_back(std::move(queue));
  consumer_arrived_.notify_all();
}

std::vector<std::shared_ptr<const TapTopic>> StationTap::topics() const {
  const std::lock_guard lock(mutex_);
  std::vector<std::shared_ptr<const TapTopic>> out;
  for (const auto& [name, topic] : topics_) out.push_back(topic);
  return out;
}

std::vector<std::string> StationTap::written_topics() const {
  const std::lock_guard lock(mutex_);
  return {written_.begin(), written_.end()};
}

std::vector<std::string> StationTap::unknown_types() const {
  const std::lock_guard lock(mutex_);
  return {unknown_.begin(), unknown_.end()};
}

TapCounters StationTap::counters() const {
  const std::lock_guard lock(mutex_);
  return counters_;
}

void StationTap::publish(const std::shared_ptr<const TapTopic>& topic, TapEvent::Kind kind) {
  const std::lock_guard lock(mutex_);
  if (kind == TapEvent::Kind::kTopic) {
    if (topics_.count(topic->ros_name) == 0) ++counters_.topics;
    topics_[topic->ros_name] = topic;
  }
  for (const auto& queue : queues_) queue->push({kind, topic, nullptr});
}

void StationTap::add_topic(const std::string& wire_name, const msgs::TypeInfo& type,
                           std::vector<dds::OfferedQos> offered) {
  ThreadState& s = *state_;
  if (s.by_name.count(wire_name) != 0 || type.descriptor == nullptr) return;
  auto schema = s.schemas.find(&type);
  if (schema == s.schemas.end()) {
    // A type without a .msg definition still gets taken (echo, watch); a recorder says it cannot
    // write it without a schema.
    auto text = msgs::ros2msg_schema(type.ros_name);
    schema = s.schemas.emplace(&type, text ? std::move(*text) : std::string()).first;
  }
  auto reading = std::make_unique<Reading>();
  reading->wire_name = wire_name;
  auto topic = std::make_shared<TapTopic>();
  topic->id = options_.first_topic_id + static_cast<std::uint32_t>(s.readings.size());
  topic->ros_name = options_.station.empty() ? wire_name : "/" + options_.station + wire_name;
  topic->station = options_.station;
  topic->domain_id = participant_->domain_id();
  topic->type = &type;
  topic->type_name = std::string(type.ros_name);
  topic->schema = schema->second;
  topic->offered = std::move(offered);
  reading->topic = topic;
  reading->has_writers = !topic->offered.empty();
  s.by_name.emplace(wire_name, s.readings.size());
  s.readings.push_back(std::move(reading));
  update_topic(*s.readings.back(), topic->offered);
  publish(s.readings.back()->topic, TapEvent::Kind::kTopic);
}

// Makes (or makes again, when the writers now need another QoS) the topic's reader.
void StationTap::update_topic(Reading& reading, std::vector<dds::OfferedQos> offered) {
  const ReaderChoice choice = choose_reader(offered);
  const TapTopic& topic = *reading.topic;
  if (offered != topic.offered) {
    auto revised = std::make_shared<TapTopic>(topic);
    revised->offered = std::move(offered);
    ++revised->revision;
    reading.topic = revised;
  }
  if (reading.reader && choice == reading.choice) return;
  if (reading.condition) (void)state_->waitset->detach(*reading.condition);
  reading.condition.reset();
  reading.reader.reset();
  if (!reading.dds_topic) {
    auto created = dds::UntypedTopic::create(*participant_, *topic.type->descriptor, reading.wire_name);
    if (!created) return;  // a name Cyclone refuses: nothing to take
    reading.dds_topic.emplace(std::move(*created));
  }
  dds::Qos qos;
  if (choice.reliable) {
    qos.reliable();
  } else {
    qos.best_effort();
  }
  if (choice.transient_local) {
    qos.transient_local();
  } else {
    qos.volatile_durability();
  }
  qos.keep_last(options_.reader_depth);
  auto reader = dds::UntypedReader::create(*participant_, *reading.dds_topic, qos);
  if (!reader) return;
  reading.reader.emplace(std::move(*reader));
  auto condition = dds::ReadCondition::create(*reading.reader);
  if (condition && state_->waitset->attach(*condition, reading.topic->id - options_.first_topic_id))
    reading.condition.emplace(std::move(*condition));
  reading.choice = choice;
}

void StationTap::follow_writers(const std::vector<dds::WatchedWriter>& writers) {
  ThreadState& s = *state_;
  std::map<std::string, std::vector<const dds::WatchedWriter*>> by_topic;
  for (const dds::WatchedWriter& writer : writers) {
    if (auto ros = dds::dds_to_ros_topic(writer.topic_name)) by_topic[*ros].push_back(&writer);
  }
  {
    const std::lock_guard lock(mutex_);
    for (const auto& [ros, list] : by_topic) written_.insert(ros);
  }
  for (const auto& [ros, list] : by_topic) {
    const msgs::TypeInfo* type = msgs::all_types().find_by_dds_name(list.front()->type_name);
    if (type == nullptr) {
      const std::lock_guard lock(mutex_);
      unknown_.insert(fmt::format("{} ({})", ros, list.front()->type_name));
      continue;
    }
    std::vector<dds::OfferedQos> offered;
    for (const dds::WatchedWriter* writer : list) {
      if (writer->type_name == list.front()->type_name) offered.push_back(writer->qos);
    }
    if (s.by_name.count(ros) == 0) {
      if (options_.filter(ros, *type)) add_topic(ros, *type, std::move(offered));
      continue;
    }
    Reading& reading = *s.readings[s.by_name.at(ros)];
    const std::uint32_t revision = reading.topic->revision;
    update_topic(reading, std::move(offered));
    if (!reading.has_writers || reading.topic->revision != revision)
      publish(reading.topic, TapEvent::Kind::kTopic);
    reading.has_writers = true;
  }
  for (const auto& reading : s.readings) {
    if (reading->has_writers && by_topic.count(reading->wire_name) == 0) {
      reading->has_writers = false;
      publish(reading->topic, TapEvent::Kind::kTopicGone);
    }
  }
}

void StationTap::take_all() {
  ThreadState& s = *state_;
  for (const auto& reading : s.readings) {
    if (!reading->reader) continue;
    for (int n = 0; n < kTakesPerTurn; ++n) {
      dds::SampleInfo info;
      const Result<bool> taken = reading->reader->take_serialized(s.buffer, &info);
      if (!taken.is_ok() || !taken.value()) break;
      auto sample = std::make_shared<TapSample>();
      sample->topic = reading->topic;
      sample->receive_time = wall_now();
      sample->source_time = info.source_time;
      sample->sequence = ++reading->sequence;
      sample->cdr = s.buffer;
      const std::shared_ptr<const TapSample> shared = std::move(sample);
      const std::lock_guard lock(mutex_);
      ++counters_.samples;
      counters_.bytes += shared->cdr.size();
      for (const auto& queue : queues_) queue->push({TapEvent::Kind::kSample, shared->topic, shared});
    }
  }
}

void StationTap::run() noexcept {
  std::array<dds::WaitSet::Token, 64> fired{};
  try {
    while (!stop_) {
      if (writers_changed_.exchange(false)) follow_writers(watch_->current());
      {
        // Consumers subscribe after start(): a sample taken before the first did would be lost
        // (hubctl echo missed a fault written the moment its reader matched). Until one is there,
        // the readers keep what comes (reader_depth); the waitset would only spin on their data.
        std::unique_lock lock(mutex_);
        if (queues_.empty()) {
          consumer_arrived_.wait_for(lock, kConsumerPoll, [this] { return stop_ || !queues_.empty(); });
          continue;
        }
      }
      (void)state_->waitset->wait(fired, kWaitBound);
      take_all();
    }
  } catch (const std::exception&) {
    // Out of memory: the tap ends; its consumers see their queue close.
  }
  close_queues();
}

}  // namespace hubrt::hubctl
