// What `hubctl list` sees: topics, types, endpoint counts, participants, local or not.
#include "hubrt/dds/discovery.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"

#include "dds_fixture.h"
#include "test_types_traits.h"

namespace hubrt::dds::test {
namespace {

const TopicSummary* find_topic(const std::vector<TopicSummary>& topics, const std::string& name) {
  const auto it =
      std::find_if(topics.begin(), topics.end(), [&](const TopicSummary& t) { return t.topic_name == name; });
  return it == topics.end() ? nullptr : &*it;
}

TEST_F(DdsTest, SeesAWritersTopicTypeAndParticipant) {
  auto topic = Topic<Ping>::create(participant(), "/hubrt_test/discovered");
  ASSERT_TRUE(topic);
  auto writer = Writer<Ping>::create(participant(), *topic);
  ASSERT_TRUE(writer);

  auto snapshot = discover(participant());
  ASSERT_TRUE(snapshot) << snapshot.error().message;
  const auto topics = snapshot->topics();
  const TopicSummary* t = find_topic(topics, "rt/hubrt_test/discovered");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->type_name, "hubrt_test::msg::dds_::Ping_");
  EXPECT_EQ(t->writers, 1u);
  EXPECT_EQ(t->readers, 0u);
  EXPECT_EQ(t->local_writers, 1u);
  EXPECT_EQ(t->participant_keys, std::vector<Guid>{participant().guid()});

  const auto& ps = snapshot->participants;
  const auto self = std::find_if(
      ps.begin(), ps.end(), [&](const DiscoveredParticipant& p) { return p.key == participant().guid(); });
  ASSERT_NE(self, ps.end());
  EXPECT_EQ(self->name, "dds_test");
  EXPECT_TRUE(self->local);
}

TEST_F(DdsTest, CountsReadersAndWritersAcrossParticipants) {
  auto second = Participant::create(config(), "second");
  ASSERT_TRUE(second);
  auto topic_a = Topic<Counter>::create(participant(), "/hubrt_test/counted");
  auto topic_b = Topic<Counter>::create(*second, "/hubrt_test/counted");
  ASSERT_TRUE(topic_a && topic_b);
  auto writer = Writer<Counter>::create(participant(), *topic_a);
  auto reader_1 = Reader<Counter>::create(*second, *topic_b);
  auto reader_2 = Reader<Counter>::create(*second, *topic_b);
  ASSERT_TRUE(writer && reader_1 && reader_2);

  auto snapshot = discover(participant());
  ASSERT_TRUE(snapshot) << snapshot.error().message;
  const auto topics = snapshot->topics();
  const TopicSummary* t = find_topic(topics, "rt/hubrt_test/counted");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->writers, 1u);
  EXPECT_EQ(t->readers, 2u);
  EXPECT_EQ(t->local_readers, 2u);
  std::vector<Guid> expected{participant().guid(), second->guid()};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(t->participant_keys, expected);
}

TEST_F(DdsTest, DeletedEndpointsDisappear) {
  auto topic = Topic<Counter>::create(participant(), "/hubrt_test/short_lived");
  ASSERT_TRUE(topic);
  {
    auto writer = Writer<Counter>::create(participant(), *topic);
    ASSERT_TRUE(writer);
    auto snapshot = discover(participant());
    ASSERT_TRUE(snapshot);
    ASSERT_NE(find_topic(snapshot->topics(), "rt/hubrt_test/short_lived"), nullptr);
  }
  auto snapshot = discover(participant());
  ASSERT_TRUE(snapshot);
  EXPECT_EQ(find_topic(snapshot->topics(), "rt/hubrt_test/short_lived"), nullptr);
}

TEST(DiscoverySnapshot, SummarisesByTopicAndTypeSorted) {
  DiscoverySnapshot snapshot;
  Guid p1;
  p1.bytes[0] = 1;
  Guid p2;
  p2.bytes[0] = 2;
  const auto endpoint = [](EndpointDirection d, const char* topic, const char* type, Guid participant,
                           bool local) {
    DiscoveredEndpoint e;
    e.direction = d;
    e.topic_name = topic;
    e.type_name = type;
    e.participant_key = participant;
    e.local = local;
    return e;
  };
  snapshot.endpoints = {endpoint(EndpointDirection::kWriter, "rt/b", "T", p2, false),
                        endpoint(EndpointDirection::kReader, "rt/a", "T", p1, true),
                        endpoint(EndpointDirection::kReader, "rt/a", "T", p1, true),
                        endpoint(EndpointDirection::kWriter, "rt/a", "T", p2, false),
                        endpoint(EndpointDirection::kWriter, "rt/a", "U", p2, false)};
  const auto topics = snapshot.topics();
  ASSERT_EQ(topics.size(), 3u);
  EXPECT_EQ(topics[0].topic_name, "rt/a");
  EXPECT_EQ(topics[0].type_name, "T");
  EXPECT_EQ(topics[0].readers, 2u);
  EXPECT_EQ(topics[0].local_readers, 2u);
  EXPECT_EQ(topics[0].writers, 1u);
  EXPECT_EQ(topics[0].local_writers, 0u);
  EXPECT_EQ(topics[0].participant_keys, (std::vector<Guid>{p1, p2}));
  EXPECT_EQ(topics[1].type_name, "U") << "same topic, other type: listed apart";
  EXPECT_EQ(topics[2].topic_name, "rt/b");
}

TEST(GuidText, FourGroupsOfEightHexDigits) {
  Guid g;
  for (std::size_t i = 0; i < g.bytes.size(); ++i) g.bytes[i] = static_cast<std::uint8_t>(i * 17);
  EXPECT_EQ(g.to_string(), "00112233:44556677:8899aabb:ccddeeff");
}

}  // namespace
}  // namespace hubrt::dds::test
