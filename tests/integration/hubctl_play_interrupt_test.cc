// `hubctl play` stopped with Ctrl-C says it was interrupted and exits with 130 — not "FAILED ...
// not met within 60.0 s" after half a second, as if the station had misbehaved.
#include <csignal>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hub_process.h"

namespace hubrt::integration {
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

  // Starts hubctl play, lets it reach the wait and sends it `sig`.
  Finished interrupt_with(int sig, const std::vector<std::string>& extra_args = {}) {
    std::vector<std::string> args = {"play", scenario_.string(), "--timeout", "5"};
    args.insert(args.end(), extra_args.begin(), extra_args.end());
    auto child = ChildProcess::start(HUBRT_HUBCTL_PATH, args, domain_->env());
    EXPECT_TRUE(child) << child.error().message;
    if (!child) return {};
    // The description ("play: ...") is printed as the run begins, after the Ctrl-C handler is in
    // place; 20 s covers start-up under sanitizers.
    EXPECT_TRUE(child->wait_for_output("play: ", seconds(20))) << child->stdout_text();
    // Into the wait step (the outcome is the same if the signal comes before it starts).
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
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
  const Finished f = interrupt_with(SIGINT);
  EXPECT_TRUE(f.status.exited_with(130)) << f.status.describe() << "\n" << f.output;
  EXPECT_NE(f.output.find("play: interrupted at step 1 of 1 ("), std::string::npos) << f.output;
  EXPECT_NE(f.output.find("  STOP  "), std::string::npos) << f.output;
  EXPECT_EQ(f.output.find("not met within"), std::string::npos) << f.output;
  EXPECT_EQ(f.output.find("FAIL"), std::string::npos) << f.output;
}

TEST_F(HubctlPlayInterruptTest, SigtermSaysInterruptedAndExits143) {
  const Finished f = interrupt_with(SIGTERM);
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
  const Finished f = interrupt_with(SIGINT, {"--rounds", "0"});
  EXPECT_TRUE(f.status.exited_with(130)) << f.status.describe() << "\n" << f.output;
  EXPECT_NE(f.output.find("play: interrupted "), std::string::npos) << f.output;
  EXPECT_EQ(f.output.find("PASSED"), std::string::npos) << f.output;
}

}  // namespace
}  // namespace hubrt::integration
