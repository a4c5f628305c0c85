// hubctl net-config: the station file's checks and the Cyclone XML it generates for each host —
// what would break a station on several hosts: a host missing from another's peers (it is never
// discovered), multicast left on (discovery leaks onto the LAN, or fails on a VPN), a participant
// index too small for the busiest host, no sample bounds.
#include <regex>
#include <set>

#include <dds/dds.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hubrt/dds/domain.h"
#include "hubrt/test_support/test_domain.h"

#include "net_config_xml.h"
#include "station_network.h"

namespace hubrt::hubctl {
namespace {

using ::testing::HasSubstr;

constexpr const char* kStation = R"(# the paper's station, five hosts
domain: 3
hosts:
  planner-pc: {address: 10.8.0.1, runs: [planner]}
  sim-pc: {address: 10.8.0.2, runs: [hubsim]}
  tool-pi: {address: 10.8.0.11, interface: wg0, runs: [tool_ecu]}
  rsp-pi: {address: 10.8.0.12, runs: [rsp_ecu]}
  cell-pi: {address: 10.8.0.13, runs: [dock_ecu, signal_lamp, hubsim_spare]}
)";

StationNetwork load(const std::string& text) {
  auto station = load_station_network_string(text, "station.yaml");
  EXPECT_TRUE(station) << station.error().message;
  return station ? *station : StationNetwork{};
}

std::string net_config_error_of(const std::string& text) {
  auto station = load_station_network_string(text, "station.yaml");
  EXPECT_FALSE(station) << "accepted:\n" << text;
  return station ? "" : station.error().message;
}

std::string xml_for(const StationNetwork& station, const std::string& host) {
  auto xml = cyclone_config_for_host(station, host);
  EXPECT_TRUE(xml) << xml.error().message;
  return xml ? *xml : "";
}

// The Peer addresses of a configuration, in order.
std::vector<std::string> peers(const std::string& xml) {
  std::vector<std::string> found;
  const std::regex peer(R"re(<Peer address="([^"]+)"/>)re");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), peer); it != std::sregex_iterator(); ++it) {
    found.push_back((*it)[1]);
  }
  return found;
}

TEST(StationNetwork, LoadsHostsInFileOrder) {
  const StationNetwork station = load(kStation);
  EXPECT_EQ(station.domain_id, 3u);
  ASSERT_EQ(station.hosts.size(), 5u);
  EXPECT_EQ(station.hosts[2].name, "tool-pi");
  EXPECT_EQ(station.hosts[2].address, "10.8.0.11");
  EXPECT_EQ(station.hosts[2].interface, "wg0");
  EXPECT_EQ(station.hosts[4].runs, (std::vector<std::string>{"dock_ecu", "signal_lamp", "hubsim_spare"}));
  EXPECT_EQ(station.hosts[4].line, 8);
}

TEST(NetConfig, EveryHostHasEveryHostAsAPeer) {
  const StationNetwork station = load(kStation);
  const std::set<std::string> all = {"10.8.0.1", "10.8.0.2", "10.8.0.11", "10.8.0.12", "10.8.0.13"};
  for (const StationHost& host : station.hosts) {
    const std::vector<std::string> listed = peers(xml_for(station, host.name));
    EXPECT_EQ(std::set<std::string>(listed.begin(), listed.end()), all) << host.name;
    EXPECT_EQ(listed.size(), all.size()) << host.name << ": a peer listed twice";
  }
}

TEST(NetConfig, MulticastIsOffAndDiscoveryIsUnicastWithAutomaticIndices) {
  const std::string xml = xml_for(load(kStation), "rsp-pi");
  EXPECT_THAT(xml, HasSubstr("<AllowMulticast>false</AllowMulticast>"));
  EXPECT_THAT(xml, ::testing::Not(HasSubstr("<AllowMulticast>true")));
  EXPECT_THAT(xml, HasSubstr("<ParticipantIndex>auto</ParticipantIndex>"));
}

TEST(NetConfig, SelectsTheInterfaceByAddressOrByName) {
  const StationNetwork station = load(kStation);
  EXPECT_THAT(xml_for(station, "rsp-pi"), HasSubstr("<NetworkInterface address=\"10.8.0.12\"/>"));
  const std::string tool = xml_for(station, "tool-pi");
  EXPECT_THAT(tool, HasSubstr("<NetworkInterface name=\"wg0\"/>"));
  EXPECT_THAT(tool, ::testing::Not(HasSubstr("NetworkInterface address")));
}

// cell-pi runs three processes, plus two spare participants (hubctl): indices 0..4, on every
// host alike, since each host sends discovery to indices 0..Max-1 of every peer. Cyclone 0.10.2
// admits MaxAutoParticipantIndex processes, not one more (net_config_xml.cc): it is 5, and a
// host running one process with no spare needs 1 (with 0 no process could join DDS at all).
TEST(NetConfig, ParticipantIndexCoversTheBusiestHostPlusSpares) {
  const StationNetwork station = load(kStation);
  EXPECT_EQ(station.max_participant_index(), 4);
  for (const StationHost& host : station.hosts) {
    EXPECT_THAT(xml_for(station, host.name),
                HasSubstr("<MaxAutoParticipantIndex>5</MaxAutoParticipantIndex>"))
        << host.name;
  }
  const StationNetwork quiet = load("spare_participants: 0\nhosts:\n  a: {address: 10.0.0.1, runs: [x]}\n");
  EXPECT_EQ(quiet.max_participant_index(), 0);
  EXPECT_THAT(xml_for(quiet, "a"), HasSubstr("<MaxAutoParticipantIndex>1</MaxAutoParticipantIndex>"));
}

// What the file says, Cyclone does: a host that runs one process and keeps no spare lets that
// process join (on loopback, in a private domain, so nothing else is reached).
TEST(NetConfig, CycloneAdmitsTheProcessesTheFileCounts) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  const StationNetwork station =
      load("domain: " + std::to_string(domain->domain_id()) +
           "\nspare_participants: 0\nhosts:\n  a: {address: 127.0.0.1, runs: [x]}\n");
  const std::string xml = xml_for(station, "a");
  const dds_entity_t cyclone_domain = dds_create_domain(domain->domain_id(), xml.c_str());
  ASSERT_GE(cyclone_domain, 0) << dds_strretcode(cyclone_domain) << "\n" << xml;
  const dds_entity_t participant = dds_create_participant(domain->domain_id(), nullptr, nullptr);
  EXPECT_GE(participant, 0) << dds_strretcode(participant) << "\n" << xml;
  EXPECT_EQ(dds_delete(cyclone_domain), DDS_RETCODE_OK);
}

TEST(NetConfig, CarriesHubrtsResourceBoundsAndThePortsForTheFirewall) {
  const std::string xml = xml_for(load(kStation), "planner-pc");
  EXPECT_THAT(xml, HasSubstr(dds::resource_bounds_elements_xml()));
  EXPECT_THAT(xml, HasSubstr("<MaxSampleSize>65536 B</MaxSampleSize>"));
  // Domain 3: B = 7400 + 750 = 8150; indices 0..4 -> 8160 .. 8160 + 1 + 8.
  EXPECT_THAT(xml, HasSubstr("UDP ports 8160 to 8169 (domain 3)"));
  EXPECT_THAT(xml, HasSubstr("<Domain id=\"any\">"));
}

TEST(NetConfig, TheXmlIsWellFormedEnoughForCyclone) {
  const std::string xml = xml_for(load(kStation), "cell-pi");
  // An XML comment may not contain "--": names are kept free of it, so only the delimiters do.
  std::size_t comments = 0;
  for (std::size_t at = xml.find("--"); at != std::string::npos; at = xml.find("--", at + 2)) ++comments;
  EXPECT_EQ(comments, 2u * 6u) << xml;  // the header and five peers, "<!--" and "-->" each
  EXPECT_EQ(xml.rfind("</CycloneDDS>\n"), xml.size() - 14);
}

TEST(NetConfig, AnUnknownHostIsNamedWithTheStationsHosts) {
  auto xml = cyclone_config_for_host(load(kStation), "dock-pi");
  ASSERT_FALSE(xml);
  EXPECT_EQ(xml.error().code, ErrorCode::kNotFound);
  EXPECT_EQ(
      xml.error().message,
      "station.yaml: no host 'dock-pi' (the station's hosts: planner-pc, sim-pc, tool-pi, rsp-pi, cell-pi)");
}

TEST(StationNetwork, RefusesADuplicateAddressAtItsLine) {
  EXPECT_EQ(net_config_error_of(
                "hosts:\n  a: {address: 10.0.0.1, runs: [x]}\n  b: {address: 10.0.0.1, runs: [y]}\n"),
            "station.yaml:3:16: hosts.b.address: 10.0.0.1 is also the address of host 'a' (line 2)");
}

TEST(StationNetwork, RefusesAProcessOnTwoHosts) {
  EXPECT_THAT(net_config_error_of("hosts:\n  a: {address: 10.0.0.1, runs: [tool_ecu]}\n"
                                  "  b: {address: 10.0.0.2, runs: [planner, tool_ecu]}\n"),
              HasSubstr("station.yaml:3:32: hosts.b.runs: 'tool_ecu' already runs on host 'a' (line 2)"));
}

TEST(StationNetwork, RefusesBadValuesWithFileAndLine) {
  EXPECT_EQ(net_config_error_of("hosts:\n  a: {address: 10.0.0.300}\n"),
            "station.yaml:2:16: hosts.a.address: '10.0.0.300' is not an IPv4 address (e.g. 10.8.0.11)");
  EXPECT_THAT(net_config_error_of("hosts:\n  a: {address: pi.local}\n"), HasSubstr("is not an IPv4 address"));
  EXPECT_THAT(net_config_error_of("hosts:\n  a: {address: 10.0.0.1, interface: 'eth0 up'}\n"),
              HasSubstr("hosts.a.interface: 'eth0 up' is not a network interface name"));
  EXPECT_THAT(net_config_error_of("hosts:\n  a--b: {address: 10.0.0.1}\n"), HasSubstr("host name 'a--b'"));
  EXPECT_THAT(net_config_error_of("hosts:\n  a: {address: 10.0.0.1, runs: ['<x>']}\n"),
              HasSubstr("is not a process name"));
  EXPECT_EQ(net_config_error_of("hosts:\n  a: {address: 10.0.0.1, run: [x]}\n"),
            "station.yaml:2:26: hosts.a.run: unknown key (expected one of: address, interface, runs)");
  EXPECT_THAT(net_config_error_of("hosts: {}\n"), HasSubstr("hosts: lists no host"));
  EXPECT_THAT(net_config_error_of("domain: 300\nhosts:\n  a: {address: 10.0.0.1}\n"),
              HasSubstr("station.yaml:1:9: domain"));
  EXPECT_THAT(net_config_error_of("hosts:\n  a: {address: 10.0.0.1\n"), HasSubstr("station.yaml:"));
}

TEST(StationNetwork, RefusesPortsBeyondUdp) {
  // Domain 232 leaves 7400 + 58000 + 10 .. 65535: 62 participant indices.
  EXPECT_THAT(net_config_error_of("domain: 232\nspare_participants: 100\nhosts:\n  a: {address: 10.0.0.1}\n"),
              HasSubstr("needs UDP port"));
  EXPECT_THAT(
      net_config_error_of("spare_participants: 119\nhosts:\n  a: {address: 10.0.0.1, runs: [x, y]}\n"),
      HasSubstr("participant index 120; Cyclone allows up to 119"));
}

TEST(StationNetwork, AMissingFileIsNotFound) {
  auto station = load_station_network("/nonexistent/station.yaml");
  ASSERT_FALSE(station);
  EXPECT_EQ(station.error().code, ErrorCode::kNotFound);
}

TEST(StationNetwork, TheNetTiersStationFileLoads) {
  auto station = load_station_network(std::string(HUBRT_SOURCE_DIR) + "/tests/net/station-net.yaml");
  ASSERT_TRUE(station) << station.error().message;
  std::set<std::string> processes;
  for (const StationHost& host : station->hosts) processes.insert(host.runs.begin(), host.runs.end());
  EXPECT_EQ(processes, (std::set<std::string>{"planner", "hubsim", "tool_ecu", "rsp_ecu", "dock_ecu"}));
}

}  // namespace
}  // namespace hubrt::hubctl
