// The plant-wide tools as processes (issue 33, docs/plant.md): two stations, each in a DDS domain
// of its own (a TestDomainRange), a different hub in each — the Dock ECU in the first, the RSP ECU
// in the second — so that a tool which put a station's hubs under the other's name, or saw
// only one domain, fails here. `hubctl list`, `watch` and `record` with `--domain A-B` must show
// each hub under its own station, and the recording must carry each channel's domain and its name
// on the wire.
#include <filesystem>
#include <map>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/mcap/linear_reader.h"
#include "hubrt/test_support/hub_process.h"

namespace hubrt::integration {
namespace {

namespace fs = std::filesystem;
using test_support::ChildProcess;
using test_support::HubProcess;

// Generous: two hubd and a hubctl under sanitizers on a loaded 2-core machine start in seconds.
constexpr auto kPatience = std::chrono::seconds(60);

class HubctlPlantTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto range = test_support::TestDomainRange::acquire(2);
    ASSERT_TRUE(range) << range.error().message;
    range_.emplace(std::move(*range));
    auto dock = HubProcess::start(range_->at(0), {.hub = "dock_ecu"});
    ASSERT_TRUE(dock) << dock.error().message;
    dock_.emplace(std::move(*dock));
    auto rsp = HubProcess::start(range_->at(1), {.hub = "rsp_ecu"});
    ASSERT_TRUE(rsp) << rsp.error().message;
    rsp_.emplace(std::move(*rsp));
  }

  // Runs hubctl to its end with the first station's environment (its Cyclone configuration:
  // loopback); `--domain` in `args` names the stations.
  std::string run_hubctl(const std::vector<std::string>& args) {
    auto hubctl = ChildProcess::start(HUBRT_HUBCTL_PATH, args, range_->at(0).env());
    EXPECT_TRUE(hubctl) << hubctl.error().message;
    if (!hubctl) return {};
    auto status = hubctl->wait(kPatience);
    EXPECT_TRUE(status) << status.error().message;
    if (!status) return {};
    EXPECT_TRUE(status->exited_with(0))
        << status->describe() << hubctl->stdout_text() << hubctl->stderr_text();
    return hubctl->stdout_text();
  }

  [[nodiscard]] std::string station(std::size_t i) const {
    return fmt::format("d{}", range_->at(i).domain_id());
  }

  std::optional<test_support::TestDomainRange> range_;
  std::optional<HubProcess> dock_;
  std::optional<HubProcess> rsp_;
};

TEST_F(HubctlPlantTest, ListShowsEachStationsHubsUnderItsDomain) {
  const std::string out = run_hubctl({"list", "--domain", range_->text(), "--wait", "3"});
  const auto first = out.find(fmt::format("station {} (domain {})", station(0), range_->at(0).domain_id()));
  const auto second = out.find(fmt::format("station {} (domain {})", station(1), range_->at(1).domain_id()));
  ASSERT_NE(first, std::string::npos) << out;
  ASSERT_NE(second, std::string::npos) << out;
  ASSERT_LT(first, second) << out;
  // Each hub in its own station's part of the listing, and only there.
  const std::string first_part = out.substr(first, second - first);
  const std::string second_part = out.substr(second);
  // A hub is a line of its own under its station, its topics below it (the RSP ECU also reads the
  // Dock's State: a topic name, not a hub).
  EXPECT_NE(first_part.find("\n  dock_ecu\n    pub    /diagnostics"), std::string::npos) << out;
  EXPECT_EQ(first_part.find("\n  rsp_ecu\n"), std::string::npos) << out;
  EXPECT_NE(second_part.find("\n  rsp_ecu\n    pub    /diagnostics"), std::string::npos) << out;
  EXPECT_EQ(second_part.find("\n  dock_ecu\n"), std::string::npos) << out;
  EXPECT_EQ(second_part.find("pub    /dock_ecu/"), std::string::npos) << out;
}

TEST_F(HubctlPlantTest, WatchShowsEveryStationsStatesUnderItsName) {
  const std::string out = run_hubctl({"watch", "--plain", "--duration", "4", "--domain", range_->text()});
  EXPECT_NE(out.find(fmt::format("/{}/dock_ecu/dock/state", station(0))), std::string::npos) << out;
  EXPECT_NE(out.find(fmt::format("/{}/rsp_ecu/", station(1))), std::string::npos) << out;
  EXPECT_EQ(out.find(fmt::format("/{}/rsp_ecu/", station(0))), std::string::npos) << out;
  EXPECT_EQ(out.find(fmt::format("/{}/dock_ecu/", station(1))), std::string::npos) << out;
}

TEST_F(HubctlPlantTest, RecordKeepsEachChannelsStationDomainAndWireName) {
  const fs::path file = fs::temp_directory_path() / fmt::format("hubrt-plant-record-{}.mcap", getpid());
  fs::remove(file);
  run_hubctl({"record", "--domain", range_->text(), "--duration", "4", "--quiet", "-o", file.string()});
  auto source = mcap::open_file(file.string());
  ASSERT_TRUE(source) << file;
  auto reader = mcap::LinearReader::open(std::move(*source));
  ASSERT_TRUE(reader) << reader.error().message;
  std::map<std::string, std::uint64_t> per_topic;
  while (auto m = reader->next()) ++per_topic[reader->channels().at(m->channel_id).topic];
  const std::string dock_topic = fmt::format("/{}/dock_ecu/dock/state", station(0));
  ASSERT_GT(per_topic[dock_topic], 0U) << "no States of the first station's Dock ECU recorded";
  bool rsp_seen = false;
  for (const auto& [id, channel] : reader->channels()) {
    const bool first = channel.topic.rfind("/" + station(0) + "/", 0) == 0;
    const bool second = channel.topic.rfind("/" + station(1) + "/", 0) == 0;
    ASSERT_TRUE(first || second) << channel.topic << " is under neither station";
    const std::size_t k = first ? 0 : 1;
    EXPECT_EQ(channel.metadata.at("hubrt.station"), station(k)) << channel.topic;
    EXPECT_EQ(channel.metadata.at("hubrt.dds_domain_id"), std::to_string(range_->at(k).domain_id()))
        << channel.topic;
    EXPECT_EQ("/" + station(k) + channel.metadata.at("hubrt.wire_topic"), channel.topic);
    // Each hub's topics under its own station only.
    if (channel.topic.find("rsp_ecu") != std::string::npos) {
      EXPECT_TRUE(second) << channel.topic;
    }
    if (channel.topic.find("dock_ecu") != std::string::npos) {
      EXPECT_TRUE(first) << channel.topic;
    }
    if (second && channel.topic.find("rsp_ecu") != std::string::npos && per_topic[channel.topic] > 0) {
      rsp_seen = true;
    }
  }
  EXPECT_TRUE(rsp_seen) << "no samples of the second station's RSP ECU recorded";
  fs::remove(file);
}

}  // namespace
}  // namespace hubrt::integration
