// The Dock ECU in the hub-oriented layout: one command and one State topic for the hub; the
// distributor hands the node its fragment, the collector assembles the hub State.
#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/typed.h"

#include "dock_messages.h"
#include "hub_process.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockEcuTypes;
using HubCommand = DockEcuTypes::Command::Wire;
using HubState = DockEcuTypes::State::Wire;
using std::chrono::milliseconds;
namespace fs = std::filesystem;

constexpr auto kPatience = std::chrono::seconds(15);  // a loaded 2-core machine, sanitizer builds

std::string errors_of(const hub_msgs_msg_dds__DockState_& s) {
  std::string out;
  for (std::uint32_t i = 0; i < s.error_list._length; ++i) out += std::string(s.error_list._buffer[i]) + "; ";
  return out;
}

class HubdDockHubLayoutTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    // The shipped configuration with the hub layout.
    std::ifstream in(std::string(HUBRT_SOURCE_DIR) + "/hubs/dock_ecu/dock_ecu.yaml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto at = text.find("layout: node_type");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 17, "layout: hub");
    hub_file_ = fs::temp_directory_path() / fmt::format("hubrt-dock-hub-layout-{}.yaml", getpid());
    std::ofstream(hub_file_) << text;

    auto participant = dds::Participant::create(domain_->config(), "test-planner");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    auto command_topic = dds::Topic<HubCommand>::create(*participant_, "/dock_ecu/command");
    ASSERT_TRUE(command_topic) << command_topic.error().message;
    command_topic_.emplace(std::move(*command_topic));
    auto writer = dds::Writer<HubCommand>::create(*participant_, *command_topic_);
    ASSERT_TRUE(writer);
    writer_.emplace(std::move(*writer));
    auto state_topic = dds::Topic<HubState>::create(*participant_, "/dock_ecu/state");
    ASSERT_TRUE(state_topic);
    state_topic_.emplace(std::move(*state_topic));
    auto reader = dds::Reader<HubState>::create(*participant_, *state_topic_);
    ASSERT_TRUE(reader);
    reader_.emplace(std::move(*reader));

    HubProcessOptions options;
    options.hub = hub_file_.string();
    auto hub = HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(writer_->wait_for_readers(1, kPatience)) << hub_->output();
  }
  void TearDown() override { fs::remove(hub_file_); }

  bool wait_for_state(const std::function<bool(const HubState&)>& predicate) {
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    while (std::chrono::steady_clock::now() < deadline) {
      const Result<bool> taken = reader_->take_next(state_);
      if (taken.is_ok() && taken.value()) {
        if (predicate(state_.get())) return true;
        continue;
      }
      std::this_thread::sleep_for(milliseconds(2));
    }
    return false;
  }

  // A planner thread repeating one hub command until stopped.
  void start_planner(const char* fragment_name) {
    planner_ = std::thread([this, fragment_name] {
      while (sending_) {
        HubCommand command{};
        hubrt::msgs::typed::assign(command.target_type, "dock_ecu");
        hubrt::msgs::typed::assign(command.target_name, "dock_ecu");
        hubrt::msgs::typed::assign(command.action, "apply");
        hubrt::msgs::typed::assign(command.dock.target_type, "");
        hubrt::msgs::typed::assign(command.dock.target_name, fragment_name);
        hubrt::msgs::typed::assign(command.dock.action, "monitor");
        writer_->write(command).ignore();
        std::this_thread::sleep_for(milliseconds(50));
      }
    });
  }
  void stop_planner() {
    sending_ = false;
    if (planner_.joinable()) planner_.join();
  }

  std::optional<test_support::TestDomain> domain_;
  fs::path hub_file_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<HubCommand>> command_topic_;
  std::optional<dds::Writer<HubCommand>> writer_;
  std::optional<dds::Topic<HubState>> state_topic_;
  std::optional<dds::Reader<HubState>> reader_;
  dds::Sample<HubState> state_;
  std::optional<HubProcess> hub_;
  std::atomic<bool> sending_{true};
  std::thread planner_;
};

TEST_F(HubdDockHubLayoutTest, TheHubCommandReachesTheNodeAndTheHubStateCarriesIt) {
  start_planner("");
  const bool seen = wait_for_state([](const HubState& s) {
    return s.fresh_msg && std::string(s.echo.action) == "apply" && s.dock.fresh_msg &&
           std::string(s.dock.echo.action) == "monitor" && std::string(s.dock.echo.target_name) == "dock";
  });
  ASSERT_TRUE(seen) << hub_->output();
  EXPECT_STREQ(state_.get().name, "dock_ecu");
  EXPECT_STREQ(state_.get().dock.name, "dock");
  EXPECT_STREQ(state_.get().dock.echo.target_type, "dock") << "an empty fragment target means this node";
  EXPECT_EQ(state_.get().dock.slots._length, 4u);
  // The planner stops: the hub-level watchdog trips, then the node's (no more fragments).
  stop_planner();
  ASSERT_TRUE(wait_for_state([](const HubState& s) { return !s.fresh_msg && !s.dock.fresh_msg; }))
      << hub_->output();
  EXPECT_NE(errors_of(state_.get().dock).find("command timeout"), std::string::npos)
      << errors_of(state_.get().dock);
}

TEST_F(HubdDockHubLayoutTest, AFragmentForAnotherNodeIsRejectedByTheNode) {
  start_planner("dock9");
  const bool rejected = wait_for_state([](const HubState& s) {
    return s.fresh_msg && errors_of(s.dock).find("wrong target: addressed to 'dock9', this node is 'dock'") !=
                              std::string::npos;
  });
  stop_planner();
  ASSERT_TRUE(rejected) << hub_->output();
  EXPECT_FALSE(state_.get().dock.fresh_msg) << "nothing took effect in the node";
}

}  // namespace
}  // namespace hubrt::integration
