#include "bridge_diagnostics.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/json.h"
#include "hubrt/msgs/sample_memory.h"

namespace hubrt::hubbridge {
namespace {

constexpr int kOk = 0;  // diagnostic_msgs/DiagnosticStatus levels
constexpr int kWarn = 1;
constexpr int kError = 2;

const msgs::TypeInfo& array_type() {
  return *msgs::all_types().find("diagnostic_msgs/msg/DiagnosticArray");
}

nlohmann::ordered_json key_value(std::string key, std::string value) {
  return {{"key", std::move(key)}, {"value", std::move(value)}};
}

}  // namespace

nlohmann::ordered_json bridge_diagnostics(const BridgeFile& file,
                                          std::vector<std::unique_ptr<Bridge>>& bridges,
                                          std::span<const EndpointSync> sync, std::uint64_t registrations,
                                          std::int64_t now_ns, std::int64_t wall_ns) {
  nlohmann::ordered_json statuses = nlohmann::ordered_json::array();
  static const EndpointSync kNoSync;
  for (std::size_t index = 0; index < bridges.size(); ++index) {
    auto& bridge = bridges[index];
    const EndpointSync& at_master = index < sync.size() ? sync[index] : kNoSync;
    const BridgeCounters& c = bridge->counters;
    const std::int64_t last = c.last_forward_ns.load();
    const std::int64_t last_drop = c.last_drop_ns.load();
    const double age_s = last < 0 ? -1.0 : static_cast<double>(now_ns - last) / 1e9;
    const bool inbound = bridge->config.direction == Direction::kRos1ToDds;
    const bool silent = inbound && (last < 0 || age_s > file.silent_after_s);
    // Over-bound messages lately: the ROS 1 side is not silent, the bridge drops what it sends.
    const bool dropping =
        last_drop >= 0 && static_cast<double>(now_ns - last_drop) / 1e9 <= file.silent_after_s;
    std::string problem;
    {
      const std::lock_guard lock(bridge->problem_mutex);
      problem = bridge->last_problem;
    }
    int level = kOk;
    std::string message = "forwarding";
    if (c.type_errors > 0) {
      level = kError;
      message = problem.empty() ? "type errors" : problem;
    } else if (dropping) {
      level = kWarn;
      message = fmt::format("dropped {} over a bound{}: {}", c.dropped.load(),
                            !silent    ? ""
                            : last < 0 ? ", forwarded none"
                                       : fmt::format(", forwarded none for {:.1f} s", age_s),
                            problem);
    } else if (silent) {
      level = kWarn;
      message = last < 0 ? "silent: no ROS 1 sample yet"
                         : fmt::format("silent: no ROS 1 sample for {:.1f} s", age_s);
    } else if (!at_master.unregistered.empty()) {
      level = kWarn;
      message = fmt::format(
          "publisher {} is not registered with the ROS master (restarted?): its link holds, but "
          "ROS 1 tools do not see it and a new subscriber will not find it",
          fmt::join(at_master.unregistered, ", "));
    } else if (c.dropped > 0 || c.stale > 0) {
      level = kWarn;
      message = problem;
    }
    nlohmann::ordered_json values = nlohmann::ordered_json::array();
    values.push_back(key_value("direction", inbound ? "ros1_to_dds" : "dds_to_ros1"));
    values.push_back(key_value("ros1_topic", bridge->config.ros1_topic));
    values.push_back(key_value("dds_topic", bridge->config.dds_topic));
    values.push_back(key_value("type", bridge->type.ros1_name));
    values.push_back(key_value("md5sum", bridge->type.md5sum));
    values.push_back(key_value("forwarded", std::to_string(c.forwarded.load())));
    values.push_back(key_value("dropped", std::to_string(c.dropped.load())));
    values.push_back(key_value("type_errors", std::to_string(c.type_errors.load())));
    values.push_back(key_value("stale", std::to_string(c.stale.load())));
    values.push_back(key_value("write_errors", std::to_string(c.write_errors.load())));
    values.push_back(
        key_value("last_sample_age_ms", last < 0 ? "never" : fmt::format("{:.0f}", age_s * 1000.0)));
    values.push_back(key_value("silent", silent ? "true" : "false"));
    values.push_back(key_value("dropping", dropping ? "true" : "false"));
    values.push_back(key_value("ros1_registrations", std::to_string(registrations)));
    if (inbound) {
      values.push_back(
          key_value("unregistered_publishers", fmt::format("{}", fmt::join(at_master.unregistered, ", "))));
    }
    values.push_back(
        key_value("registered_for", fmt::format("{}", fmt::join(at_master.registered_for, ", "))));
    statuses.push_back({{"level", level},
                        {"name", fmt::format("hubbridge {}: {}", file.name, bridge->config.dds_topic)},
                        {"message", message},
                        {"hardware_id", "hubbridge"},
                        {"values", std::move(values)}});
  }
  return {{"header",
           {{"stamp", {{"sec", wall_ns / 1000000000}, {"nanosec", wall_ns % 1000000000}}}, {"frame_id", ""}}},
          {"status", std::move(statuses)}};
}

Expected<DiagnosticsPublisher> DiagnosticsPublisher::create(dds::Participant& participant) {
  auto topic = dds::UntypedTopic::create(participant, *array_type().descriptor, "/diagnostics");
  if (!topic) return std::move(topic).error();
  auto writer = dds::UntypedWriter::create(participant, *topic);
  if (!writer) return std::move(writer).error();
  return DiagnosticsPublisher(std::move(*topic), std::move(*writer));
}

Expected<void> DiagnosticsPublisher::publish(const nlohmann::ordered_json& array) {
  std::vector<std::uint8_t> sample(array_type().size, 0);
  auto filled = msgs::from_json(array_type(), array, sample.data());
  const Status written = filled ? writer_.write(sample.data()) : Status();
  msgs::free_contents(array_type(), sample.data());
  if (!filled) return filled;
  if (!written.is_ok())
    return make_error(written.code(), fmt::format("write /diagnostics: {}", to_string(written.code())));
  return {};
}

}  // namespace hubrt::hubbridge
