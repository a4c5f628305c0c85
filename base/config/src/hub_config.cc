#include "hubrt/config/hub_config.h"

#include <cmath>
#include <set>

#include <fmt/format.h>

namespace hubrt::config {
namespace {

constexpr double kMaxRateHz = 1000.0;

Expected<std::string> ros_name(const YamlMap& map, std::string_view key) {
  auto value = map.string(key);
  if (!value) return value;
  if (!is_ros_name_token(*value)) {
    return map.error_at(key, fmt::format("'{}' cannot be used in a topic name: use letters, digits and "
                                         "underscores, starting with a letter",
                                         *value));
  }
  return value;
}

Expected<std::string> ros_namespace(const YamlMap& map) {
  auto value = map.string_or("namespace", "");
  if (!value || value->empty() || *value == "/") return value ? Expected<std::string>(std::string()) : value;
  std::string_view checked = *value;
  if (checked.size() > 1 && checked.back() == '/') checked.remove_suffix(1);
  if (auto ok = check_ros_namespace(checked); !ok) {
    // The message names the namespace as written, trailing '/' and all.
    return map.error_at("namespace", checked.front() != '/'
                                         ? ok.error().message
                                         : fmt::format("'{}' is not a valid ROS namespace", *value));
  }
  std::string normalized = *value;
  if (normalized.back() == '/') normalized.pop_back();
  return normalized;
}

Expected<std::vector<Subscription>> subscriptions(const YamlMap& root) {
  std::vector<Subscription> out;
  if (!root.has("subscriptions")) return out;
  auto entries = root.named_maps("subscriptions");
  if (!entries) return std::move(entries).error();
  for (auto& [name, map] : *entries) {
    if (auto ok = map.only_keys({"topic", "type", "field", "timeout_ms"}); !ok) return std::move(ok).error();
    auto topic = map.string("topic");
    if (!topic) return std::move(topic).error();
    if (topic->front() != '/')
      return map.error_at("topic", "must be an absolute ROS topic name, e.g. /rsp_ecu/rsp/state");
    auto type = map.string("type");
    if (!type) return std::move(type).error();
    auto field = map.string_or("field", "");
    if (!field) return std::move(field).error();
    auto timeout = map.integer_or("timeout_ms", 1000, 1, 600'000);
    if (!timeout) return std::move(timeout).error();
    out.push_back(Subscription{name, *topic, *type, *field, std::chrono::milliseconds(*timeout)});
  }
  return out;
}

Expected<std::optional<HubSecurity>> security(const YamlMap& root) {
  if (!root.has("security")) return std::optional<HubSecurity>();
  auto map = root.map("security");
  if (!map) return std::move(map).error();
  if (auto ok = map->only_keys({"dir", "identity"}); !ok) return std::move(ok).error();
  auto dir = map->string("dir");
  if (!dir) return std::move(dir).error();
  if (dir->empty()) return map->error_at("dir", "must name the station's security folder");
  auto identity = map->string("identity");
  if (!identity) return std::move(identity).error();
  std::string folder = *dir;
  if (folder.front() != '/') {
    const std::string& file = root.file();
    const auto slash = file.rfind('/');
    folder = (slash == std::string::npos ? std::string(".") : file.substr(0, slash)) + "/" + folder;
  }
  return std::optional<HubSecurity>(HubSecurity{folder, *identity});
}

Expected<HubBlackBox> blackbox(const YamlMap& root) {
  HubBlackBox out;
  if (!root.has("blackbox")) return out;
  auto map = root.map("blackbox");
  if (!map) return std::move(map).error();
  if (auto ok = map->only_keys({"enabled", "seconds", "memory_kib", "directory", "directory_mib"}); !ok)
    return std::move(ok).error();
  auto enabled = map->boolean_or("enabled", true);
  if (!enabled) return std::move(enabled).error();
  out.enabled = *enabled;
  auto seconds = map->integer_or("seconds", 60, 1, 3600);
  if (!seconds) return std::move(seconds).error();
  out.span = std::chrono::seconds(*seconds);
  // 64 KiB to 1 GiB: below that a single hub-layout State would not fit (the ring keeps entries of
  // up to a quarter of itself).
  if (map->has("memory_kib")) {
    auto memory = map->integer("memory_kib", 64, 1 << 20);
    if (!memory) return std::move(memory).error();
    out.memory_bytes = static_cast<std::size_t>(*memory) * 1024;
  }
  auto directory = map->string_or("directory", "");
  if (!directory) return std::move(directory).error();
  if (!directory->empty() && directory->front() != '/')
    return map->error_at("directory", "must be an absolute path (e.g. /var/lib/hubrt/blackbox)");
  out.directory = *directory;
  auto cap = map->integer_or("directory_mib", 64, 1, 1 << 20);
  if (!cap) return std::move(cap).error();
  out.directory_bytes = static_cast<std::uint64_t>(*cap) << 20;
  return out;
}

// `clock_tolerance_ms`: a whole number of milliseconds, or `none` (the clocks are not synced).
// Default 50 ms, as runtime::kDefaultClockTolerance (the reasoning is there). Below the command
// timeout: a tolerance as long as the timeout would let a command from the future stay fresh for
// two timeouts.
Expected<std::optional<Duration>> clock_tolerance(const YamlMap& root, Duration command_timeout) {
  constexpr std::int64_t kDefaultMs = 50;
  constexpr std::int64_t kMaxMs = 1000;
  if (!root.has("clock_tolerance_ms")) return std::optional<Duration>(std::chrono::milliseconds(kDefaultMs));
  auto text = root.string("clock_tolerance_ms");
  if (!text) return std::move(text).error();
  if (*text == "none") return std::optional<Duration>();
  auto ms = root.integer("clock_tolerance_ms", 0, kMaxMs);
  if (!ms) {
    return root.error_at("clock_tolerance_ms",
                         fmt::format("'{}' is neither a whole number of milliseconds from 0 to {} nor 'none' "
                                     "(the clocks are not synced)",
                                     *text, kMaxMs));
  }
  const Duration tolerance = std::chrono::milliseconds(*ms);
  if (tolerance >= command_timeout) {
    return root.error_at(
        "clock_tolerance_ms",
        fmt::format("{} ms is not below the command timeout ({} ms): a command stamped that far in the "
                    "future would stay fresh for two timeouts",
                    *ms, std::chrono::duration_cast<std::chrono::milliseconds>(command_timeout).count()));
  }
  return std::optional<Duration>(tolerance);
}

}  // namespace

bool is_ros_name_token(std::string_view name) noexcept {
  if (name.empty()) return false;
  const auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  if (!alpha(name.front())) return false;
  for (const char c : name) {
    if (!alpha(c) && !(c >= '0' && c <= '9') && c != '_') return false;
  }
  return true;
}

Expected<void> check_ros_namespace(std::string_view text) {
  if (text.empty() || text.front() != '/') {
    return make_error(ErrorCode::kInvalidArgument, "must start with '/', e.g. /station1");
  }
  // Every part between the slashes a token: "/", "//", "/a//b" and "/a/" have an empty one.
  for (std::string_view rest = text.substr(1);;) {
    const auto slash = rest.find('/');
    if (!is_ros_name_token(rest.substr(0, slash))) {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("'{}' is not a valid ROS namespace", text));
    }
    if (slash == std::string_view::npos) return {};
    rest.remove_prefix(slash + 1);
  }
}

Expected<HubConfig> parse_hub_config(const YamlMap& root) {
  if (auto ok = root.only_keys({"hub", "name", "rate_hz", "command_timeout_ms", "clock_tolerance_ms",
                                "immediate_state_interval_ms", "layout", "namespace", "diagnostics_hz",
                                "nodes", "subscriptions", "security", "blackbox"});
      !ok) {
    return std::move(ok).error();
  }
  HubConfig config;
  config.file = root.file();
  auto type = ros_name(root, "hub");
  if (!type) return std::move(type).error();
  config.type = *type;
  auto name = root.has("name") ? ros_name(root, "name") : Expected<std::string>(config.type);
  if (!name) return std::move(name).error();
  config.name = *name;

  auto rate = root.number_or("rate_hz", 10.0, 0.01, kMaxRateHz);
  if (!rate) return std::move(rate).error();
  config.rate_hz = *rate;
  config.period = std::chrono::nanoseconds(static_cast<std::int64_t>(std::llround(1e9 / *rate)));

  const auto default_timeout_ms = std::max<std::int64_t>(1000, 3 * config.period.count() / 1'000'000);
  auto timeout = root.integer_or("command_timeout_ms", default_timeout_ms, 1, 3'600'000);
  if (!timeout) return std::move(timeout).error();
  config.command_timeout = std::chrono::milliseconds(*timeout);
  if (config.command_timeout < 2 * config.period) {
    return root.error_at("command_timeout_ms",
                         fmt::format("{} ms is shorter than two cycle periods ({:.1f} ms at {} Hz): every "
                                     "jitter would trip the watchdog",
                                     *timeout, 2e3 / *rate, *rate));
  }

  auto tolerance = clock_tolerance(root, config.command_timeout);
  if (!tolerance) return std::move(tolerance).error();
  config.clock_tolerance = *tolerance;

  // Default 10 ms, as runtime::kDefaultImmediateStateInterval (the reasoning is there); at most a
  // second: a longer window would hold a change back longer than any heartbeat period allowed.
  auto immediate = root.integer_or("immediate_state_interval_ms", 10, 1, 1000);
  if (!immediate) return std::move(immediate).error();
  config.immediate_state_interval = std::chrono::milliseconds(*immediate);

  auto layout = root.choice_or("layout", "node_type", {"node_type", "hub"});
  if (!layout) return std::move(layout).error();
  config.layout = *layout == "hub" ? Layout::kHub : Layout::kNodeType;

  auto ns = ros_namespace(root);
  if (!ns) return std::move(ns).error();
  config.ros_namespace = *ns;

  auto diagnostics = root.number_or("diagnostics_hz", 1.0, 0.0, 100.0);
  if (!diagnostics) return std::move(diagnostics).error();
  config.diagnostics_hz = *diagnostics;

  auto nodes = root.named_maps("nodes");
  if (!nodes) return std::move(nodes).error();
  if (nodes->empty()) return root.error_at("nodes", "a hub needs at least one node");
  std::set<std::string> seen;
  for (auto& [node_name, map] : *nodes) {
    if (!is_ros_name_token(node_name)) {
      return map.error(
          fmt::format("node name '{}' cannot be used in a topic name: use letters, digits and "
                      "underscores, starting with a letter",
                      node_name));
    }
    if (!seen.insert(node_name).second)
      return map.error(fmt::format("node '{}' is defined twice", node_name));
    auto node_type = ros_name(map, "type");
    if (!node_type) return std::move(node_type).error();
    config.nodes.push_back(NodeConfig{node_name, *node_type, map});
  }

  auto subs = subscriptions(root);
  if (!subs) return std::move(subs).error();
  config.subscriptions = std::move(*subs);
  auto secured = security(root);
  if (!secured) return std::move(secured).error();
  config.security = std::move(*secured);
  auto box = blackbox(root);
  if (!box) return std::move(box).error();
  config.blackbox = std::move(*box);
  return config;
}

Expected<HubConfig> load_hub_config(const std::string& path) {
  auto root = YamlMap::load_file(path);
  if (!root) return std::move(root).error();
  return parse_hub_config(*root);
}

}  // namespace hubrt::config
