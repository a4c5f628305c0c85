#include "hubrt/config/hub_config.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

namespace hubrt::config {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;

Expected<HubConfig> parse(const std::string& text) {
  auto root = YamlMap::load_string(text, "hub.yaml");
  if (!root) return std::move(root).error();
  return parse_hub_config(*root);
}

TEST(HubConfig, DefaultsAreSane) {
  auto config = parse("hub: dock_ecu\nnodes:\n  dock: {type: dock, slots: []}\n");
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->name, "dock_ecu") << "the instance name defaults to the hub type";
  EXPECT_EQ(config->period, milliseconds(100));
  EXPECT_EQ(config->command_timeout, milliseconds(1000));
  EXPECT_EQ(config->layout, Layout::kNodeType);
  EXPECT_EQ(config->ros_namespace, "");
  ASSERT_EQ(config->nodes.size(), 1u);
  EXPECT_EQ(config->nodes[0].name, "dock");
  EXPECT_EQ(config->nodes[0].type, "dock");
  EXPECT_TRUE(config->nodes[0].settings.has("slots"));
}

TEST(HubConfig, ReadsEverything) {
  auto config = parse(R"(hub: tool_ecu
name: tool1
rate_hz: 100
command_timeout_ms: 250
layout: hub
namespace: /station1/
diagnostics_hz: 2
nodes:
  tool: {type: smart_tool}
  lift: {type: lift}
subscriptions:
  rsp: {topic: /rsp_ecu/rsp/state, type: hub_msgs/msg/RspState, timeout_ms: 300}
)");
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->name, "tool1");
  EXPECT_EQ(config->period, milliseconds(10));
  EXPECT_EQ(config->command_timeout, milliseconds(250));
  EXPECT_EQ(config->layout, Layout::kHub);
  EXPECT_EQ(config->ros_namespace, "/station1");
  EXPECT_EQ(config->nodes.size(), 2u);
  ASSERT_EQ(config->subscriptions.size(), 1u);
  EXPECT_EQ(config->subscriptions[0].topic, "/rsp_ecu/rsp/state");
  EXPECT_EQ(config->subscriptions[0].timeout, milliseconds(300));
}

// The one rule for a namespace on a command line (hubsim, hubctl play) and in a hub file.
TEST(HubConfig, ANamespaceIsSlashAndNameTokensAsOnTheCommandLineAndInTheHubFile) {
  for (const char* good : {"/station1", "/plant/cell_a", "/A_1"})
    EXPECT_TRUE(check_ros_namespace(good)) << good;
  for (const char* bad : {"", "station1", "/", "/cell_a/", "//", "/a//b", "/1cell", "/_cell", "/cell-a"}) {
    auto checked = check_ros_namespace(bad);
    ASSERT_FALSE(checked) << bad;
    EXPECT_EQ(checked.error().code, ErrorCode::kInvalidArgument);
  }
  EXPECT_EQ(check_ros_namespace("cell").error().message, "must start with '/', e.g. /station1");
  EXPECT_EQ(check_ros_namespace("/cell-a").error().message, "'/cell-a' is not a valid ROS namespace");
  // The hub file also takes none ("" or "/") and a trailing '/', and names what was written.
  EXPECT_EQ(parse("hub: dock_ecu\nnamespace: /\nnodes:\n  dock: {type: dock, slots: []}\n")->ros_namespace,
            "");
  EXPECT_EQ(
      parse("hub: dock_ecu\nnamespace: /cell_a/\nnodes:\n  dock: {type: dock, slots: []}\n")->ros_namespace,
      "/cell_a");
  auto doubled = parse("hub: dock_ecu\nnamespace: /a//b/\nnodes:\n  dock: {type: dock, slots: []}\n");
  ASSERT_FALSE(doubled);
  EXPECT_NE(doubled.error().message.find("'/a//b/' is not a valid ROS namespace"), std::string::npos)
      << doubled.error().message;
}

TEST(HubConfig, TheBudgetOfImmediateStatesDefaultsTo10MsAndIsBounded) {
  auto config = parse("hub: dock_ecu\nnodes:\n  dock: {type: dock}\n");
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->immediate_state_interval, std::chrono::milliseconds(10));
  config = parse("hub: dock_ecu\nimmediate_state_interval_ms: 25\nnodes:\n  dock: {type: dock}\n");
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->immediate_state_interval, std::chrono::milliseconds(25));
  for (const char* bad : {"0", "1001", "-5", "fast"}) {
    config = parse(std::string("hub: dock_ecu\nimmediate_state_interval_ms: ") + bad +
                   "\nnodes:\n  dock: {type: dock}\n");
    ASSERT_FALSE(config) << bad;
    EXPECT_NE(config.error().message.find("immediate_state_interval_ms"), std::string::npos)
        << config.error().message;
  }
}

TEST(HubConfig, LongPeriodsGetALongerDefaultTimeout) {
  auto config = parse("hub: dock_ecu\nrate_hz: 1\nnodes:\n  dock: {type: dock}\n");
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->command_timeout, milliseconds(3000));
}

TEST(HubConfig, DuplicateNodeNamesAreRejected) {
  auto config = parse("hub: dock_ecu\nnodes:\n  dock: {type: dock}\n  dock: {type: dock}\n");
  ASSERT_FALSE(config);
  EXPECT_EQ(config.error().message, "hub.yaml:4:3: nodes.dock: declared twice (first at line 3)");
}

// yaml-cpp keeps the first of two equal keys for every look-up: these hubs used to run at 10 Hz,
// with a 1000 ms watchdog, and with the lift's first "work" position.
TEST(HubConfig, RepeatedSettingsAreRefusedWithFileAndLine) {
  auto rate = parse("hub: dock_ecu\nrate_hz: 10\nrate_hz: 500\nnodes:\n  dock: {type: dock}\n");
  ASSERT_FALSE(rate) << "ran at " << rate->rate_hz << " Hz";
  EXPECT_EQ(rate.error().message, "hub.yaml:3:1: rate_hz: declared twice (first at line 2)");
  auto timeout = parse(
      "hub: dock_ecu\ncommand_timeout_ms: 1000\nnodes:\n  dock: {type: dock}\ncommand_timeout_ms: 300\n");
  ASSERT_FALSE(timeout);
  EXPECT_EQ(timeout.error().message, "hub.yaml:5:1: command_timeout_ms: declared twice (first at line 2)");
  auto position = parse(R"(hub: tool_ecu
nodes:
  lift:
    type: lift
    positions:
      home: 380.0
      work: 120.0
      work: 20.0
)");
  ASSERT_FALSE(position);
  EXPECT_EQ(position.error().message,
            "hub.yaml:8:7: nodes.lift.positions.work: declared twice (first at line 7)");
}

TEST(HubConfig, InvalidUtf8InAHubFileIsRefused) {
  const fs::path path = fs::temp_directory_path() / fmt::format("hubrt-hub-utf8-{}.yaml", getpid());
  // A subscription's topic with a Latin-1 "ä" (E4) rather than UTF-8: the loader checks only
  // that it starts with '/', and the bytes would go on into a DDS topic name.
  std::ofstream(path) << "hub: dock_ecu\nnodes:\n  dock: {type: dock}\nsubscriptions:\n"
                         "  rsp: {topic: /rsp_ecu/rsp/st\xE4te, type: hub_msgs/msg/RspState}\n";
  auto config = load_hub_config(path.string());
  fs::remove(path);
  ASSERT_FALSE(config) << "loaded with topic '" << config->subscriptions.at(0).topic << "'";
  EXPECT_EQ(
      config.error().message,
      path.string() + ":5:31: not valid UTF-8 (byte 0xE4): configuration files are UTF-8 text (RFC 3629)");
}

// Every file in broken_hubs/ names its expected error in a first line "# expect: <message>".
TEST(HubConfig, BrokenFilesGiveTheirExpectedMessages) {
  const fs::path dir = fs::path(HUBRT_BROKEN_HUBS_DIR);
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::ifstream in(entry.path());
    std::string first;
    std::getline(in, first);
    const std::string marker = "# expect: ";
    ASSERT_EQ(first.rfind(marker, 0), 0u) << entry.path() << " lacks its '# expect:' line";
    const std::string expected = first.substr(marker.size());
    auto config = load_hub_config(entry.path().string());
    ASSERT_FALSE(config) << entry.path() << " loaded but should not";
    const std::string& message = config.error().message;
    // The message starts with the full path; compare from the file name on.
    const auto at = message.find(entry.path().filename().string());
    ASSERT_NE(at, std::string::npos) << message;
    EXPECT_EQ(message.substr(at), expected);
    ++checked;
  }
  EXPECT_GE(checked, 10);
}

}  // namespace
}  // namespace hubrt::config

namespace hubrt::config {
namespace {

TEST(HubConfig, SecuritySectionNamesFolderAndIdentity) {
  auto config = YamlMap::load_string(
      "hub: dock_ecu\nnodes:\n  dock: {type: dock}\n"
      "security: {dir: /etc/hubrt/security, identity: dock_ecu}\n",
      "/etc/hubrt/hubs/dock_ecu.yaml");
  ASSERT_TRUE(config) << config.error().message;
  auto hub = parse_hub_config(*config);
  ASSERT_TRUE(hub) << hub.error().message;
  ASSERT_TRUE(hub->security.has_value());
  EXPECT_EQ(hub->security->dir, "/etc/hubrt/security");
  EXPECT_EQ(hub->security->identity, "dock_ecu");
}

TEST(HubConfig, SecurityFolderIsRelativeToTheHubFile) {
  auto config = YamlMap::load_string(
      "hub: dock_ecu\nnodes:\n  dock: {type: dock}\n"
      "security: {dir: ../security, identity: dock_ecu}\n",
      "/etc/hubrt/hubs/dock_ecu.yaml");
  ASSERT_TRUE(config) << config.error().message;
  auto hub = parse_hub_config(*config);
  ASSERT_TRUE(hub) << hub.error().message;
  EXPECT_EQ(hub->security->dir, "/etc/hubrt/hubs/../security");
  auto none =
      parse_hub_config(*YamlMap::load_string("hub: dock_ecu\nnodes:\n  dock: {type: dock}\n", "x.yaml"));
  ASSERT_TRUE(none);
  EXPECT_FALSE(none->security.has_value()) << "no section: unsecured";
}

TEST(HubConfig, SecuritySectionNeedsAnIdentityAndNothingElse) {
  for (const char* section :
       {"security: {dir: /etc/hubrt/security}\n", "security: {dir: /x, identity: a, password: b}\n",
        "security: {dir: '', identity: a}\n"}) {
    auto config = YamlMap::load_string(std::string("hub: dock_ecu\nnodes:\n  dock: {type: dock}\n") + section,
                                       "x.yaml");
    ASSERT_TRUE(config) << section;
    EXPECT_FALSE(parse_hub_config(*config)) << section;
  }
}

// The black box (issue 30): on by default with a minute in memory sized from the hub's rates
// (memory_kib absent; blackbox/ring_size.h), or in what memory_kib says; each setting bounded; a directory
// must be absolute (a relative one would depend on where hubd happened to start).
TEST(HubConfig, BlackBoxDefaultsAndBounds) {
  auto defaults = parse("hub: dock_ecu\nnodes:\n  dock: {type: dock, slots: []}\n");
  ASSERT_TRUE(defaults) << defaults.error().message;
  EXPECT_TRUE(defaults->blackbox.enabled);
  EXPECT_EQ(defaults->blackbox.span, std::chrono::seconds(60));
  EXPECT_FALSE(defaults->blackbox.memory_bytes.has_value());
  EXPECT_EQ(defaults->blackbox.directory, "");
  EXPECT_EQ(defaults->blackbox.directory_bytes, std::uint64_t{64} << 20);
  auto set = parse(
      "hub: dock_ecu\nnodes:\n  dock: {type: dock, slots: []}\n"
      "blackbox: {seconds: 30, memory_kib: 1024, directory: /srv/box, directory_mib: 10, enabled: false}\n");
  ASSERT_TRUE(set) << set.error().message;
  EXPECT_FALSE(set->blackbox.enabled);
  EXPECT_EQ(set->blackbox.span, std::chrono::seconds(30));
  EXPECT_EQ(set->blackbox.memory_bytes, std::optional<std::size_t>(std::size_t{1} << 20));
  EXPECT_EQ(set->blackbox.directory, "/srv/box");
  EXPECT_EQ(set->blackbox.directory_bytes, std::uint64_t{10} << 20);
  for (const char* bad :
       {"blackbox: {seconds: 0}", "blackbox: {memory_kib: 10}", "blackbox: {directory: box}",
        "blackbox: {speed: 3}", "blackbox: {directory_mib: 0}"}) {
    auto refused =
        parse(std::string("hub: dock_ecu\nnodes:\n  dock: {type: dock, slots: []}\n") + bad + "\n");
    EXPECT_FALSE(refused) << bad;
    if (!refused) {
      EXPECT_NE(refused.error().message.find("hub.yaml:4"), std::string::npos) << refused.error().message;
    }
  }
}

}  // namespace
}  // namespace hubrt::config
