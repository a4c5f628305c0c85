// The live tap on a private loopback domain: a topic that appears after it started is taken, with
// its writer's QoS; each sample arrives as Cyclone's bytes of what was written, with its times and
// a count; a consumer that never reads loses its own samples and holds up nobody; a topic whose
// writer goes is said to be gone; the default selection is the station's traffic.
#include "station_tap.h"

#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/cdr_codec.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/json.h"
#include "hubrt/test_support/test_domain.h"

namespace hubrt::hubctl {
namespace {

// Discovery and delivery take milliseconds; generous for sanitizer builds on a loaded machine.
constexpr auto kStationTapPatience = std::chrono::seconds(30);

class StationTapTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto tapping = dds::Participant::create(domain_->config(), "tap");
    auto station = dds::Participant::create(domain_->config(), "station");
    ASSERT_TRUE(tapping && station);
    tapping_.emplace(std::move(*tapping));
    station_.emplace(std::move(*station));
    command_type_ = msgs::all_types().find("hub_msgs/msg/DockCommand");
    ASSERT_NE(command_type_, nullptr);
  }

  // The next event of `kind` on `topic`, skipping others; nullopt after kStationTapPatience.
  static std::optional<TapEvent> next_of(TapSource& source, TapEvent::Kind kind, const std::string& topic) {
    const auto deadline = std::chrono::steady_clock::now() + kStationTapPatience;
    while (std::chrono::steady_clock::now() < deadline) {
      auto event = source.next(std::chrono::milliseconds(50));
      if (event && event->kind == kind && event->topic->ros_name == topic) return event;
    }
    return std::nullopt;
  }

  dds::UntypedSample command(const std::string& action) const {
    dds::UntypedSample sample(*command_type_->descriptor);
    const nlohmann::ordered_json value = {
        {"target_type", "dock"}, {"target_name", "dock"}, {"action", action}};
    EXPECT_TRUE(msgs::from_json(*command_type_, value, sample.data()));
    return sample;
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> tapping_;
  std::optional<dds::Participant> station_;
  const msgs::TypeInfo* command_type_ = nullptr;
};

TEST_F(StationTapTest, ATopicThatAppearsLaterIsTakenAsTheBytesThatWereWritten) {
  auto tap = StationTap::start(*tapping_, TapOptions{});
  ASSERT_TRUE(tap) << tap.error().message;
  auto source = (*tap)->subscribe(1000);
  // The writer comes after the tap started, and offers what a recording must keep.
  auto topic = dds::UntypedTopic::create(*station_, *command_type_->descriptor, "/dock/command");
  ASSERT_TRUE(topic);
  auto writer = dds::UntypedWriter::create(*station_, *topic, dds::Qos::sensor_data(7));
  ASSERT_TRUE(writer);
  auto announced = next_of(*source, TapEvent::Kind::kTopic, "/dock/command");
  ASSERT_TRUE(announced);
  EXPECT_EQ(announced->topic->type, command_type_);
  EXPECT_EQ(announced->topic->type_name, "hub_msgs/msg/DockCommand");
  EXPECT_NE(announced->topic->schema.find("string<=64 action"), std::string::npos)
      << announced->topic->schema;
  ASSERT_EQ(announced->topic->offered.size(), 1U);
  EXPECT_EQ(announced->topic->offered[0].reliability, dds::OfferedQos::Reliability::kBestEffort);
  EXPECT_EQ(announced->topic->offered[0].depth, 7);

  // Best effort: the tap's reader matches it only if it asked for best effort too.
  ASSERT_TRUE(writer->wait_for_readers(1, kStationTapPatience));
  auto codec = dds::CdrCodec::create(*station_, *command_type_->descriptor);
  ASSERT_TRUE(codec);
  const dds::UntypedSample sent = command("monitor");
  const auto expected = codec->encode(sent.data());
  ASSERT_TRUE(expected);
  for (int n = 0; n < 5; ++n) ASSERT_TRUE(writer->write(sent.data()).is_ok());
  for (std::uint64_t n = 1; n <= 5; ++n) {
    auto event = next_of(*source, TapEvent::Kind::kSample, "/dock/command");
    ASSERT_TRUE(event) << "sample " << n;
    EXPECT_EQ(event->sample->cdr, *expected);
    EXPECT_EQ(event->sample->sequence, n);
    EXPECT_GT(event->sample->source_time.ns_since_epoch, 0);
    // Taken after it was written (both this machine's wall clock; 1 s of slack for its steps).
    EXPECT_GE(event->sample->receive_time.ns_since_epoch,
              event->sample->source_time.ns_since_epoch - 1'000'000'000);
  }
  const TapCounters counters = (*tap)->counters();
  EXPECT_EQ(counters.samples, 5U);
  EXPECT_EQ(counters.topics, 1U);

  // The writer goes: the topic is gone (and its last revision is what was announced).
  writer = make_error(ErrorCode::kInternal, "deleted");
  EXPECT_TRUE(next_of(*source, TapEvent::Kind::kTopicGone, "/dock/command"));
}

// hubctl echo starts the tap and then subscribes: a sample written the moment the tap's reader
// matched (as `hubctl send --wait` does) came in between, and the tap's thread took it for nobody.
TEST_F(StationTapTest, SamplesThatCameBeforeTheFirstConsumerWaitForIt) {
  TapOptions options;
  options.filter = [](std::string_view, const msgs::TypeInfo&) { return false; };
  options.fixed.emplace_back("/dock/command", command_type_);
  auto tap = StationTap::start(*tapping_, std::move(options));
  ASSERT_TRUE(tap) << tap.error().message;
  auto topic = dds::UntypedTopic::create(*station_, *command_type_->descriptor, "/dock/command");
  auto writer = dds::UntypedWriter::create(*station_, *topic, dds::Qos::ros2_default(10));
  ASSERT_TRUE(topic && writer);
  ASSERT_TRUE(writer->wait_for_readers(1, kStationTapPatience));
  const dds::UntypedSample sent = command("monitor");
  for (int n = 0; n < 3; ++n) ASSERT_TRUE(writer->write(sent.data()).is_ok());
  // Acknowledged: in the tap's reader. Then longer than the tap's thread takes to wake on it.
  ASSERT_TRUE(writer->wait_for_acks(kStationTapPatience));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  auto source = (*tap)->subscribe(1000);
  for (std::uint64_t n = 1; n <= 3; ++n) {
    auto event = next_of(*source, TapEvent::Kind::kSample, "/dock/command");
    ASSERT_TRUE(event) << "sample " << n << " was taken before anyone subscribed";
    EXPECT_EQ(event->sample->sequence, n);
  }
}

TEST_F(StationTapTest, AConsumerThatDoesNotReadLosesItsOwnSamplesAndHoldsUpNobody) {
  auto tap = StationTap::start(*tapping_, TapOptions{});
  ASSERT_TRUE(tap);
  auto stalled = (*tap)->subscribe(3);  // never read while the samples come
  auto reading = (*tap)->subscribe(1000);
  auto topic = dds::UntypedTopic::create(*station_, *command_type_->descriptor, "/dock/command");
  auto writer = dds::UntypedWriter::create(*station_, *topic, dds::Qos::ros2_default(100));
  ASSERT_TRUE(topic && writer);
  ASSERT_TRUE(next_of(*reading, TapEvent::Kind::kTopic, "/dock/command"));
  ASSERT_TRUE(writer->wait_for_readers(1, kStationTapPatience));
  const dds::UntypedSample sent = command("monitor");
  for (int n = 0; n < 50; ++n) ASSERT_TRUE(writer->write(sent.data()).is_ok());
  for (int n = 1; n <= 50; ++n) ASSERT_TRUE(next_of(*reading, TapEvent::Kind::kSample, "/dock/command")) << n;
  EXPECT_EQ(reading->dropped(), 0U);
  EXPECT_EQ(stalled->dropped(), 47U);
  std::size_t samples = 0;
  while (auto event = stalled->next(Duration::zero()))
    samples += event->kind == TapEvent::Kind::kSample ? 1 : 0;
  EXPECT_EQ(samples, 3U);
}

TEST_F(StationTapTest, TheDefaultSelectionIsTheStationsTraffic) {
  auto tap = StationTap::start(*tapping_, TapOptions{});
  ASSERT_TRUE(tap);
  auto source = (*tap)->subscribe(1000);
  const msgs::TypeInfo* instruction = msgs::all_types().find("hub_msgs/msg/OperatorInstruction");
  const msgs::TypeInfo* state = msgs::all_types().find("hub_msgs/msg/DockState");
  ASSERT_TRUE(instruction && state);
  auto other_topic = dds::UntypedTopic::create(*station_, *instruction->descriptor, "/operator/instruction");
  auto other = dds::UntypedWriter::create(*station_, *other_topic);
  auto state_topic = dds::UntypedTopic::create(*station_, *state->descriptor, "/dock_ecu/dock/state");
  auto states = dds::UntypedWriter::create(*station_, *state_topic);
  ASSERT_TRUE(other && states);
  ASSERT_TRUE(next_of(*source, TapEvent::Kind::kTopic, "/dock_ecu/dock/state"));
  const auto written = (*tap)->written_topics();
  EXPECT_NE(std::find(written.begin(), written.end(), "/operator/instruction"), written.end());
  for (const auto& topic : (*tap)->topics()) EXPECT_NE(topic->ros_name, "/operator/instruction");
}

}  // namespace
}  // namespace hubrt::hubctl
