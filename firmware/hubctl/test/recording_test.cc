// The recording side of the tap, without a domain: a consumer's queue bounds samples but never
// topics; the offered QoS in rosbag2's YAML and back; what the recorder writes (a schema per
// type, a channel per topic with its QoS, the times) read back as a tap by RecordingSource, with
// --start/--end, a topic filter and the recorded pace.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "hubrt/mcap/linear_reader.h"
#include "hubrt/mcap/summary.h"
#include "hubrt/msgs/all_types.h"

#include "recorder.h"
#include "recording_source.h"
#include "ros2_qos_yaml.h"
#include "tap.h"

namespace hubrt::hubctl {
namespace {

namespace fs = std::filesystem;

TapEvent sample_event(const std::shared_ptr<const TapTopic>& topic, std::uint64_t seq, std::int64_t t_ns) {
  auto sample = std::make_shared<TapSample>();
  sample->topic = topic;
  sample->receive_time = WallTime{t_ns};
  sample->source_time = WallTime{t_ns - 1000};
  sample->sequence = seq;
  sample->cdr = {0, 1, 0, 0, static_cast<std::uint8_t>(seq), 0, 0, 0};
  return {TapEvent::Kind::kSample, topic, std::move(sample)};
}

TEST(TapQueue, DropsSamplesBeyondItsCapacityButNeverATopicAndNeverWaits) {
  TapQueue queue(2);
  auto topic = std::make_shared<const TapTopic>();
  for (std::uint64_t n = 1; n <= 5; ++n) queue.push(sample_event(topic, n, 10));
  queue.push({TapEvent::Kind::kTopic, topic, nullptr});
  EXPECT_EQ(queue.dropped(), 3U);
  EXPECT_EQ(queue.pop(Duration::zero())->sample->sequence, 1U);
  EXPECT_EQ(queue.pop(Duration::zero())->sample->sequence, 2U);
  EXPECT_EQ(queue.pop(Duration::zero())->kind, TapEvent::Kind::kTopic);
  EXPECT_FALSE(queue.pop(Duration::zero()));
  EXPECT_FALSE(queue.closed_and_empty());
  queue.push(sample_event(topic, 6, 10));  // room again
  queue.close();
  queue.push(sample_event(topic, 7, 10));  // after close: not taken
  EXPECT_EQ(queue.pop(std::chrono::seconds(5))->sample->sequence, 6U);
  // Closed and empty: no waiting.
  const auto before = std::chrono::steady_clock::now();
  EXPECT_FALSE(queue.pop(std::chrono::seconds(30)));
  EXPECT_LT(std::chrono::steady_clock::now() - before, std::chrono::seconds(10));
  EXPECT_TRUE(queue.closed_and_empty());
}

TEST(Ros2QosYaml, WritesRosbag2sProfilesAndReadsThemBack) {
  const dds::OfferedQos ros2_default = dds::read_offered_qos(dds::Qos::ros2_default().get());
  // What rosbag2 (metadata version 9+) writes for a default ROS 2 publisher on Cyclone.
  EXPECT_EQ(offered_qos_yaml({ros2_default}),
            "- history: keep_last\n  depth: 10\n  reliability: reliable\n  durability: volatile\n"
            "  deadline:\n    sec: 9223372036\n    nsec: 854775807\n"
            "  lifespan:\n    sec: 9223372036\n    nsec: 854775807\n  liveliness: automatic\n"
            "  liveliness_lease_duration:\n    sec: 9223372036\n    nsec: 854775807\n"
            "  avoid_ros_namespace_conventions: false\n");
  EXPECT_EQ(offered_qos_yaml({}), "[]\n");
  dds::OfferedQos other;
  other.reliability = dds::OfferedQos::Reliability::kBestEffort;
  other.durability = dds::OfferedQos::Durability::kTransientLocal;
  other.depth = 3;
  other.deadline = std::chrono::milliseconds(1500);
  const auto back = parse_offered_qos_yaml(offered_qos_yaml({ros2_default, other}));
  ASSERT_EQ(back.size(), 2U);
  EXPECT_EQ(back[0].depth, 10);
  EXPECT_EQ(back[1], other);
  // rosbag2 before metadata version 9 wrote the rmw enum values (rosbag2_storage test_qos.cpp).
  const auto old = parse_offered_qos_yaml(
      "- history: 1\n  depth: 10\n  reliability: 2\n  durability: 1\n  deadline:\n    sec: 0\n    nsec: 0\n");
  ASSERT_EQ(old.size(), 1U);
  EXPECT_EQ(old[0].reliability, dds::OfferedQos::Reliability::kBestEffort);
  EXPECT_EQ(old[0].durability, dds::OfferedQos::Durability::kTransientLocal);
  EXPECT_TRUE(parse_offered_qos_yaml("{not: [yaml").empty());
  EXPECT_TRUE(parse_offered_qos_yaml("- &a [*a, *a]\n").empty());
}

class RecorderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("hubrt-recorder-" + std::to_string(getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::shared_ptr<TapTopic> topic(std::uint32_t id, std::string name, std::string type_name) {
    auto t = std::make_shared<TapTopic>();
    t->id = id;
    t->ros_name = std::move(name);
    t->type = msgs::all_types().find(type_name);
    t->type_name = std::move(type_name);
    t->schema = "string text\n";
    return t;
  }

  // 30 samples, 100 ms apart, over two topics of one type and a topic without a schema.
  std::string record(const std::string& name) {
    RecorderOptions options;
    options.path = (dir_ / name).string();
    auto recorder = Recorder::create(options);
    EXPECT_TRUE(recorder) << recorder.error().message;
    auto a = topic(0, "/dock/command", "hub_msgs/msg/DockCommand");
    a->offered = {dds::read_offered_qos(dds::Qos::ros2_default().get())};
    auto b = topic(1, "/rsp/command", "hub_msgs/msg/DockCommand");
    auto nameless = topic(2, "/odd", "hub_msgs/msg/DockState");
    nameless->schema.clear();
    const auto now = std::chrono::steady_clock::now();
    for (std::uint64_t n = 0; n < 30; ++n) {
      const auto& t = n % 3 == 0 ? b : (n % 3 == 1 ? a : nameless);
      EXPECT_TRUE(
          recorder->take(sample_event(t, n + 1, kStart + static_cast<std::int64_t>(n) * 100'000'000), now));
    }
    EXPECT_TRUE(recorder->take({TapEvent::Kind::kTopicGone, a, nullptr}, now));
    EXPECT_TRUE(recorder->finish());
    EXPECT_EQ(recorder->progress().messages, 20U);
    EXPECT_EQ(recorder->progress().topics, 2U);
    EXPECT_EQ(recorder->unrecordable().count("/odd"), 1U);
    return options.path;
  }

  static constexpr std::int64_t kStart = 1'800'000'000'000'000'000;
  fs::path dir_;
};

TEST_F(RecorderTest, WritesTheRos2ProfileASchemaPerTypeAndAChannelPerTopic) {
  const std::string path = record("r.mcap");
  auto source = mcap::open_file(path);
  ASSERT_TRUE(source);
  auto summary = mcap::read_summary(**source);
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_EQ(summary->schemas.size(), 1U);
  EXPECT_EQ(summary->schemas.begin()->second.name, "hub_msgs/msg/DockCommand");
  EXPECT_EQ(summary->schemas.begin()->second.encoding, "ros2msg");
  ASSERT_EQ(summary->channels.size(), 2U);
  for (const auto& [id, channel] : summary->channels) {
    EXPECT_EQ(channel.message_encoding, "cdr");
    const std::string& qos = channel.metadata.at("offered_qos_profiles");
    EXPECT_EQ(qos.starts_with("- history: keep_last"), channel.topic == "/dock/command") << qos;
  }
  auto again = mcap::open_file(path);
  auto reader = mcap::LinearReader::open(std::move(*again));
  ASSERT_TRUE(reader);
  EXPECT_EQ(reader->header().profile, "ros2");
  auto first = reader->next();
  ASSERT_TRUE(first);
  EXPECT_EQ(first->log_time, static_cast<std::uint64_t>(kStart));
  EXPECT_EQ(first->publish_time, static_cast<std::uint64_t>(kStart - 1000));  // the source timestamp
  EXPECT_EQ(first->sequence, 1U);
  EXPECT_EQ(first->data.size(), 8U);
}

TEST_F(RecorderTest, ARecordingReadsBackAsATapWithStartEndAndAFilter) {
  const std::string path = record("r.mcap");
  RecordingOptions options;
  options.start_s = 0.5;
  options.end_s = 2.0;
  options.filter = [](std::string_view topic, const msgs::TypeInfo&) { return topic == "/dock/command"; };
  auto source = RecordingSource::open({path}, options);
  ASSERT_TRUE(source) << source.error().message;
  std::vector<TapEvent> events;
  while (auto event = (*source)->next(Duration::zero())) events.push_back(*event);
  EXPECT_TRUE((*source)->finished());
  EXPECT_TRUE((*source)->problem().empty()) << (*source)->problem();
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.front().kind, TapEvent::Kind::kTopic);
  EXPECT_EQ(events.front().topic->ros_name, "/dock/command");
  EXPECT_EQ(events.front().topic->offered.size(), 1U);  // the recorded QoS, parsed back
  // /dock/command has samples 2, 5, 8, ... at 0.1 s, 0.4 s, 0.7 s, ...: within [0.5, 2.0] those of
  // 0.7 s to 1.9 s, five of them.
  std::vector<std::uint64_t> sequences;
  for (const TapEvent& e : events) {
    if (e.kind == TapEvent::Kind::kSample) sequences.push_back(e.sample->sequence);
  }
  EXPECT_EQ(sequences, (std::vector<std::uint64_t>{8, 11, 14, 17, 20}));
}

TEST_F(RecorderTest, ARecordingPlaysAtItsRecordedPaceTimesTheRate) {
  const std::string path = record("r.mcap");
  RecordingOptions options;
  options.rate = 10;  // 2.9 s of recording in 0.29 s
  auto source = RecordingSource::open({path}, options);
  ASSERT_TRUE(source);
  const auto start = std::chrono::steady_clock::now();
  std::size_t samples = 0;
  while (!(*source)->finished()) {
    if (auto e = (*source)->next(std::chrono::milliseconds(20)); e && e->kind == TapEvent::Kind::kSample)
      ++samples;
  }
  EXPECT_EQ(samples, 20U);
  // Sleeping never ends early: the lower bound holds on any machine (an upper one would not).
  EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(270));
}

TEST_F(RecorderTest, AFileThatIsNotARecordingIsRefusedAndACutOneSaysWhereItStopped) {
  const fs::path text = dir_ / "notes.mcap";
  std::ofstream(text) << "not a recording";
  EXPECT_FALSE(RecordingSource::open({text.string()}, RecordingOptions{}));
  const std::string path = record("r.mcap");
  const auto size = fs::file_size(path);
  fs::resize_file(path, size / 2);
  auto source = RecordingSource::open({path}, RecordingOptions{});
  ASSERT_TRUE(source);
  while ((*source)->next(Duration::zero())) {
  }
  EXPECT_NE((*source)->problem().find("read up to byte"), std::string::npos) << (*source)->problem();
}

}  // namespace
}  // namespace hubrt::hubctl
