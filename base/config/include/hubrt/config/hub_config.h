// A hub's configuration file (hubs/<type>/<type>.yaml): what the hub is called on the network,
// how fast it runs, how its topics are laid out and which nodes it has. Node-specific settings
// stay as located YAML for the hub type to read, so its errors name file and line too.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/config/yaml_map.h"

namespace hubrt::config {

enum class Layout : std::uint8_t {
  kNodeType,  // one command topic per node type, addressed by name; one State topic per node
  kHub,       // one command/State topic pair per hub; a distributor and a collector
};

struct NodeConfig {
  std::string name;  // unique within the hub; the node's State topic and target_name
  std::string type;  // node type, e.g. "dock"
  YamlMap settings;  // the node's mapping, for the hub type to read its own keys
};

// Another hub's State topic that this hub consumes as an input (e.g. the Tool ECU watching
// whether the RSP ECU holds the smart tool).
struct Subscription {
  std::string name;    // how the hub's logic refers to it
  std::string topic;   // ROS topic name, e.g. "/rsp_ecu/rsp/state"
  std::string type;    // ROS type name, e.g. "hub_msgs/msg/RspState"
  std::string field;   // for a hub-layout State: the field holding the node's State; else empty
  Duration timeout{};  // older than this counts as lost
};

// DDS Security for this hub (docs/deploy.md, "Securing a station"): the station's security
// folder (relative paths: from the hub file's folder) and the identity the hub joins as.
struct HubSecurity {
  std::string dir;
  std::string identity;
};

// The hub's black box (docs/recording.md, "A hub's black box"; its key in docs/hub-config.md): the
// last `span` of its commands, States and /diagnostics in `memory_bytes` allocated at start (absent:
// sized from the hub's rates, blackbox::ring_bytes_for), written as MCAP into `directory` (empty: hubd's
// default, $HUBRT_BLACKBOX_DIR or /var/lib/hubrt/blackbox) whose files of this hub are kept under
// `directory_bytes`.
struct HubBlackBox {
  bool enabled = true;
  Duration span = std::chrono::seconds(60);
  std::optional<std::size_t> memory_bytes;  // `memory_kib`; absent: sized from the rates
  std::string directory;
  std::uint64_t directory_bytes = std::uint64_t{64} << 20;
};

struct HubConfig {
  std::string file;
  std::string type;
  std::string name;
  double rate_hz = 10.0;
  Duration period{};
  Duration command_timeout{};
  // How far this hub's and the planner's clocks are trusted to agree (`clock_tolerance_ms`): a
  // command's age comes from its source timestamp (runtime/command_age.h). std::nullopt
  // (`clock_tolerance_ms: none`): the clocks are not synced, ages are not judged.
  std::optional<Duration> clock_tolerance = std::chrono::milliseconds(50);
  // At most one State per node published at once (outside the heartbeat) per this interval.
  Duration immediate_state_interval = std::chrono::milliseconds(10);
  Layout layout = Layout::kNodeType;
  std::string ros_namespace;  // "" or "/station1": prefix of every topic
  double diagnostics_hz = 1.0;
  std::vector<NodeConfig> nodes;
  std::vector<Subscription> subscriptions;
  std::optional<HubSecurity> security;  // absent: the hub joins the domain unsecured
  HubBlackBox blackbox;
};

// Loads and validates a hub configuration. Errors name file:line:col, the key and the problem.
// Checks: known keys, rate in (0, 1000] Hz, timeout at least two periods, clock tolerance 'none'
// or [0, 1000] ms and below the timeout, immediate-State interval in [1, 1000] ms, names usable in ROS
// topic names, node names unique, layout known. Node settings are checked by the hub type.
Expected<HubConfig> load_hub_config(const std::string& path);
Expected<HubConfig> parse_hub_config(const YamlMap& root);

// True when `name` can be one ROS name token: [A-Za-z][A-Za-z0-9_]*.
bool is_ros_name_token(std::string_view name) noexcept;

// A ROS namespace as a command line names it (`hubsim --namespace`, `hubctl play --namespace`):
// '/' and ROS name tokens separated by '/', no '/' at the end ("/station1", "/plant/cell_a"). The
// hub file's `namespace:` is checked with it too, after taking "" and "/" as none and dropping a
// trailing '/'. Errors (kInvalidArgument): "must start with '/', e.g. /station1", or "'<text>' is
// not a valid ROS namespace". Thread-safe.
Expected<void> check_ros_namespace(std::string_view text);

}  // namespace hubrt::config
