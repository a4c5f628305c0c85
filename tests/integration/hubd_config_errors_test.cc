// hubd refuses broken configuration with a message that names file, line and problem, and exit
// code 2, before touching any device.
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hub_process.h"

namespace hubrt::integration {
namespace {

namespace fs = std::filesystem;
using std::chrono::seconds;

class HubdConfigErrorsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    dir_ = fs::temp_directory_path() / fmt::format("hubrt-config-{}", getpid());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }

  Finished run(const std::vector<std::string>& args) {
    auto finished = run_hubd(*domain_, args, seconds(30));
    EXPECT_TRUE(finished) << finished.error().message;
    return finished ? *finished : Finished{};
  }

  std::optional<test_support::TestDomain> domain_;
  fs::path dir_;
};

TEST_F(HubdConfigErrorsTest, AnUnknownBoardNameListsWhereItLooked) {
  const Finished f = run({"--board", "rpi9-nothing", "--hub", "dock_ecu"});
  EXPECT_TRUE(f.status.exited_with(2)) << f.status.describe();
  EXPECT_NE(f.output.find("no boards file named 'rpi9-nothing'; looked for:"), std::string::npos) << f.output;
}

TEST_F(HubdConfigErrorsTest, ABrokenHubFileNamesFileLineAndProblem) {
  const std::string hub = write("dock.yaml", "hub: dock_ecu\nrate_hz: fast\nnodes:\n  dock: {type: dock}\n");
  const Finished f = run({"--board", "host-sim", "--hub", hub});
  EXPECT_TRUE(f.status.exited_with(2)) << f.status.describe();
  EXPECT_NE(f.output.find(hub + ":2:10: rate_hz: expected a number in [0.01, 1000], got 'fast'"),
            std::string::npos)
      << f.output;
}

TEST_F(HubdConfigErrorsTest, ASlotWiredToAMissingSignalIsRefused) {
  const std::string hub = write("dock.yaml",
                                "hub: dock_ecu\nnodes:\n  dock:\n    type: dock\n    slots:\n"
                                "      - {name: extra, signal: dock.slot.nowhere}\n");
  const Finished f = run({"--board", "host-sim", "--hub", hub});
  EXPECT_TRUE(f.status.exited_with(2)) << f.status.describe();
  EXPECT_NE(f.output.find("dock.slot.nowhere"), std::string::npos) << f.output;
}

TEST_F(HubdConfigErrorsTest, AnUnknownHubTypeSaysWhichAreKnown) {
  const std::string hub = write("x.yaml", "hub: coffee_machine\nnodes:\n  pot: {type: pot}\n");
  const Finished f = run({"--board", "host-sim", "--hub", hub});
  EXPECT_TRUE(f.status.exited_with(2)) << f.status.describe();
  EXPECT_NE(f.output.find("unknown hub type 'coffee_machine' (this hubd knows: dock_ecu"), std::string::npos)
      << f.output;
}

TEST_F(HubdConfigErrorsTest, CheckValidatesWithoutRunning) {
  const Finished f = run({"--board", "host-sim", "--hub", "dock_ecu", "--check"});
  EXPECT_TRUE(f.status.exited_with(0)) << f.status.describe() << f.output;
  EXPECT_NE(f.output.find("configuration OK: hub 'dock_ecu'"), std::string::npos) << f.output;
}

TEST_F(HubdConfigErrorsTest, BadCommandLineIsAUsageError) {
  const Finished f = run({"--board", "host-sim", "--backend", "quantum"});
  EXPECT_FALSE(f.status.exited_with(0)) << f.status.describe();
  EXPECT_NE(f.output.find("quantum"), std::string::npos) << f.output;
}

}  // namespace
}  // namespace hubrt::integration
