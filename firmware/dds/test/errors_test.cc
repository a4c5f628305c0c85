// Failures come back as values that say what was being done, where, and what Cyclone said.
#include <string>

#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"

#include "dds_fixture.h"
#include "test_types_traits.h"

namespace hubrt::dds::test {
namespace {

::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

TEST_F(DdsTest, InvalidRosTopicNameIsRejectedBeforeCyclone) {
  auto topic = Topic<Ping>::create(participant(), "dock/command");
  ASSERT_FALSE(topic);
  EXPECT_EQ(topic.error().code, ErrorCode::kInvalidArgument);
  EXPECT_TRUE(contains(topic.error().message, "'dock/command' must start with '/'"));
}

TEST_F(DdsTest, CycloneRefusalNamesTopicTypeDomainAndCode) {
  auto topic = Topic<Ping>::create_with_dds_name(participant(), "rt/bad name");
  ASSERT_FALSE(topic);
  EXPECT_EQ(topic.error().code, ErrorCode::kInvalidArgument);
  const std::string& m = topic.error().message;
  EXPECT_TRUE(contains(m, "create topic 'rt/bad name' of type 'hubrt_test::msg::dds_::Ping_' in domain " +
                              std::to_string(domain_->domain_id())));
  EXPECT_TRUE(contains(m, "DDS_RETCODE_BAD_PARAMETER (Bad Parameter)"));
}

TEST_F(DdsTest, CreatingOnADeletedParticipantSaysWhatAndWhere) {
  auto topic = Topic<Ping>::create(participant(), "/dock/command");
  ASSERT_TRUE(topic) << topic.error().message;
  // Delete the participant behind the wrapper's back, as a bug elsewhere could.
  ASSERT_EQ(dds_delete(participant().handle()), DDS_RETCODE_OK);
  auto reader = Reader<Ping>::create(participant(), *topic);
  ASSERT_FALSE(reader);
  EXPECT_EQ(reader.error().code, ErrorCode::kInvalidArgument);
  EXPECT_TRUE(contains(reader.error().message, "create reader on 'rt/dock/command' in domain " +
                                                   std::to_string(domain_->domain_id()) +
                                                   ": DDS_RETCODE_BAD_PARAMETER"));
  auto writer = Writer<Ping>::create(participant(), *topic);
  ASSERT_FALSE(writer);
  EXPECT_TRUE(contains(writer.error().message, "create writer on 'rt/dock/command'"));
  auto again = Topic<Ping>::create(participant(), "/dock/state");
  ASSERT_FALSE(again);
  EXPECT_TRUE(contains(again.error().message, "create topic 'rt/dock/state'"));
}

TEST_F(DdsTest, HotPathCallsOnDeletedEntitiesReturnCodes) {
  auto topic = Topic<Counter>::create(participant(), "/hubrt_test/deleted");
  ASSERT_TRUE(topic);
  auto writer = Writer<Counter>::create(participant(), *topic);
  auto reader = Reader<Counter>::create(participant(), *topic);
  ASSERT_TRUE(writer && reader);
  ASSERT_EQ(dds_delete(writer->handle()), DDS_RETCODE_OK);
  ASSERT_EQ(dds_delete(reader->handle()), DDS_RETCODE_OK);
  const Counter c{};
  EXPECT_EQ(writer->write(c).code(), ErrorCode::kInvalidArgument);
  Counter in{};
  EXPECT_EQ(reader->take_next(in).status().code(), ErrorCode::kInvalidArgument);
  EXPECT_FALSE(writer->matched_readers().is_ok());
  EXPECT_FALSE(reader->matched_writers().is_ok());
}

TEST(DdsErrors, BrokenCycloneXmlIsReportedForItsDomain) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  auto participant =
      Participant::create(DomainConfig{domain->domain_id(), "<CycloneDDS><NoSuchElement/></CycloneDDS>"});
  ASSERT_FALSE(participant);
  EXPECT_TRUE(contains(participant.error().message, "create domain " + std::to_string(domain->domain_id()) +
                                                        " with the given Cyclone XML configuration"));
  EXPECT_TRUE(contains(participant.error().message, "DDS_RETCODE_"));
  // The failed attempt leaves nothing behind: a good configuration still works afterwards.
  auto good = Participant::create(domain->config());
  EXPECT_TRUE(good) << good.error().message;
}

TEST(DdsErrors, DomainIdOutOfRangeIsRefused) {
  // Loopback configuration even here: a refused domain must not touch the real network.
  auto participant = Participant::create(DomainConfig{kMaxDomainId + 100, loopback_config_xml()}, "too_far");
  ASSERT_FALSE(participant);
  EXPECT_TRUE(contains(participant.error().message, "domain " + std::to_string(kMaxDomainId + 100)));
}

}  // namespace
}  // namespace hubrt::dds::test
