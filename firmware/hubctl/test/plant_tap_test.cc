// The tap over several stations' domains (plant_tap.h), each station in a domain of its own from a
// TestDomainRange: the same topic in two stations must reach a consumer as two topics, each under
// its station's name with its own id and domain, every sample under the right one; a station
// that has no such topic shows nothing; the consumer's queue ends only when every station's tap
// has ended; one unnamed station keeps the plain names.
#include "plant_tap.h"

#include <map>
#include <set>

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
constexpr auto kPlantTapPatience = std::chrono::seconds(30);

class PlantTapTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto range = test_support::TestDomainRange::acquire(3);
    ASSERT_TRUE(range) << range.error().message;
    range_.emplace(std::move(*range));
    type_ = msgs::all_types().find("hub_msgs/msg/DockCommand");
    ASSERT_NE(type_, nullptr);
  }

  dds::Participant join(std::size_t station, const char* name) {
    auto participant = dds::Participant::create(range_->at(station).config(), name);
    EXPECT_TRUE(participant) << participant.error().message;
    return std::move(*participant);
  }

  // A writer of /dock/command in `participant`'s domain whose action says which station it is.
  struct Station {
    dds::UntypedTopic topic;
    dds::UntypedWriter writer;
  };
  std::optional<Station> station_writer(const dds::Participant& participant) {
    auto topic = dds::UntypedTopic::create(participant, *type_->descriptor, "/dock/command");
    if (!topic) return std::nullopt;
    auto writer = dds::UntypedWriter::create(participant, *topic, dds::Qos::ros2_default(100));
    if (!writer) return std::nullopt;
    return Station{std::move(*topic), std::move(*writer)};
  }

  dds::UntypedSample command(const std::string& action) const {
    dds::UntypedSample sample(*type_->descriptor);
    const nlohmann::ordered_json value = {
        {"target_type", "dock"}, {"target_name", "dock"}, {"action", action}};
    EXPECT_TRUE(msgs::from_json(*type_, value, sample.data()));
    return sample;
  }

  std::optional<test_support::TestDomainRange> range_;
  const msgs::TypeInfo* type_ = nullptr;
};

TEST_F(PlantTapTest, EachStationsTopicsComeUnderItsNameWithItsOwnIdAndDomain) {
  std::vector<PlantMember> members;
  members.push_back({"cell_a", join(0, "tool")});
  members.push_back({"cell_b", join(1, "tool")});
  members.push_back({"cell_c", join(2, "tool")});  // a station with no such topic
  auto tap = PlantTap::start(members, TapOptions{});
  ASSERT_TRUE(tap) << tap.error().message;
  auto source = (*tap)->subscribe(1000);
  dds::Participant hub_a = join(0, "hub_a");
  dds::Participant hub_b = join(1, "hub_b");
  auto a = station_writer(hub_a);
  auto b = station_writer(hub_b);
  ASSERT_TRUE(a && b);

  // What each station writes, as the bytes the tap must hand out.
  auto codec = dds::CdrCodec::create(hub_a, *type_->descriptor);
  ASSERT_TRUE(codec);
  const dds::UntypedSample from_a = command("from_a");
  const dds::UntypedSample from_b = command("from_b");
  const std::map<std::vector<std::uint8_t>, std::string> action_of = {
      {*codec->encode(from_a.data()), "from_a"}, {*codec->encode(from_b.data()), "from_b"}};
  std::map<std::string, std::shared_ptr<const TapTopic>> topics;
  std::map<std::string, std::set<std::string>> actions;  // per topic name
  bool written = false;
  const auto deadline = std::chrono::steady_clock::now() + kPlantTapPatience;
  while (std::chrono::steady_clock::now() < deadline &&
         (actions["/cell_a/dock/command"].size() < 1 || actions["/cell_b/dock/command"].size() < 1)) {
    if (!written && topics.size() == 2 && a->writer.wait_for_readers(1, kPlantTapPatience) &&
        b->writer.wait_for_readers(1, kPlantTapPatience)) {
      ASSERT_TRUE(a->writer.write(from_a.data()).is_ok());
      ASSERT_TRUE(b->writer.write(from_b.data()).is_ok());
      written = true;
    }
    auto event = source->next(std::chrono::milliseconds(50));
    if (!event) continue;
    if (event->kind == TapEvent::Kind::kTopic) topics[event->topic->ros_name] = event->topic;
    if (event->kind == TapEvent::Kind::kSample) {
      const auto known = action_of.find(event->sample->cdr);
      actions[event->topic->ros_name].insert(known == action_of.end() ? "unknown bytes" : known->second);
    }
  }
  ASSERT_EQ(topics.size(), 2U) << "the topics of cell_a and cell_b, nothing of cell_c";
  const TapTopic& ta = *topics.at("/cell_a/dock/command");
  const TapTopic& tb = *topics.at("/cell_b/dock/command");
  EXPECT_EQ(ta.station, "cell_a");
  EXPECT_EQ(tb.station, "cell_b");
  EXPECT_EQ(ta.domain_id, range_->at(0).domain_id());
  EXPECT_EQ(tb.domain_id, range_->at(1).domain_id());
  EXPECT_NE(ta.id, tb.id);
  EXPECT_EQ(ta.id / PlantTap::kTopicIdsPerStation, 0U);
  EXPECT_EQ(tb.id / PlantTap::kTopicIdsPerStation, 1U);
  // Every sample under the station it was written in.
  EXPECT_EQ(actions["/cell_a/dock/command"], std::set<std::string>{"from_a"});
  EXPECT_EQ(actions["/cell_b/dock/command"], std::set<std::string>{"from_b"});
  const auto written_topics = (*tap)->written_topics();
  EXPECT_NE(std::find(written_topics.begin(), written_topics.end(), "/cell_b/dock/command"),
            written_topics.end());
  EXPECT_EQ((*tap)->counters().topics, 2U);

  // The queue ends only when every station's tap has: once the plant tap is gone.
  EXPECT_FALSE(source->finished());
  tap->reset();
  while (source->next(std::chrono::milliseconds(0))) {
  }
  EXPECT_TRUE(source->finished());
}

TEST_F(PlantTapTest, OneUnnamedStationKeepsThePlainNames) {
  std::vector<PlantMember> members;
  members.push_back({"", join(0, "tool")});
  auto tap = PlantTap::start(members, TapOptions{});
  ASSERT_TRUE(tap) << tap.error().message;
  auto source = (*tap)->subscribe(100);
  dds::Participant hub = join(0, "hub");
  auto station = station_writer(hub);
  ASSERT_TRUE(station);
  const auto deadline = std::chrono::steady_clock::now() + kPlantTapPatience;
  std::shared_ptr<const TapTopic> seen;
  while (!seen && std::chrono::steady_clock::now() < deadline) {
    auto event = source->next(std::chrono::milliseconds(50));
    if (event && event->kind == TapEvent::Kind::kTopic) seen = event->topic;
  }
  ASSERT_TRUE(seen);
  EXPECT_EQ(seen->ros_name, "/dock/command");
  EXPECT_EQ(seen->station, "");
  EXPECT_EQ(seen->id, 0U);
}

TEST(TapQueueProducers, ClosesOnlyWhenEveryProducerHas) {
  TapQueue queue(10);
  queue.add_producer();
  queue.close();
  EXPECT_FALSE(queue.closed_and_empty());
  queue.push({TapEvent::Kind::kTopic, std::make_shared<TapTopic>(), nullptr});
  queue.close();
  EXPECT_FALSE(queue.closed_and_empty()) << "one event still to take";
  EXPECT_TRUE(queue.pop(std::chrono::milliseconds(0)));
  EXPECT_TRUE(queue.closed_and_empty());
  queue.push({TapEvent::Kind::kTopic, std::make_shared<TapTopic>(), nullptr});
  EXPECT_TRUE(queue.closed_and_empty()) << "nothing is pushed after the last close";
}

}  // namespace
}  // namespace hubrt::hubctl
