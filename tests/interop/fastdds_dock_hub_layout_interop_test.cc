// The Fast DDS planner against the Dock ECU in the hub-oriented layout: one DockEcuCommand on
// /dock_ecu/command carrying the node's fragment, one DockEcuState on /dock_ecu/state carrying
// the node's State — nested types and per-hub addressing, where a wrong target is rejected
// (issue 13 point 3; docs/interop.md).
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/test_support/hub_process.h"

#include "fastdds_dock_planner.h"

namespace hubrt::interop {
namespace {

using hub_msgs::msg::DockEcuState;
namespace fs = std::filesystem;
namespace lifecycle = hub_msgs::msg::StateHeader_Constants;

hub_msgs::msg::DockEcuCommand hub_command(const std::string& hub_name, const std::string& fragment_name,
                                          const std::string& action) {
  hub_msgs::msg::DockEcuCommand command;
  command.target_type("dock_ecu");
  command.target_name(hub_name);
  command.action("apply");
  command.dock(dock_command("", fragment_name, action));
  return command;
}

class FastDdsDockHubLayoutInteropTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire_outside_ephemeral_ports();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    // The shipped hub file, switched to the hub layout.
    std::ifstream in(std::string(HUBRT_SOURCE_DIR) + "/hubs/dock_ecu/dock_ecu.yaml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto at = text.find("layout: node_type");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, std::string("layout: node_type").size(), "layout: hub");
    hub_file_ = fs::temp_directory_path() / fmt::format("hubrt-fastdds-dock-hub-{}.yaml", getpid());
    std::ofstream(hub_file_) << text;

    auto planner = FastDdsDockEcuPlanner::create(domain_->domain_id(), DockEcuHubTypes::kCommandTopic,
                                                 DockEcuHubTypes::kStateTopic);
    ASSERT_TRUE(planner) << planner.error().message;
    planner_ = std::move(*planner);
    test_support::HubProcessOptions options;
    options.hub = hub_file_.string();
    auto hub = test_support::HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(planner_->wait_for_hub(kPatience)) << planner_->match_report() << "\n" << hub_->output();
  }
  void TearDown() override {
    if (planner_) (void)planner_->stop_repeating();
    fs::remove(hub_file_);
  }

  std::optional<DockEcuState> state_where(const std::function<bool(const DockEcuState&)>& predicate) {
    auto received = planner_->wait_for_state(predicate, kPatience);
    if (!received) return std::nullopt;
    return received->state;
  }

  std::optional<test_support::TestDomain> domain_;
  fs::path hub_file_;
  std::unique_ptr<FastDdsDockEcuPlanner> planner_;
  std::optional<test_support::HubProcess> hub_;
};

TEST_F(FastDdsDockHubLayoutInteropTest, TheHubCommandReachesTheNodeAndTheHubStateCarriesItsState) {
  planner_->start_repeating(hub_command("dock_ecu", "", "monitor"), kCommandPeriod);
  auto state = state_where([](const DockEcuState& s) { return s.fresh_msg() && s.dock().fresh_msg(); });
  ASSERT_TRUE(state) << hub_->output();
  EXPECT_EQ(state->name(), "dock_ecu");
  EXPECT_EQ(state->echo().action(), "apply");
  EXPECT_EQ(state->echo().dock().action(), "monitor");
  EXPECT_EQ(state->dock().name(), "dock");
  EXPECT_EQ(state->dock().echo().target_type(), "dock") << "an empty fragment target means this node";
  EXPECT_EQ(state->dock().header().lifecycle(), lifecycle::LIFECYCLE_OPERATIONAL);
  EXPECT_EQ(state->dock().slots().size(), 4u);
  EXPECT_TRUE(state->error_list().empty()) << joined_errors(*state);
  EXPECT_TRUE(state->dock().error_list().empty()) << joined_errors(state->dock());
}

TEST_F(FastDdsDockHubLayoutInteropTest, ACommandForAnotherHubIsRejectedByTheHub) {
  planner_->start_repeating(hub_command("dock_ecu9", "", "monitor"), kCommandPeriod);
  auto rejected = state_where([](const DockEcuState& s) {
    return joined_errors(s).find("wrong target: addressed to 'dock_ecu9', this node is 'dock_ecu'") !=
           std::string::npos;
  });
  ASSERT_TRUE(rejected) << hub_->output();
  EXPECT_FALSE(rejected->fresh_msg());
  EXPECT_FALSE(rejected->dock().fresh_msg()) << "nothing reached the node";
}

TEST_F(FastDdsDockHubLayoutInteropTest, AFragmentForAnotherNodeIsRejectedByTheNode) {
  planner_->start_repeating(hub_command("dock_ecu", "dock9", "monitor"), kCommandPeriod);
  auto rejected = state_where([](const DockEcuState& s) {
    return joined_errors(s.dock()).find("wrong target: addressed to 'dock9', this node is 'dock'") !=
           std::string::npos;
  });
  ASSERT_TRUE(rejected) << hub_->output();
  EXPECT_TRUE(rejected->fresh_msg()) << "the hub command itself is valid";
  EXPECT_FALSE(rejected->dock().fresh_msg()) << "nothing took effect in the node";
  EXPECT_NE(rejected->dock().header().lifecycle(), lifecycle::LIFECYCLE_OPERATIONAL);
}

}  // namespace
}  // namespace hubrt::interop
