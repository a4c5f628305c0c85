#include "ros2_qos_yaml.h"

#include <fmt/format.h>

#include "hubrt/config/yaml_map.h"

namespace hubrt::hubctl {
namespace {

// rmw's RMW_DURATION_INFINITE (rmw/types.h), which rosbag2 writes for DDS_INFINITY.
constexpr std::int64_t kInfiniteSec = 9223372036;
constexpr std::int64_t kInfiniteNsec = 854775807;

std::string duration_yaml(const char* name, Duration d) {
  const std::int64_t ns = d.count();
  const std::int64_t sec = d == Duration::max() ? kInfiniteSec : ns / 1'000'000'000;
  const std::int64_t nsec = d == Duration::max() ? kInfiniteNsec : ns % 1'000'000'000;
  return fmt::format("  {}:\n    sec: {}\n    nsec: {}\n", name, sec, nsec);
}

// rmw_qos_*_policy_to_str names (rmw/src/qos_string_conversions.c); what rmw has no name for is
// "unknown", as rosbag2 writes RMW_QOS_POLICY_*_UNKNOWN.
const char* history_name(const dds::OfferedQos& q) {
  return q.history == dds::OfferedQos::History::kKeepAll ? "keep_all" : "keep_last";
}
const char* reliability_name(const dds::OfferedQos& q) {
  return q.reliability == dds::OfferedQos::Reliability::kReliable ? "reliable" : "best_effort";
}
const char* durability_name(const dds::OfferedQos& q) {
  switch (q.durability) {
    case dds::OfferedQos::Durability::kVolatile:
      return "volatile";
    case dds::OfferedQos::Durability::kTransientLocal:
      return "transient_local";
    default:
      return "unknown";
  }
}
const char* liveliness_name(const dds::OfferedQos& q) {
  switch (q.liveliness) {
    case dds::OfferedQos::Liveliness::kAutomatic:
      return "automatic";
    case dds::OfferedQos::Liveliness::kManualByTopic:
      return "manual_by_topic";
    default:
      return "unknown";
  }
}

Duration read_duration(const config::YamlMap& profile, const char* key) {
  auto map = profile.map(key);
  if (!map) return Duration::max();
  const auto sec = map->integer_or("sec", kInfiniteSec, 0, INT64_MAX);
  const auto nsec = map->integer_or("nsec", 0, 0, INT64_MAX);
  if (!sec || !nsec || *sec >= kInfiniteSec || *sec > INT64_MAX / 1'000'000'000 - 1) return Duration::max();
  return Duration(*sec * 1'000'000'000 + *nsec % 1'000'000'000);
}

// A policy given by name (version 9+) or by its rmw enum value (older bags: rmw/types.h, e.g.
// RMW_QOS_POLICY_HISTORY_KEEP_LAST = 1), `numbered` listing the values by number.
std::string policy(const config::YamlMap& profile, const char* key,
                   std::initializer_list<std::pair<const char*, const char*>> numbered) {
  auto text = profile.string_or(key, "");
  if (!text) return "";
  for (const auto& [number, name] : numbered) {
    if (*text == number) return name;
  }
  return *text;
}

}  // namespace

std::string offered_qos_yaml(const std::vector<dds::OfferedQos>& offered) {
  if (offered.empty()) return "[]\n";
  std::string out;
  for (const dds::OfferedQos& q : offered) {
    out += fmt::format("- history: {}\n  depth: {}\n", history_name(q),
                       q.history == dds::OfferedQos::History::kKeepAll ? 0 : q.depth);
    out += fmt::format("  reliability: {}\n  durability: {}\n", reliability_name(q), durability_name(q));
    out += duration_yaml("deadline", q.deadline);
    out += duration_yaml("lifespan", q.lifespan);
    out += fmt::format("  liveliness: {}\n", liveliness_name(q));
    out += duration_yaml("liveliness_lease_duration", q.liveliness_lease);
    out += "  avoid_ros_namespace_conventions: false\n";
  }
  return out;
}

std::vector<dds::OfferedQos> parse_offered_qos_yaml(const std::string& text) {
  // YamlMap reads mappings (and guards against what a hostile file can do to yaml-cpp: aliases,
  // repeated keys, invalid UTF-8): the sequence goes under a key.
  std::string document = "profiles:\n";
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    document += "  " + text.substr(start, end == std::string::npos ? std::string::npos : end - start) + "\n";
    if (end == std::string::npos) break;
    start = end + 1;
  }
  std::vector<dds::OfferedQos> out;
  try {
    auto root = config::YamlMap::load_string(document, "offered_qos_profiles");
    if (!root) return out;
    auto profiles = root->list_of_maps("profiles", true);
    if (!profiles) return out;
    for (const config::YamlMap& p : *profiles) {
      dds::OfferedQos q;
      q.history = policy(p, "history", {{"1", "keep_last"}, {"2", "keep_all"}}) == "keep_all"
                      ? dds::OfferedQos::History::kKeepAll
                      : dds::OfferedQos::History::kKeepLast;
      const auto depth = p.integer_or("depth", 1, 0, INT32_MAX);
      q.depth = depth && *depth > 0 ? static_cast<std::int32_t>(*depth) : 1;
      q.reliability = policy(p, "reliability", {{"1", "reliable"}, {"2", "best_effort"}}) == "best_effort"
                          ? dds::OfferedQos::Reliability::kBestEffort
                          : dds::OfferedQos::Reliability::kReliable;
      q.durability =
          policy(p, "durability", {{"1", "transient_local"}, {"2", "volatile"}}) == "transient_local"
              ? dds::OfferedQos::Durability::kTransientLocal
              : dds::OfferedQos::Durability::kVolatile;
      q.deadline = read_duration(p, "deadline");
      q.lifespan = read_duration(p, "lifespan");
      q.liveliness =
          policy(p, "liveliness", {{"1", "automatic"}, {"3", "manual_by_topic"}}) == "manual_by_topic"
              ? dds::OfferedQos::Liveliness::kManualByTopic
              : dds::OfferedQos::Liveliness::kAutomatic;
      q.liveliness_lease = read_duration(p, "liveliness_lease_duration");
      out.push_back(q);
    }
  } catch (const std::exception&) {
    out.clear();  // yaml-cpp or memory: no profiles, the caller's default applies
  }
  return out;
}

}  // namespace hubrt::hubctl
