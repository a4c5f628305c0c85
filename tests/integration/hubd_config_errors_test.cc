// hubd refuses broken configuration with a message that names file, line and problem, and exit
// code 2, before touching any device.
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/test_support/hub_process.h"

namespace hubrt::integration {
using test_support::Finished;
using test_support::run_hubd;
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

TEST_F(HubdConfigErrorsTest, ARepeatedKeyInAHubFileIsRefusedAtItsLine) {
  const std::string hub =
      write("dock.yaml", "hub: dock_ecu\nrate_hz: 10\nnodes:\n  dock: {type: dock}\nrate_hz: 500\n");
  const Finished f = run({"--board", "host-sim", "--hub", hub, "--check"});
  EXPECT_TRUE(f.status.exited_with(2)) << f.status.describe() << f.output;
  EXPECT_NE(f.output.find(hub + ":5:1: rate_hz: declared twice (first at line 2)"), std::string::npos)
      << f.output;
}

// Anywhere in the file: here in a comment (Latin-1 "Träger"), which hubd used to pass over.
TEST_F(HubdConfigErrorsTest, InvalidUtf8InAHubFileIsRefusedAtItsLine) {
  const std::string hub = write("dock.yaml", "hub: dock_ecu\nnodes:\n  dock: {type: dock}  # Tr\xE4ger\n");
  const Finished f = run({"--board", "host-sim", "--hub", hub, "--check"});
  EXPECT_TRUE(f.status.exited_with(2)) << f.status.describe() << f.output;
  EXPECT_NE(f.output.find(hub + ":3:27: not valid UTF-8 (byte 0xE4)"), std::string::npos) << f.output;
}

TEST_F(HubdConfigErrorsTest, ADirectoryGivenAsHubFileIsSaidToBeOne) {
  fs::create_directory(dir_ / "dock_ecu.yaml");
  const std::string hub = (dir_ / "dock_ecu.yaml").string();
  const Finished f = run({"--board", "host-sim", "--hub", hub, "--check"});
  EXPECT_TRUE(f.status.exited_with(2)) << f.status.describe() << f.output;
  EXPECT_NE(f.output.find("hubs file " + hub + ": is a directory, not a file"), std::string::npos)
      << f.output;
  EXPECT_EQ(f.output.find("does not exist"), std::string::npos) << f.output;
}

TEST_F(HubdConfigErrorsTest, ASymbolicLinkLoopGivenAsBoardFileIsSaidToBeOne) {
  const fs::path a = dir_ / "a.yaml";
  const fs::path b = dir_ / "b.yaml";
  fs::create_symlink(b, a);
  fs::create_symlink(a, b);
  const Finished f = run({"--board", a.string(), "--hub", "dock_ecu", "--check"});
  EXPECT_TRUE(f.status.exited_with(2)) << f.status.describe() << f.output;
  EXPECT_NE(f.output.find("boards file " + a.string() +
                          ": is a symbolic link loop (too many levels of symbolic links)"),
            std::string::npos)
      << f.output;
}

// Found by name in a search folder: a loop there is reported, not skipped as if absent.
TEST_F(HubdConfigErrorsTest, ASymbolicLinkLoopInASearchFolderIsReported) {
  fs::create_directories(dir_ / "boards");
  const fs::path loop = dir_ / "boards" / "looped.yaml";
  fs::create_symlink(loop, loop);
  auto finished = run_hubd(*domain_, {"--board", "looped", "--hub", "dock_ecu", "--check"}, seconds(30),
                           {{"HUBRT_CONFIG_DIR", dir_.string()}});
  ASSERT_TRUE(finished) << finished.error().message;
  EXPECT_TRUE(finished->status.exited_with(2)) << finished->status.describe() << finished->output;
  EXPECT_NE(finished->output.find("boards file " + loop.string() + ": is a symbolic link loop"),
            std::string::npos)
      << finished->output;
}

TEST_F(HubdConfigErrorsTest, BadCommandLineIsAUsageError) {
  const Finished f = run({"--board", "host-sim", "--backend", "quantum"});
  EXPECT_FALSE(f.status.exited_with(0)) << f.status.describe();
  EXPECT_NE(f.output.find("quantum"), std::string::npos) << f.output;
}

}  // namespace
}  // namespace hubrt::integration
