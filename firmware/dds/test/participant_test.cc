// Participants and the domains they live in, within one process.
#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"

#include "dds_fixture.h"
#include "test_types_traits.h"

namespace hubrt::dds::test {
namespace {

TEST_F(DdsTest, TwoParticipantsInOneProcessShareTheDomainAndTalk) {
  auto second = Participant::create(config(), "second");
  ASSERT_TRUE(second) << second.error().message;
  EXPECT_EQ(second->domain_id(), participant().domain_id());
  EXPECT_EQ(dds_get_parent(second->handle()), dds_get_parent(participant().handle())) << "one domain entity";
  EXPECT_NE(second->guid(), participant().guid());
  EXPECT_NE(second->guid(), Guid{});

  auto topic_a = Topic<Counter>::create(participant(), "/hubrt_test/shared");
  auto topic_b = Topic<Counter>::create(*second, "/hubrt_test/shared");
  ASSERT_TRUE(topic_a && topic_b);
  auto writer = Writer<Counter>::create(participant(), *topic_a);
  auto reader = Reader<Counter>::create(*second, *topic_b);
  ASSERT_TRUE(writer && reader);
  ASSERT_TRUE(writer->wait_for_readers(1, kDeliveryBound));
  Counter c{};
  c.count = 99;
  ASSERT_TRUE(writer->write(c).is_ok());
  ASSERT_TRUE(wait_for_data(*reader, *second));
  Counter in{};
  ASSERT_TRUE(reader->take_next(in).value());
  EXPECT_EQ(in.count, 99);
}

TEST_F(DdsTest, FirstConfigurationOfADomainWinsInAProcess) {
  // Once the domain exists here, another participant joins it whatever XML it brings — even XML
  // Cyclone would refuse — instead of failing with "domain already exists".
  auto second =
      Participant::create(DomainConfig{domain_->domain_id(), "<CycloneDDS><NoSuchElement/></CycloneDDS>"});
  ASSERT_TRUE(second) << second.error().message;
  EXPECT_EQ(dds_get_parent(second->handle()), dds_get_parent(participant().handle()));
}

TEST_F(DdsTest, DefaultConfigParticipantJoinsAnExplicitlyConfiguredDomain) {
  auto second = Participant::create(DomainConfig{domain_->domain_id(), ""});
  ASSERT_TRUE(second) << second.error().message;
  EXPECT_EQ(dds_get_parent(second->handle()), dds_get_parent(participant().handle()));
}

TEST(DdsDomain, DomainGoesAwayWithItsLastParticipantAndCanBeCreatedAgain) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  dds_entity_t first_domain = 0;
  {
    auto a = Participant::create(domain->config());
    ASSERT_TRUE(a) << a.error().message;
    first_domain = dds_get_parent(a->handle());
    ASSERT_GT(first_domain, 0);
    auto b = Participant::create(domain->config());
    ASSERT_TRUE(b) << b.error().message;
    { const Participant gone = std::move(*a); }
    // b still holds the domain: it must be alive and b usable.
    EXPECT_EQ(dds_get_parent(b->handle()), first_domain);
    auto topic = Topic<Counter>::create(*b, "/hubrt_test/still_alive");
    EXPECT_TRUE(topic) << topic.error().message;
  }
  // All our participants are gone: so is the domain we created, and a new one can be made.
  EXPECT_LT(dds_get_parent(first_domain), 0);
  auto again = Participant::create(domain->config());
  ASSERT_TRUE(again) << again.error().message;
  EXPECT_NE(dds_get_parent(again->handle()), first_domain);
}

TEST(DdsDomain, MovedParticipantKeepsWorking) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain);
  auto created = Participant::create(domain->config());
  ASSERT_TRUE(created);
  const dds_entity_t handle = created->handle();
  Participant moved = std::move(*created);
  EXPECT_EQ(moved.handle(), handle);
  EXPECT_EQ(created->handle(), 0);  // NOLINT(bugprone-use-after-move): documented state
  auto topic = Topic<Counter>::create(moved, "/hubrt_test/moved");
  EXPECT_TRUE(topic) << topic.error().message;
}

}  // namespace
}  // namespace hubrt::dds::test
