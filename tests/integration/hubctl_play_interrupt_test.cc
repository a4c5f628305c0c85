// `hubctl play` stopped with Ctrl-C says it was interrupted and exits with 130 — not "FAILED ...
// not met within 60.0 s" after half a second, as if the station had misbehaved.
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/dds/discovery.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/ros_names.h"
#include "hubrt/test_support/hub_process.h"

namespace hubrt::integration {
using test_support::Finished;
namespace {

namespace fs = std::filesystem;
using std::chrono::seconds;
using test_support::ChildProcess;

class HubctlPlayInterruptTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    scenario_ = fs::temp_directory_path() / fmt::format("hubrt-play-interrupt-{}.yaml", getpid());
    // Nobody publishes the station's State in this domain: the wait can only end by its 60 s
    // timeout — or by Ctrl-C.
    std::ofstream(scenario_) << "description: a wait on a station that is not there\n"
                                "timeout: 60\n"
                                "steps:\n"
                                "  - wait: {station: true, until: \"robot_at == engine\"}\n";
  }
  void TearDown() override { fs::remove(scenario_); }

  // Whether a process other than this one reads `ros_topic`, within `patience` (DDS discovery,
  // looked at every 20 ms).
  bool someone_reads(std::string_view ros_topic, Duration patience) {
    auto participant = dds::Participant::create(domain_->config(), "play-interrupt-test");
    auto dds_name = dds::ros_to_dds_topic(ros_topic);
    if (!participant || !dds_name) return false;
    const auto deadline = std::chrono::steady_clock::now() + patience;
    while (std::chrono::steady_clock::now() < deadline) {
      auto snapshot = dds::discover(*participant);
      if (!snapshot) return false;
      for (const auto& e : snapshot->endpoints) {
        if (!e.local && e.direction == dds::EndpointDirection::kReader && e.topic_name == *dds_name)
          return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

  // The wait step has begun: play reads the station's State (it makes the reader as the step
  // starts). 20 s covers start-up and discovery under sanitizers.
  std::function<bool(ChildProcess&)> in_the_wait() {
    return [this](ChildProcess&) { return someone_reads("/sim/station/state", seconds(20)); };
  }

  // Starts hubctl play, waits until `in_progress` says it got where it is to be stopped, and sends
  // it `sig`.
  Finished interrupt_with(int sig, const std::function<bool(ChildProcess&)>& in_progress,
                          const std::vector<std::string>& extra_args = {}) {
    std::vector<std::string> args = {"play", scenario_.string(), "--timeout", "5"};
    args.insert(args.end(), extra_args.begin(), extra_args.end());
    auto child = ChildProcess::start(HUBRT_HUBCTL_PATH, args, domain_->env());
    EXPECT_TRUE(child) << child.error().message;
    if (!child) return {};
    // The description ("play: ...") is printed as the run begins, after the Ctrl-C handler is in
    // place; 20 s covers start-up under sanitizers.
    EXPECT_TRUE(child->wait_for_output("play: ", seconds(20))) << child->stdout_text();
    EXPECT_TRUE(in_progress(*child)) << child->stdout_text();
    EXPECT_TRUE(child->signal(sig));
    auto status = child->wait(seconds(30));
    EXPECT_TRUE(status) << status.error().message;
    return Finished{status ? *status : test_support::ExitStatus{},
                    child->stdout_text() + child->stderr_text()};
  }

  std::optional<test_support::TestDomain> domain_;
  fs::path scenario_;
};

TEST_F(HubctlPlayInterruptTest, CtrlCSaysInterruptedAndExits130) {
  const Finished f = interrupt_with(SIGINT, in_the_wait());
  EXPECT_TRUE(f.status.exited_with(130)) << f.status.describe() << "\n" << f.output;
  EXPECT_NE(f.output.find("play: interrupted at step 1 of 1 ("), std::string::npos) << f.output;
  EXPECT_NE(f.output.find("  STOP  "), std::string::npos) << f.output;
  EXPECT_EQ(f.output.find("not met within"), std::string::npos) << f.output;
  EXPECT_EQ(f.output.find("FAIL"), std::string::npos) << f.output;
}

TEST_F(HubctlPlayInterruptTest, SigtermSaysInterruptedAndExits143) {
  const Finished f = interrupt_with(SIGTERM, in_the_wait());
  EXPECT_TRUE(f.status.exited_with(143)) << f.status.describe() << "\n" << f.output;
  EXPECT_NE(f.output.find("play: interrupted at step 1 of 1 ("), std::string::npos) << f.output;
  EXPECT_EQ(f.output.find("not met within"), std::string::npos) << f.output;
}

// --rounds 0 runs until Ctrl-C, which ends it as interrupted too (before: "PASSED", exit 0, or a
// failed step, depending on when the signal came).
TEST_F(HubctlPlayInterruptTest, RoundsUntilCtrlCEndInterrupted) {
  std::ofstream(scenario_) << "description: a short sleep, round after round\n"
                              "steps:\n"
                              "  - sleep: 0.05\n";
  // Stopped once the rounds are going round.
  const Finished f = interrupt_with(
      SIGINT, [](ChildProcess& play) { return play.wait_for_output("play: round 3", seconds(20)); },
      {"--rounds", "0"});
  EXPECT_TRUE(f.status.exited_with(130)) << f.status.describe() << "\n" << f.output;
  EXPECT_NE(f.output.find("play: interrupted "), std::string::npos) << f.output;
  EXPECT_EQ(f.output.find("PASSED"), std::string::npos) << f.output;
}

}  // namespace
}  // namespace hubrt::integration
