// Two hubs with the same name assembled in one process, each on its own participant and manual
// clock (so which one started later is chosen by the test): the start-up check refuses the
// second, and when both run, both report the twin and only the later one asks to stop.
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/assembly/fake_simulation.h"
#include "hubrt/assembly/hub_assembly.h"
#include "hubrt/test_support/test_domain.h"

namespace hubrt::assembly {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

std::string host_name() {
  std::array<char, 256> name{};
  EXPECT_EQ(gethostname(name.data(), name.size() - 1), 0);
  return name.data();
}

class TwinAssemblyTest : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    later_clock_.advance(seconds(1));  // the second hub's start stamp is one second later
    // The shipped Dock ECU configuration in the layout under test.
    std::ifstream in(std::string(HUBRT_SOURCE_DIR) + "/hubs/dock_ecu/dock_ecu.yaml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto at = text.find("layout: node_type");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 17, std::string("layout: ") + GetParam());
    hub_file_ =
        std::filesystem::temp_directory_path() / fmt::format("hubrt-twin-{}-{}.yaml", GetParam(), getpid());
    std::ofstream(hub_file_) << text;
  }
  void TearDown() override { std::filesystem::remove(hub_file_); }

  AssemblyRequest request(std::optional<Duration> twin_check, std::atomic<int>& stops) const {
    AssemblyRequest r;
    r.board_file = std::string(HUBRT_SOURCE_DIR) + "/boards/host-sim.yaml";
    r.hub_file = hub_file_.string();
    r.backend = BackendKind::kFake;
    r.simulation = &fake_simulation();
    r.domain = domain_->config();
    r.twin_check = twin_check;
    r.request_stop = [&stops] { ++stops; };
    return r;
  }

  std::optional<test_support::TestDomain> domain_;
  std::filesystem::path hub_file_;
  ManualClock earlier_clock_;
  ManualClock later_clock_;
  std::atomic<int> earlier_stops_{0};
  std::atomic<int> later_stops_{0};
};

TEST_P(TwinAssemblyTest, TheSecondHubIsRefusedAtStartUpNamingHostAndPid) {
  auto first = assemble_hub(request(Duration::zero(), earlier_stops_), earlier_clock_);
  ASSERT_TRUE(first) << first.error().message;
  auto second = assemble_hub(request(milliseconds(300), later_stops_), later_clock_);
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().code, ErrorCode::kBusy);
  EXPECT_NE(second.error().message.find(
                "twin: another hub already publishes the States of hub 'dock_ecu': /dock_ecu/"),
            std::string::npos)
      << second.error().message;
  EXPECT_NE(second.error().message.find(fmt::format("from host {} pid {}", host_name(), getpid())),
            std::string::npos)
      << second.error().message;
}

TEST_P(TwinAssemblyTest, AloneOnTheDomainTheStartUpCheckEndsOnceDiscoverySettledNotAfterItsWindow) {
  // A window far longer than any settling: before the check ended on settled discovery, assembly
  // took the whole window. The bound is a tenth of it, generous for a loaded machine under
  // sanitizers (the check settles after kDefaultTwinCheckQuiet, 15 ms, of quiet discovery).
  const auto started = std::chrono::steady_clock::now();
  auto alone = assemble_hub(request(seconds(30), earlier_stops_), earlier_clock_);
  const auto took = std::chrono::steady_clock::now() - started;
  ASSERT_TRUE(alone) << alone.error().message;
  EXPECT_LT(took, seconds(3));
}

TEST_P(TwinAssemblyTest, ATwinIsRefusedWithinItsWindowEvenWhenTheCheckCouldSettleEarly) {
  auto first = assemble_hub(request(Duration::zero(), earlier_stops_), earlier_clock_);
  ASSERT_TRUE(first) << first.error().message;
  // The first hub's identity is in its SPDP: known to the second before any endpoint, so the
  // check cannot settle on "alone" however quiet discovery gets.
  AssemblyRequest second_request = request(seconds(30), later_stops_);
  second_request.twin_quiet = milliseconds(1);
  auto second = assemble_hub(second_request, later_clock_);
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().code, ErrorCode::kBusy);
  EXPECT_NE(second.error().message.find("twin: another hub already publishes the States of hub 'dock_ecu'"),
            std::string::npos)
      << second.error().message;
}

TEST_P(TwinAssemblyTest, BothReportTheTwinAndOnlyTheLaterOneStops) {
  auto earlier = assemble_hub(request(Duration::zero(), earlier_stops_), earlier_clock_);
  ASSERT_TRUE(earlier) << earlier.error().message;
  // Start-up check off: as if the second hub came up inside the first one's discovery window.
  auto later = assemble_hub(request(Duration::zero(), later_stops_), later_clock_);
  ASSERT_TRUE(later) << later.error().message;
  runtime::Hub& a = *(*earlier)->hub;
  runtime::Hub& b = *(*later)->hub;

  const std::string report = fmt::format("twin: another hub publishes /dock_ecu/{} from host {} pid {}",
                                         std::string_view(GetParam()) == "node_type" ? "dock/state" : "state",
                                         host_name(), getpid());
  // Discovery of local participants is quick but runs on Cyclone's threads: cycle until both saw
  // it (generous deadline: a loaded machine under sanitizers).
  const auto deadline = std::chrono::steady_clock::now() + seconds(20);
  while (std::chrono::steady_clock::now() < deadline &&
         (a.nodes().front()->first_error().empty() || b.nodes().front()->first_error().empty())) {
    earlier_clock_.advance(milliseconds(100));
    later_clock_.advance(milliseconds(100));
    a.cycle(earlier_clock_.now());
    b.cycle(later_clock_.now());
    std::this_thread::sleep_for(milliseconds(5));
  }
  EXPECT_EQ(a.nodes().front()->first_error(), report);
  EXPECT_EQ(b.nodes().front()->first_error(), report);
  EXPECT_EQ(a.nodes().front()->health(), runtime::Health::kError);
  EXPECT_EQ(earlier_stops_, 0);
  EXPECT_EQ(later_stops_, 1);
  EXPECT_FALSE((*earlier)->twins->yielded());
  ASSERT_TRUE((*later)->twins->yielded());
  EXPECT_NE((*later)->twins->yield_message().find("started earlier than this one"), std::string::npos);

  // Asked once only, however many cycles run before the runner stops.
  b.cycle(later_clock_.now());
  EXPECT_EQ(later_stops_, 1);
}

INSTANTIATE_TEST_SUITE_P(Layouts, TwinAssemblyTest, ::testing::Values("node_type", "hub"));

}  // namespace
}  // namespace hubrt::assembly
