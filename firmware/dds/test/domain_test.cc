#include "hubrt/dds/domain.h"

#include <stdlib.h>

#include <dds/dds.h>
#include <gtest/gtest.h>

namespace hubrt::dds {
namespace {

// Each TEST runs in its own process (gtest_discover_tests), so changing the environment here
// cannot leak into other tests; it is restored anyway. No other thread runs meanwhile.
// NOLINTBEGIN(concurrency-mt-unsafe)
class DomainFromEnvironment : public ::testing::Test {
 protected:
  void TearDown() override { ::unsetenv(kDomainIdEnvVar); }
  static void set(const char* value) { ASSERT_EQ(::setenv(kDomainIdEnvVar, value, 1), 0); }
};

TEST_F(DomainFromEnvironment, UnsetMeansDomainZeroAndCycloneReadsItsOwnUri) {
  ::unsetenv(kDomainIdEnvVar);
  auto config = domain_config_from_environment();
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->domain_id, 0u);
  EXPECT_TRUE(config->cyclone_xml.empty());
}

TEST_F(DomainFromEnvironment, ReadsRosDomainId) {
  set("42");
  auto config = domain_config_from_environment();
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->domain_id, 42u);
}

TEST_F(DomainFromEnvironment, RejectsNonNumbersAndIdsOutOfRange) {
  for (const char* bad : {"abc", "12x", "-1", "233"}) {
    set(bad);
    auto config = domain_config_from_environment();
    ASSERT_FALSE(config) << bad;
    EXPECT_EQ(config.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(config.error().message.find(std::string("ROS_DOMAIN_ID='") + bad + "'"), std::string::npos)
        << config.error().message;
  }
}

// 64 hubs, hubctl and a planner on one host (tests/support/test/loopback_capacity_test.cc starts
// the 65th and 66th); domain 232 alone is bounded by its port numbers (7400 + 250 * 232 + 11 +
// 2 * 62 = 65535).
TEST(LoopbackConfig, PinsLoopbackWithoutMulticastAndAStationOfParticipants) {
  const std::string xml = loopback_config_xml();
  EXPECT_NE(xml.find("<NetworkInterface name=\"lo\"/>"), std::string::npos);
  EXPECT_NE(xml.find("<AllowMulticast>false</AllowMulticast>"), std::string::npos);
  EXPECT_NE(xml.find("<ParticipantIndex>auto</ParticipantIndex>"), std::string::npos);
  EXPECT_GE(kLoopbackParticipantsPerHost, 66);
  EXPECT_NE(xml.find("<MaxAutoParticipantIndex>100</MaxAutoParticipantIndex>"), std::string::npos);
  EXPECT_NE(xml.find("<Peer address=\"127.0.0.1\"/>"), std::string::npos);
  EXPECT_EQ(7400 + 250 * kMaxDomainId + 11 + 2 * (kLoopbackParticipantsInLastDomain - 1), 65535u);
  EXPECT_NE(xml.find(",<CycloneDDS><Domain id=\"232\"><Discovery><MaxAutoParticipantIndex>63"
                     "</MaxAutoParticipantIndex></Discovery></Domain></CycloneDDS>"),
            std::string::npos);
}

// Cyclone accepts the two sources in the last domain too (a Domain element with a numeric id is
// only valid as the first data of its source), and the smaller bound applies there.
TEST(LoopbackConfig, CycloneTakesItInTheLastDomain) {
  const dds_entity_t domain = dds_create_domain(kMaxDomainId, loopback_config_xml().c_str());
  ASSERT_GE(domain, 0) << dds_strretcode(domain);
  const dds_entity_t participant = dds_create_participant(kMaxDomainId, nullptr, nullptr);
  EXPECT_GE(participant, 0) << dds_strretcode(participant);
  EXPECT_EQ(dds_delete(domain), DDS_RETCODE_OK);
}

// The receive buffer bounds the saw-tooth of RSS that discovery and commands cause (docs/soak.md:
// 3 kB per planner reconnect with Cyclone's 1 MiB default, flat with 192 KiB). Every DDS test in
// the suite creates its participants with this configuration, so Cyclone accepting it is tested
// there; tests/soak/reconnect-growth measures the effect.
TEST(LoopbackConfig, BoundsTheReceiveBufferSawTooth) {
  EXPECT_NE(loopback_config_xml().find("<Sizing><ReceiveBufferSize>192 KiB</ReceiveBufferSize></Sizing>"),
            std::string::npos);
}

// Cyclone discards samples larger than Internal/MaxSampleSize on their first datagram
// (q_receive.c, drop_oversize): every configuration hubrt writes carries the bound, and the
// 192 KiB receive buffer (hubd's first source: a station's configuration alone left it at 1 MiB).
TEST(LoopbackConfig, BoundsTheSampleSize) {
  EXPECT_EQ(kMaxSampleSizeBytes, 65536u);
  EXPECT_NE(loopback_config_xml().find("<Internal><MaxSampleSize>65536 B</MaxSampleSize></Internal>"),
            std::string::npos);
  EXPECT_EQ(sample_bounds_config_xml(),
            "<CycloneDDS><Domain id=\"any\"><Sizing><ReceiveBufferSize>192 KiB</ReceiveBufferSize></Sizing>"
            "<Internal><MaxSampleSize>65536 B</MaxSampleSize></Internal></Domain></CycloneDDS>");
}

// hubd creates its domain with the bound first and the station's configuration after it (a later
// source overrides an earlier one in Cyclone, so a station may still choose another bound).
class SampleBounds : public ::testing::Test {
 protected:
  void TearDown() override { ::unsetenv(kCycloneUriEnvVar); }
};

TEST_F(SampleBounds, GoInFrontOfTheGivenConfiguration) {
  ASSERT_EQ(::setenv(kCycloneUriEnvVar, "file:///ignored.xml", 1), 0);
  EXPECT_EQ(with_sample_bounds("file:///etc/hubrt/cyclonedds.xml"),
            sample_bounds_config_xml() + ",file:///etc/hubrt/cyclonedds.xml");
}

TEST_F(SampleBounds, GoInFrontOfCycloneddsUriWhenNoConfigurationIsGiven) {
  ASSERT_EQ(::setenv(kCycloneUriEnvVar, "<CycloneDDS><Domain><General/></Domain></CycloneDDS>", 1), 0);
  EXPECT_EQ(with_sample_bounds(""),
            sample_bounds_config_xml() + ",<CycloneDDS><Domain><General/></Domain></CycloneDDS>");
}

TEST_F(SampleBounds, StandAloneWithoutAnyConfiguration) {
  ::unsetenv(kCycloneUriEnvVar);
  EXPECT_EQ(with_sample_bounds(""), sample_bounds_config_xml());
}

// NOLINTEND(concurrency-mt-unsafe)

}  // namespace
}  // namespace hubrt::dds
