// What the suite tests: one State topic of a hub, and everything needed to command it — worked
// out from the wire alone (topic names, types announced by discovery, /diagnostics) plus the hub
// type's conformance profile.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/msgs/type_info.h"

#include "conformance_profile.h"
#include "hub_diagnostics.h"

namespace hubrt::hubctl {

enum class TargetLayout : std::uint8_t {
  kNodeType,  // <ns>/<hub>/<node>/state, commands on <ns>/<node_type>/command addressed by node name
  kHub,       // <ns>/<hub>/state, commands on <ns>/<hub>/command addressed by hub name
};

struct Target {
  std::string state_topic;
  const msgs::TypeInfo* state_type = nullptr;
  const msgs::TypeInfo* command_type = nullptr;  // the type of the State's echo
  TargetLayout layout = TargetLayout::kNodeType;
  std::string ros_namespace;  // "" or "/station1"
  std::string hub_name;
  std::string node_name;  // node-type layout only
  std::string hub_type;   // empty when unknown
  std::string node_type;  // node-type layout only; empty when unknown
  std::string command_topic;
  std::string target_type;  // what the command's target_type must say
  std::string target_name;
  double period_s = 0;  // 0: unknown
  std::string period_source;
  double timeout_s = 0;  // 0: unknown
  std::string timeout_source;
  // The hub's budget of immediate States (at most one per this interval; README, wire contract):
  // from /diagnostics, else the contract's default of 10 ms.
  double immediate_interval_s = 0.010;
  const ConformanceProfile* profile = nullptr;
  const CommandProfile* commands = nullptr;  // nullptr: cannot command it
  // Why the command checks cannot run (no profile, unknown node type, ...); empty when they can.
  std::vector<std::string> command_problems;
};

// A type with the common State fields (echo, fresh_msg).
bool is_state_type(const msgs::TypeInfo& type) noexcept;
// Whether a State topic (ROS name) can be a hub's: the simulation's own topics live under /sim/
// (firmware/sim: the sim bridge's /sim/<hub>/signals, hubsim's world on /sim/station/state, which
// follows the Command/State contract but is no hub), and a suite run over "every State topic"
// (no --hub, no --topic) leaves them out.
bool is_hub_state_topic(std::string_view ros_topic) noexcept;
// The hub layout's State: one of its fields is itself a State.
bool is_hub_state_type(const msgs::TypeInfo& type) noexcept;

// Hub, node and namespace from a State topic name. Errors: kInvalidArgument when the name does
// not have the layout's shape (<ns>/<hub>/<node>/state or <ns>/<hub>/state).
struct StateTopicParts {
  std::string ros_namespace;
  std::string hub_name;
  std::string node_name;
};
Expected<StateTopicParts> split_state_topic(std::string_view topic, TargetLayout layout);

// What the user may force on the command line instead of learning it.
struct TargetOverrides {
  std::optional<double> rate_hz;
  std::optional<double> command_timeout_ms;
  std::string hub_type;
};

// Profiles by hub type, loaded once; a missing one is remembered with the reason.
class ProfileBook {
 public:
  // Adds a profile given by file (--profile); it wins over searched ones for its hub type.
  Expected<void> add_file(const std::string& path);
  // The profile of `hub_type`: given, or found by find_profile(); nullptr with `why` set if none.
  const ConformanceProfile* find(const std::string& hub_type, std::string& why);
  // The only profile given with --profile, if exactly one was (for hubs without diagnostics).
  [[nodiscard]] const ConformanceProfile* only_given() const noexcept;

 private:
  std::map<std::string, ConformanceProfile, std::less<>> profiles_;
  std::map<std::string, std::string, std::less<>> missing_;
  std::vector<std::string> given_;
};

// Works out a Target for a State topic of type `state_type`. Never fails: what cannot be known
// ends in Target::command_problems (and a zero period/timeout), so the checks that need it report
// why they could not run.
Target resolve_target(const std::string& state_topic, const msgs::TypeInfo& state_type,
                      const DiagnosticsByHub& diagnostics, ProfileBook& profiles,
                      const TargetOverrides& overrides);

}  // namespace hubrt::hubctl
