// docs/foxglove-layout.json cannot rot: it is JSON of Foxglove's layout shape (every panel of the
// mosaic has a config and every config a place), and every topic and field path it names exists
// in the station as ./hubrt demo runs it — each hub file's State topics (hub_api/topic_names.h),
// each typed as the registered State whose echo is the node type's command (the hub type's
// conformance profile names it), plus /diagnostics. Plots plot numbers, state transitions a scalar.
// (The ecosystem tier also resolves the paths in the schemas a live hubctl foxglove advertises.)
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hubrt/config/hub_config.h"
#include "hubrt/hub_api/topic_names.h"
#include "hubrt/msgs/all_types.h"

#include "conformance_profile.h"
#include "conformance_target.h"

namespace hubrt::hubctl {
namespace {

using nlohmann::json;

const std::string kSource = HUBRT_SOURCE_DIR;
// The station of toolchain/demo: its hub files, in its order.
const char* const kStationHubFiles[] = {"hubs/station/hub-files/tool_ecu.yaml", "hubs/rsp_ecu/rsp_ecu.yaml",
                                        "hubs/dock_ecu/dock_ecu.yaml", "hubs/mir_com/mir_com.yaml",
                                        "hubs/station/hub-files/operator_hub.yaml"};

// The registered State type whose echo is `command_type`.
const msgs::TypeInfo* state_echoing(std::string_view command_type) {
  for (const msgs::TypeInfo* type : msgs::all_types().types()) {
    if (!is_state_type(*type)) continue;
    for (const msgs::FieldInfo& field : type->fields) {
      if (field.name == "echo" && field.nested != nullptr && field.nested->ros_name == command_type)
        return type;
    }
  }
  return nullptr;
}

// Every State topic of the station, with its type.
std::map<std::string, const msgs::TypeInfo*> station_topics() {
  std::map<std::string, const msgs::TypeInfo*> topics;
  for (const char* file : kStationHubFiles) {
    auto hub = config::load_hub_config(kSource + "/" + file);
    EXPECT_TRUE(hub) << hub.error().message;
    if (!hub) continue;
    auto profile = load_profile(kSource + "/hubs/" + hub->type + "/conformance.yaml");
    EXPECT_TRUE(profile) << profile.error().message;
    if (!profile) continue;
    if (hub->layout == config::Layout::kHub) {
      topics[hub_api::hub_state_topic(hub->ros_namespace, hub->name)] =
          state_echoing(profile->hub_layout->command_type);
      continue;
    }
    for (const config::NodeConfig& node : hub->nodes) {
      const CommandProfile* commands = profile->for_node_type(node.type);
      EXPECT_NE(commands, nullptr) << file << ": node type " << node.type << " has no conformance profile";
      if (commands == nullptr) continue;
      const msgs::TypeInfo* state = state_echoing(commands->command_type);
      EXPECT_NE(state, nullptr) << "no State echoes " << commands->command_type;
      topics[hub_api::node_state_topic(hub->ros_namespace, hub->name, node.name)] = state;
    }
  }
  topics[std::string(hub_api::kDiagnosticsTopic)] =
      msgs::all_types().find("diagnostic_msgs/msg/DiagnosticArray");
  return topics;
}

// The field `path` ("header.lifecycle") names in `type`, or nullptr and why in `problem`.
const msgs::FieldInfo* field_at(const msgs::TypeInfo& type, const std::string& path, std::string& problem) {
  const msgs::TypeInfo* current = &type;
  const msgs::FieldInfo* found = nullptr;
  std::istringstream parts(path);
  for (std::string name; std::getline(parts, name, '.');) {
    if (current == nullptr) {
      problem = "'" + std::string(found->name) + "' has no fields";
      return nullptr;
    }
    found = nullptr;
    for (const msgs::FieldInfo& field : current->fields) {
      if (field.name == name) found = &field;
    }
    if (found == nullptr) {
      problem = "no field '" + name + "' in " + std::string(current->ros_name);
      return nullptr;
    }
    current = found->kind == msgs::FieldKind::kStruct ? found->nested : nullptr;
  }
  return found;
}

bool is_scalar(const msgs::FieldInfo& field) {
  return field.kind != msgs::FieldKind::kStruct && field.kind != msgs::FieldKind::kSequence &&
         field.kind != msgs::FieldKind::kArray;
}

void collect_panels(const json& node, std::set<std::string>& out) {
  if (node.is_string()) {
    out.insert(node.get<std::string>());
    return;
  }
  ASSERT_TRUE(node.is_object() && node.contains("first") && node.contains("second")) << node.dump();
  collect_panels(node["first"], out);
  collect_panels(node["second"], out);
}

json load_layout() {
  std::ifstream in(kSource + "/docs/foxglove-layout.json");
  EXPECT_TRUE(in.good());
  return json::parse(in);  // throws, failing the test, when not JSON
}

TEST(FoxgloveLayout, IsAFoxgloveLayoutWhosePanelsAllHaveAConfigAndAPlace) {
  const json layout = load_layout();
  for (const char* key : {"configById", "globalVariables", "userNodes", "playbackConfig", "layout"})
    EXPECT_TRUE(layout.contains(key)) << key;
  std::set<std::string> placed;
  collect_panels(layout["layout"], placed);
  std::set<std::string> configured;
  for (const auto& [panel, config] : layout["configById"].items()) configured.insert(panel);
  EXPECT_EQ(placed, configured);
  std::set<std::string> kinds;
  for (const std::string& panel : configured) kinds.insert(panel.substr(0, panel.find('!')));
  // What issue 31 asks of it: plots, the lifecycles' transitions, /diagnostics, raw messages.
  EXPECT_EQ(kinds, (std::set<std::string>{"DiagnosticSummary", "Plot", "RawMessages", "StateTransitions"}));
}

TEST(FoxgloveLayout, EveryPathExistsInTheStationsTypes) {
  const auto topics = station_topics();
  ASSERT_GE(topics.size(), 8U);  // seven node States and /diagnostics
  const json layout = load_layout();
  std::set<std::string> plotted;
  std::set<std::string> lifecycles;
  for (const auto& [panel, config] : layout["configById"].items()) {
    const std::string kind = panel.substr(0, panel.find('!'));
    std::vector<std::string> paths;
    if (kind == "Plot" || kind == "StateTransitions") {
      for (const json& path : config["paths"]) paths.push_back(path["value"]);
    } else {
      paths.push_back(config.value(kind == "RawMessages" ? "topicPath" : "topicToRender", ""));
    }
    for (const std::string& path : paths) {
      const std::string topic = path.substr(0, path.find('.'));
      const auto known = topics.find(topic);
      ASSERT_NE(known, topics.end()) << panel << ": " << topic << " is no topic of the station";
      ASSERT_NE(known->second, nullptr) << topic;
      if (kind == "RawMessages" || kind == "DiagnosticSummary") {
        EXPECT_EQ(path, topic) << panel;
        continue;
      }
      std::string problem;
      const msgs::FieldInfo* field = field_at(*known->second, path.substr(topic.size() + 1), problem);
      ASSERT_NE(field, nullptr) << panel << ": " << path << ": " << problem;
      EXPECT_TRUE(is_scalar(*field)) << panel << ": " << path << " is not a scalar";
      if (kind == "Plot") {
        EXPECT_NE(field->kind, msgs::FieldKind::kString) << panel << ": " << path << " is text, not a number";
        plotted.insert(path);
      } else {
        lifecycles.insert(topic);
        EXPECT_TRUE(path.ends_with(".header.lifecycle")) << path;
      }
    }
  }
  EXPECT_TRUE(plotted.count("/tool_ecu/lift/state.position_mm")) << "the lift's position";
  EXPECT_TRUE(plotted.count("/tool_ecu/tool/state.torque_nm")) << "the smart tool's torque";
  // Every node's lifecycle: each State topic of the station.
  for (const auto& [topic, type] : topics) {
    if (topic != hub_api::kDiagnosticsTopic) {
      EXPECT_TRUE(lifecycles.count(topic)) << topic << "'s lifecycle is not shown";
    }
  }
}

}  // namespace
}  // namespace hubrt::hubctl
