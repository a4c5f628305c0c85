// What hubs say about themselves on /diagnostics (diagnostic_msgs/DiagnosticArray): per hub its
// type, cycle period and command timeout; per node its type. The conformance suite learns the
// expected rate and the watchdog timeout here, from the wire, instead of from the hub's files.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "hubrt/base/status.h"
#include "hubrt/dds/participant.h"

namespace hubrt::hubctl {

struct HubDiagnostics {
  std::string hub_type;
  std::optional<double> period_ms;
  std::optional<double> command_timeout_ms;
  std::optional<double> immediate_state_interval_ms;           // the budget of immediate States
  std::map<std::string, std::string, std::less<>> node_types;  // node name -> node type
};

using DiagnosticsByHub = std::map<std::string, HubDiagnostics, std::less<>>;

// Reads one DiagnosticArray (as msgs::to_json gives it) into `hubs`. Status "<hub>: cycle" with
// key hub_type describes a hub (period_ms, command_timeout_ms, immediate_state_interval_ms); a status "<hub>:
// <node>" with key node_type describes a node. Other statuses are ignored.
void absorb_diagnostics(const nlohmann::ordered_json& array, DiagnosticsByHub& hubs);

// Listens on /diagnostics until every hub in `wanted` has described itself and its nodes, or
// `timeout_s` passes; returns what was heard (possibly less than wanted). Hubs publish
// diagnostics at 1 Hz by default, so allow a little more than a second.
// Errors: the DDS entities that could not be created.
Expected<DiagnosticsByHub> listen_for_diagnostics(const dds::Participant& participant,
                                                  const std::set<std::string>& wanted, double timeout_s);

// Why a bridged topic carries nothing: what `hubctl list` shows next to it.
struct BridgeQuiet {
  std::string label;    // "DROPPED OVER A BOUND" or "SILENT"
  std::string message;  // the bridge's status message
};

// The BridgeQuiet of one hubbridge status (diagnostic_msgs/DiagnosticStatus as JSON), or nullopt
// when it is not a bridge's or the bridge forwards: `dropping: true` (the ROS 1 side sends, the
// bridge drops over a bound) comes ahead of `silent: true` (docs/ros1-bridge.md).
std::optional<BridgeQuiet> bridge_quiet(const nlohmann::ordered_json& status);

// Listens on /diagnostics for `duration_s` and returns, per DDS topic a hubbridge bridges from
// ROS 1, why it carries nothing — only the topics whose latest status says so (bridge_quiet). A
// silent bridge's DDS writer is still there, so discovery alone would show it like a live hub's.
// Errors: the DDS entities that could not be created.
Expected<std::map<std::string, BridgeQuiet>> listen_for_quiet_bridges(const dds::Participant& participant,
                                                                      double duration_s);

}  // namespace hubrt::hubctl
