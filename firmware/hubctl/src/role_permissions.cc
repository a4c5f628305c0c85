#include "role_permissions.h"

#include <algorithm>

#include <fmt/format.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hub_api/topic_names.h"

// hubd's search for hub files by name (/etc/hubrt/hubs, /usr/share/hubrt/hubs, ...), shared so
// that `--hub dock_ecu` names the same file for both programs.
#include "../../hubd/src/config_files.h"

namespace hubrt::hubctl {
namespace {

std::string dds(const std::string& ros_topic) {
  return "rt" + ros_topic;
}

void add_unique(std::vector<std::string>& topics, std::string topic) {
  if (std::find(topics.begin(), topics.end(), topic) == topics.end()) topics.push_back(std::move(topic));
}

Expected<void> add_hub(TopicPermissions& out, const std::string& hub, bool simulation) {
  auto file = hubd::find_config_file("hubs", hub);
  if (!file) return std::move(file).error();
  auto config = config::load_hub_config(*file);
  if (!config) return std::move(config).error();
  const std::string& ns = config->ros_namespace;
  if (config->layout == config::Layout::kHub) {
    add_unique(out.publish, dds(hub_api::hub_state_topic(ns, config->name)));
    add_unique(out.subscribe, dds(hub_api::hub_command_topic(ns, config->name)));
  } else {
    for (const config::NodeConfig& node : config->nodes) {
      add_unique(out.publish, dds(hub_api::node_state_topic(ns, config->name, node.name)));
      add_unique(out.subscribe, dds(hub_api::node_command_topic(ns, node.type)));
    }
  }
  for (const config::Subscription& subscription : config->subscriptions) {
    add_unique(out.subscribe, dds(subscription.topic));
  }
  add_unique(out.publish, dds(std::string(hub_api::kDiagnosticsTopic)));
  if (config->blackbox.enabled) {
    // Its black box's request and answer (firmware/assembly black_box_service.h).
    add_unique(out.subscribe, fmt::format("rt{}/{}/blackbox/request", ns, config->name));
    add_unique(out.publish, fmt::format("rt{}/{}/blackbox/written", ns, config->name));
  }
  if (simulation) {
    // Under the hub's namespace, as its sim bridge names them (sim_bridge_stage.h, sim_topic).
    add_unique(out.publish, fmt::format("rt{}/sim/{}/signals", ns, config->name));
    // Every topic a hub's sim bridge reads (firmware/sim: sim_bridge_stage.h, kSim*Topic): a
    // simulated hub that may not read one of them does not start.
    add_unique(out.subscribe, fmt::format("rt{}/sim/input", ns));
    add_unique(out.subscribe, fmt::format("rt{}/sim/badge", ns));
    add_unique(out.subscribe, fmt::format("rt{}/sim/fault", ns));
  }
  return {};
}

}  // namespace

Expected<TopicPermissions> role_permissions(const std::string& role, const std::vector<std::string>& hubs,
                                            bool simulation) {
  TopicPermissions out;
  if (role != "hub" && !hubs.empty()) {
    return make_error(ErrorCode::kInvalidArgument, "--hub is for --role hub only");
  }
  // Asking a hub for its black box (hubctl blackbox) actuates nothing and the hub bounds it (one
  // file per 10 s): planners and observers may.
  if (role == "planner") {
    out.publish = {"rt/*/command", "rt/*/blackbox/request"};
    out.subscribe = {"rt/*"};
    if (simulation) out.publish.emplace_back("rt/sim/*");
  } else if (role == "observer") {
    out.publish = {"rt/*/blackbox/request"};
    out.subscribe = {"rt/*"};
  } else if (role == "simulator") {
    out.publish = {"rt/sim/*"};
    out.subscribe = {"rt/sim/*"};
  } else if (role == "hub") {
    if (hubs.empty())
      return make_error(ErrorCode::kInvalidArgument, "--role hub needs --hub <hub file or type>");
    for (const std::string& hub : hubs) {
      if (auto ok = add_hub(out, hub, simulation); !ok) return std::move(ok).error();
    }
  } else {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("unknown role '{}': hub, planner, observer or simulator", role));
  }
  return out;
}

}  // namespace hubrt::hubctl
