#include "hubrt/dds/ports.h"

#include <string>

#include <gtest/gtest.h>

namespace hubrt::dds {
namespace {

TEST(DomainPortBand, IsTheDdsiMappingOfTheIdUpToTheNextDomain) {
  EXPECT_EQ(domain_port_band(0).first, 7400);
  EXPECT_EQ(domain_port_band(0).last, 7649);
  EXPECT_EQ(domain_port_band(100).first, 32400);
  EXPECT_EQ(domain_port_band(101).last, 32899);
  EXPECT_EQ(domain_port_band(215).first, 61150);
}

TEST(UnicastDiscoveryPort, IsTenPastTheBandAndTwoPerParticipantIndex) {
  EXPECT_EQ(unicast_discovery_port(0, 0), 7410);
  EXPECT_EQ(unicast_discovery_port(3, 4), 8168);
  EXPECT_EQ(unicast_discovery_port(215, 1), 61162);
}

TEST(DomainPortBand, OnLinuxDefaultsIdsUpTo100And215OnAreOutsideTheEphemeralRange) {
  EXPECT_TRUE(disjoint(domain_port_band(100), kLinuxDefaultEphemeralPorts));   // 32400-32649
  EXPECT_FALSE(disjoint(domain_port_band(101), kLinuxDefaultEphemeralPorts));  // 32650-32899
  EXPECT_FALSE(disjoint(domain_port_band(214), kLinuxDefaultEphemeralPorts));  // 60900-61149
  EXPECT_TRUE(disjoint(domain_port_band(215), kLinuxDefaultEphemeralPorts));   // 61150-61399
  EXPECT_TRUE(disjoint(PortRange{1, 2}, PortRange{3, 4}));
  EXPECT_FALSE(disjoint(PortRange{1, 3}, PortRange{3, 4}));
  EXPECT_FALSE(disjoint(PortRange{3, 4}, PortRange{1, 3}));
}

TEST(PortRangeText, ReadsTheKernelsFormat) {
  const auto range = parse_port_range("32768\t60999\n");
  ASSERT_TRUE(range);
  EXPECT_EQ(range->first, 32768);
  EXPECT_EQ(range->last, 60999);
  const auto one = parse_port_range("1024 1024");
  ASSERT_TRUE(one);
  EXPECT_EQ(one->last, 1024);
}

TEST(PortRangeText, RefusesWhatIsNotTwoAscendingPorts) {
  for (const char* bad : {"", "32768", "60999 32768", "0 10", "1 65536", "1 2 3", "a b", "-1 5", "10\t20x"}) {
    EXPECT_FALSE(parse_port_range(bad)) << "'" << bad << "'";
  }
}

TEST(EphemeralPortRange, IsTwoAscendingPorts) {
  const PortRange range = ephemeral_port_range();
  EXPECT_GE(range.first, 1);
  EXPECT_LE(range.first, range.last);
  EXPECT_LE(range.last, 65535);
}

TEST(EphemeralPortHazard, NamesTheDomainItsPortsTheRangeAndTheWayOut) {
  const auto hazard = ephemeral_port_hazard(150, kLinuxDefaultEphemeralPorts);
  ASSERT_TRUE(hazard);
  for (const std::string part : {"docs/deploy.md", "DDS domain 150", "44900-45149", "32768-60999", "Fast DDS",
                                 "0-100 or 215-232", "DDS Security"}) {
    EXPECT_NE(hazard->find(part), std::string::npos) << part << " not in: " << *hazard;
  }
}

TEST(EphemeralPortHazard, NoneOutsideTheRange) {
  EXPECT_FALSE(ephemeral_port_hazard(0, kLinuxDefaultEphemeralPorts));
  EXPECT_FALSE(ephemeral_port_hazard(100, kLinuxDefaultEphemeralPorts));
  EXPECT_FALSE(ephemeral_port_hazard(215, kLinuxDefaultEphemeralPorts));
  EXPECT_TRUE(ephemeral_port_hazard(0, PortRange{7000, 7500}));  // a machine whose range reaches down
}

}  // namespace
}  // namespace hubrt::dds
