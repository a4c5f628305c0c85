#include "conformance_profile.h"

#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace hubrt::hubctl {
namespace {

// `{path: value, ...}`; every value a single scalar (it is handed to set_field as text).
Expected<FieldAssignments> read_assignments(const config::YamlMap& map) {
  FieldAssignments out;
  out.source = map;
  for (const std::string& key : map.keys()) {
    const YAML::Node value = map.node()[key];
    if (!value.IsScalar()) return map.error_at(key, "expected a single value (text, number or true/false)");
    out.fields.emplace_back(key, value.Scalar());
  }
  return out;
}

Expected<FieldAssignments> optional_assignments(const config::YamlMap& parent, std::string_view key) {
  if (!parent.has(key)) return FieldAssignments{};
  auto map = parent.map(key);
  if (!map) return std::move(map).error();
  return read_assignments(*map);
}

Expected<CommandProfile> read_command_profile(const config::YamlMap& map) {
  if (auto ok = map.only_keys({"command_type", "probes", "reset", "safe_state"}); !ok)
    return std::move(ok).error();
  CommandProfile profile;
  auto command_type = map.string_or("command_type", "");
  if (!command_type) return std::move(command_type).error();
  profile.command_type = *command_type;
  auto probes = map.list_of_maps("probes");
  if (!probes) return std::move(probes).error();
  if (probes->size() != 2) {
    return map.error_at("probes", fmt::format("expected two valid commands that differ (each takes effect "
                                              "when it replaces the other), got {}",
                                              probes->size()));
  }
  for (const config::YamlMap& probe : *probes) {
    auto assignments = read_assignments(probe);
    if (!assignments) return std::move(assignments).error();
    profile.probes.push_back(std::move(*assignments));
  }
  if (profile.probes[0].fields == profile.probes[1].fields) {
    return map.error_at("probes", "the two probes are identical: the second would never take effect");
  }
  auto reset = map.map("reset");
  if (!reset) return std::move(reset).error();
  auto reset_fields = read_assignments(*reset);
  if (!reset_fields) return std::move(reset_fields).error();
  profile.reset = std::move(*reset_fields);
  auto safe = optional_assignments(map, "safe_state");
  if (!safe) return std::move(safe).error();
  profile.safe_state = std::move(*safe);
  return profile;
}

}  // namespace

Error FieldAssignments::error_at(const std::string& path, std::string_view message) const {
  if (source) return source->error_at(path, message);
  return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: {}", path, message));
}

const CommandProfile* ConformanceProfile::for_node_type(std::string_view node_type) const noexcept {
  const auto it = node_types.find(node_type);
  return it == node_types.end() ? nullptr : &it->second;
}

std::optional<std::string> ConformanceProfile::node_type_of_command(std::string_view ros_type) const {
  for (const auto& [name, profile] : node_types) {
    if (!profile.command_type.empty() && profile.command_type == ros_type) return name;
  }
  return std::nullopt;
}

Expected<ConformanceProfile> load_profile(const std::string& path) {
  auto root = config::YamlMap::load_file(path);
  if (!root) return std::move(root).error();
  if (auto ok = root->only_keys(
          {"hub_type", "rate_hz", "command_timeout_ms", "timeout_error", "node_types", "hub_layout"});
      !ok) {
    return std::move(ok).error();
  }
  ConformanceProfile profile;
  profile.file = path;
  auto hub_type = root->string("hub_type");
  if (!hub_type) return std::move(hub_type).error();
  profile.hub_type = *hub_type;
  if (root->has("rate_hz")) {
    auto rate = root->number("rate_hz", 0.01, 1000.0);
    if (!rate) return std::move(rate).error();
    profile.rate_hz = *rate;
  }
  if (root->has("command_timeout_ms")) {
    auto timeout = root->integer("command_timeout_ms", 1, 3'600'000);
    if (!timeout) return std::move(timeout).error();
    profile.command_timeout_ms = static_cast<double>(*timeout);
  }
  auto timeout_error = root->string_or("timeout_error", profile.timeout_error);
  if (!timeout_error) return std::move(timeout_error).error();
  profile.timeout_error = *timeout_error;
  auto node_types = root->named_maps("node_types");
  if (!node_types) return std::move(node_types).error();
  for (const auto& [name, map] : *node_types) {
    auto entry = read_command_profile(map);
    if (!entry) return std::move(entry).error();
    profile.node_types.emplace(name, std::move(*entry));
  }
  if (root->has("hub_layout")) {
    auto map = root->map("hub_layout");
    if (!map) return std::move(map).error();
    auto entry = read_command_profile(*map);
    if (!entry) return std::move(entry).error();
    profile.hub_layout = std::move(*entry);
  }
  return profile;
}

std::vector<std::string> profile_search_paths(std::string_view hub_type) {
  std::vector<std::string> folders;
  // NOLINTNEXTLINE(concurrency-mt-unsafe): documented as not to be raced with setenv().
  if (const char* dir = std::getenv("HUBRT_CONFIG_DIR"); dir != nullptr && *dir != '\0') {
    folders.push_back(fmt::format("{}/hubs", dir));
  }
  folders.emplace_back("/etc/hubrt/hubs");
  folders.emplace_back("/usr/share/hubrt/hubs");
#ifdef HUBRT_SOURCE_DIR
  folders.push_back(fmt::format("{}/hubs", HUBRT_SOURCE_DIR));
#endif
  std::vector<std::string> paths;
  for (const std::string& folder : folders)
    paths.push_back(fmt::format("{}/{}/conformance.yaml", folder, hub_type));
  return paths;
}

Expected<ConformanceProfile> find_profile(std::string_view hub_type) {
  const std::vector<std::string> paths = profile_search_paths(hub_type);
  std::error_code ec;
  for (const std::string& path : paths) {
    if (std::filesystem::is_regular_file(path, ec)) return load_profile(path);
  }
  return make_error(ErrorCode::kNotFound,
                    fmt::format("no conformance profile for hub type '{}'; looked for: {}", hub_type,
                                fmt::join(paths, ", ")));
}

}  // namespace hubrt::hubctl
