// The conformance suite's data: thresholds with defaults and overrides, and the profiles hubs ship.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "hubrt/msgs/all_types.h"

#include "command_channel.h"
#include "conformance_profile.h"
#include "conformance_target.h"
#include "conformance_thresholds.h"
#include "dock_ecu_reflect.h"
#include "dock_reflect.h"

namespace hubrt::hubctl {
namespace {

// A file in a private temporary folder, removed with it.
class TempFile {
 public:
  explicit TempFile(const std::string& text) {
    dir_ = std::filesystem::temp_directory_path() /
           ("hubctl-conformance-test-" + std::to_string(getpid()) + "-" + std::to_string(counter_++));
    std::filesystem::create_directories(dir_);
    path_ = (dir_ / "file.yaml").string();
    std::ofstream(path_) << text;
  }
  ~TempFile() { std::filesystem::remove_all(dir_); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  static inline int counter_ = 0;
  std::filesystem::path dir_;
  std::string path_;
};

TEST(Thresholds, EveryDefaultHasAReason) {
  const Thresholds defaults = default_thresholds();
  for (const ThresholdSpec& spec : threshold_specs()) {
    EXPECT_GT(spec.reason.size(), 40u) << spec.key;
    EXPECT_EQ(defaults.*spec.field, spec.default_value) << spec.key;
  }
  EXPECT_EQ(defaults.rate_error_pct, 1.0);
  EXPECT_NE(describe_thresholds(defaults).find("jitter_floor_ms"), std::string::npos);
}

TEST(Thresholds, FileAndAssignmentsOverrideDefaults) {
  TempFile file("echo_p99_ms: 50   # sanitizer builds\nrate_error_pct: 3\n");
  Thresholds t = default_thresholds();
  ASSERT_TRUE(load_thresholds_file(file.path(), t));
  EXPECT_EQ(t.echo_p99_ms, 50);
  EXPECT_EQ(t.rate_error_pct, 3);
  EXPECT_EQ(t.echo_p50_ms, default_thresholds().echo_p50_ms);
  ASSERT_TRUE(apply_threshold_assignment("echo_p50_ms=7.5", t));
  EXPECT_EQ(t.echo_p50_ms, 7.5);
}

TEST(Thresholds, MistakesAreNamed) {
  Thresholds t = default_thresholds();
  TempFile unknown("echo_p99: 50\n");
  auto loaded = load_thresholds_file(unknown.path(), t);
  ASSERT_FALSE(loaded);
  EXPECT_NE(loaded.error().message.find(":1:11: echo_p99: unknown threshold"), std::string::npos)
      << loaded.error().message;
  TempFile negative("echo_p99_ms: -1\n");
  EXPECT_FALSE(load_thresholds_file(negative.path(), t));
  EXPECT_FALSE(apply_threshold_assignment("echo_p99_ms", t));
  EXPECT_FALSE(apply_threshold_assignment("echo_p99_ms=fast", t));
  EXPECT_FALSE(apply_threshold_assignment("nope=1", t));
}

TEST(Profile, TheDockProfileLoadsAndMakesCommandsTheDockAccepts) {
  auto profile = load_profile(std::string(HUBRT_SOURCE_DIR) + "/hubs/dock_ecu/conformance.yaml");
  ASSERT_TRUE(profile) << profile.error().message;
  EXPECT_EQ(profile->hub_type, "dock_ecu");
  const CommandProfile* dock = profile->for_node_type("dock");
  ASSERT_NE(dock, nullptr);
  EXPECT_EQ(profile->node_type_of_command("hub_msgs/msg/DockCommand"), "dock");
  const msgs::TypeInfo& type = msgs::type_info_of<hub_msgs_msg_dds__DockCommand_>();
  auto first = prepare_command(type, "dock", "dock1", dock->probes[0], "probe 1");
  ASSERT_TRUE(first) << first.error().message;
  EXPECT_EQ(first->json.dump(), R"({"target_type":"dock","target_name":"dock1","action":"monitor"})");
  auto second = prepare_command(type, "dock", "dock1", dock->probes[1], "probe 2");
  ASSERT_TRUE(second);
  EXPECT_NE(first->json, second->json);
  ASSERT_TRUE(profile->hub_layout);
  auto hub = prepare_command(msgs::type_info_of<hub_msgs_msg_dds__DockEcuCommand_>(), "dock_ecu", "dock_ecu",
                             profile->hub_layout->probes[1], "probe 2");
  ASSERT_TRUE(hub) << hub.error().message;
  EXPECT_EQ(hub->json["dock"]["action"], "reset");
}

TEST(Profile, AFieldTheCommandTypeLacksIsReportedAtItsLine) {
  TempFile file(
      "hub_type: x\nnode_types:\n  dock:\n    probes:\n      - {action: monitor}\n      - {acton: reset}\n"
      "    reset: {action: reset}\n");
  auto profile = load_profile(file.path());
  ASSERT_TRUE(profile) << profile.error().message;
  auto command = prepare_command(msgs::type_info_of<hub_msgs_msg_dds__DockCommand_>(), "dock", "dock",
                                 profile->node_types.at("dock").probes[1], "probe 2");
  ASSERT_FALSE(command);
  EXPECT_NE(command.error().message.find(":6:"), std::string::npos) << command.error().message;
  EXPECT_NE(command.error().message.find("acton"), std::string::npos) << command.error().message;
}

TEST(Profile, BrokenProfilesAreRefusedWithTheReason) {
  const std::pair<const char*, const char*> cases[] = {
      {"hub_type: x\nnode_types:\n  dock:\n    probes: [{action: a}]\n    reset: {action: reset}\n", "two"},
      {"hub_type: x\nnode_types:\n  dock:\n    probes: [{action: a}, {action: a}]\n    reset: {action: "
       "reset}\n",
       "identical"},
      {"hub_type: x\nnode_types:\n  dock:\n    probes: [{action: a}, {action: b}]\n", "reset"},
      {"hub_type: x\nnode_types:\n  dock:\n    probes: [{action: [a]}, {action: b}]\n    reset: {action: "
       "r}\n",
       "single value"},
      {"hub_type: x\nrate: 10\nnode_types: {}\n", "unknown key"},
  };
  for (const auto& [text, expected] : cases) {
    TempFile file(text);
    auto profile = load_profile(file.path());
    ASSERT_FALSE(profile) << text;
    EXPECT_NE(profile.error().message.find(expected), std::string::npos) << profile.error().message;
  }
}

TEST(Target, TopicNamesSplitIntoNamespaceHubAndNode) {
  auto node = split_state_topic("/station1/dock_ecu/dock/state", TargetLayout::kNodeType);
  ASSERT_TRUE(node);
  EXPECT_EQ(node->ros_namespace, "/station1");
  EXPECT_EQ(node->hub_name, "dock_ecu");
  EXPECT_EQ(node->node_name, "dock");
  auto hub = split_state_topic("/dock_ecu/state", TargetLayout::kHub);
  ASSERT_TRUE(hub);
  EXPECT_EQ(hub->ros_namespace, "");
  EXPECT_EQ(hub->hub_name, "dock_ecu");
  EXPECT_FALSE(split_state_topic("/dock_ecu/state", TargetLayout::kNodeType));
  EXPECT_FALSE(split_state_topic("/dock_ecu/dock/status", TargetLayout::kNodeType));
}

// Issue 16, point 7: `hubctl conformance` without --hub tested hubsim's world State as a hub.
TEST(Target, TheSimulationsStateTopicsAreNoHubs) {
  EXPECT_FALSE(is_hub_state_topic("/sim/station/state"));
  EXPECT_FALSE(is_hub_state_topic("/sim/dock_ecu/state"));
  EXPECT_TRUE(is_hub_state_topic("/dock_ecu/dock/state"));
  EXPECT_TRUE(is_hub_state_topic("/station1/dock_ecu/dock/state"));
  EXPECT_TRUE(is_hub_state_topic("/simulator_hub/state")) << "only the /sim/ namespace is the simulation's";
}

TEST(Target, ResolvedFromDiagnosticsAndTheProfile) {
  const msgs::TypeInfo& state = msgs::type_info_of<hub_msgs_msg_dds__DockState_>();
  EXPECT_TRUE(is_state_type(state));
  EXPECT_FALSE(is_hub_state_type(state));
  EXPECT_TRUE(is_hub_state_type(msgs::type_info_of<hub_msgs_msg_dds__DockEcuState_>()));

  DiagnosticsByHub diagnostics;
  absorb_diagnostics(nlohmann::ordered_json::parse(R"({"status": [
      {"name": "left: cycle", "values": [{"key": "hub_type", "value": "dock_ecu"},
                                          {"key": "period_ms", "value": "20"},
                                          {"key": "command_timeout_ms", "value": "500"}]},
      {"name": "left: dock", "values": [{"key": "node_type", "value": "dock"}]}]})"),
                     diagnostics);
  // The profile is found through $HUBRT_CONFIG_DIR, as an installed hubctl finds it: cross builds
  // compile in no source-tree fallback. Single-threaded test, so setenv is safe here.
  ASSERT_EQ(setenv("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR, 1), 0);  // NOLINT(concurrency-mt-unsafe)
  ProfileBook profiles;
  const Target t = resolve_target("/cell/left/dock/state", state, diagnostics, profiles, {});
  unsetenv("HUBRT_CONFIG_DIR");  // NOLINT(concurrency-mt-unsafe)
  EXPECT_TRUE(t.command_problems.empty()) << t.command_problems.front();
  EXPECT_EQ(t.command_topic, "/cell/dock/command");
  EXPECT_EQ(t.target_type, "dock");
  EXPECT_EQ(t.target_name, "dock");
  EXPECT_DOUBLE_EQ(t.period_s, 0.02);
  EXPECT_EQ(t.period_source, "/diagnostics");
  EXPECT_DOUBLE_EQ(t.timeout_s, 0.5);
  ASSERT_NE(t.commands, nullptr);

  // Without diagnostics the profile's command_type names the node type, its rate the period.
  const Target quiet =
      resolve_target("/cell/left/dock/state", state, {}, profiles, {std::nullopt, 750.0, "dock_ecu"});
  EXPECT_EQ(quiet.node_type, "dock");
  EXPECT_DOUBLE_EQ(quiet.period_s, 0.1);
  EXPECT_EQ(quiet.timeout_source, "--command-timeout");

  // Nothing known about the hub: it cannot be commanded, and the reason says why.
  const Target unknown = resolve_target("/cell/left/dock/state", state, {}, profiles, {});
  EXPECT_EQ(unknown.commands, nullptr);
  EXPECT_FALSE(unknown.command_problems.empty());
}

}  // namespace
}  // namespace hubrt::hubctl
