// A hub type's conformance profile (hubs/<type>/conformance.yaml): what `hubctl conformance` must
// know about a hub type that the wire does not say — two valid commands per node type, the reset
// command, the State fields of the safe state. Schema and an example: docs/conformance.md.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/config/yaml_map.h"

namespace hubrt::hubctl {

// `field.path: value` pairs, as `hubctl send` takes them, kept with their place in the file so
// that a value the message type refuses is reported at its line.
struct FieldAssignments {
  std::vector<std::pair<std::string, std::string>> fields;
  std::optional<config::YamlMap> source;

  // An error located at `path` in the file (or plain when the assignments did not come from one).
  [[nodiscard]] Error error_at(const std::string& path, std::string_view message) const;
};

// What is needed to command one node type (node-type layout) or a whole hub (hub layout).
struct CommandProfile {
  std::string command_type;              // ROS type name; optional, to recognise the node type
  std::vector<FieldAssignments> probes;  // exactly two, differing: each takes effect in turn
  FieldAssignments reset;                // the command whose echo sets got_reset
  FieldAssignments safe_state;           // State field -> value once the watchdog tripped
};

struct ConformanceProfile {
  std::string file;
  std::string hub_type;
  // The shipped configuration's rate and command timeout, for hubs that publish no /diagnostics.
  std::optional<double> rate_hz;
  std::optional<double> command_timeout_ms;
  // What the error_list must contain once the watchdog tripped.
  std::string timeout_error = "command timeout";
  std::map<std::string, CommandProfile, std::less<>> node_types;
  std::optional<CommandProfile> hub_layout;

  // nullptr when the profile does not list `node_type`.
  [[nodiscard]] const CommandProfile* for_node_type(std::string_view node_type) const noexcept;
  // The node type whose command_type is `ros_type`, or nothing.
  [[nodiscard]] std::optional<std::string> node_type_of_command(std::string_view ros_type) const;
};

// Loads and checks a profile: known keys only, two probes per entry, scalars for values.
// Errors name file:line:col, the key and the problem; kNotFound when the file is missing.
Expected<ConformanceProfile> load_profile(const std::string& path);

// Where the profile of `hub_type` is looked for, in order: $HUBRT_CONFIG_DIR/hubs, /etc/hubrt/hubs,
// /usr/share/hubrt/hubs and (development builds) the source tree's hubs/, each as
// <folder>/<hub_type>/conformance.yaml. Reads the environment: not to be raced with setenv().
std::vector<std::string> profile_search_paths(std::string_view hub_type);

// The first profile found for `hub_type`. Errors: kNotFound listing every place looked at; the
// loader's errors for a broken file.
Expected<ConformanceProfile> find_profile(std::string_view hub_type);

}  // namespace hubrt::hubctl
