#include "station_process.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string_view>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

namespace hubrt::integration {
namespace {

namespace fs = std::filesystem;

// Each hub: its instance (= type) name, its hub file in the robot cell and on the full station,
// its board.
struct StationHub {
  const char* name;
  const char* cell_file;  // "" = not in the three-hub cell
  const char* full_file;  // the full station's, relative to the source folder
  const char* board;
};
constexpr StationHub kHubs[] = {
    {"dock_ecu", "hubs/dock_ecu/dock_ecu.yaml", "hubs/dock_ecu/dock_ecu.yaml", "host-sim"},
    {"rsp_ecu", "hubs/rsp_ecu/rsp_ecu.yaml", "hubs/rsp_ecu/rsp_ecu.yaml", "host-sim"},
    {"tool_ecu", "hubs/tool_ecu/tool_ecu.yaml", "hubs/station/hub-files/tool_ecu.yaml", "host-sim"},
    {"mir_com", "", "hubs/mir_com/mir_com.yaml", "host-sim-mir-com"},
    {"operator_hub", "", "hubs/station/hub-files/operator_hub.yaml", "host-sim-operator-hub"},
};
// The hub-level State of each hub type (hub layout), which embeds the node States.
const std::map<std::string, std::string> kHubStateTypes = {{"dock_ecu", "hub_msgs/msg/DockEcuState"},
                                                           {"rsp_ecu", "hub_msgs/msg/RspEcuState"},
                                                           {"tool_ecu", "hub_msgs/msg/ToolEcuState"},
                                                           {"mir_com", "hub_msgs/msg/MirComState"},
                                                           {"operator_hub", "hub_msgs/msg/OperatorHubState"}};
// Start-up under sanitizers on a loaded 2-core machine is slow.
constexpr auto kStartPatience = std::chrono::seconds(20);

// /<hub>/<node>/state -> {hub, node}; nothing for other topics.
std::optional<std::pair<std::string, std::string>> node_state_topic(const std::string& topic) {
  std::vector<std::string> parts;
  std::size_t start = 1;
  while (start <= topic.size()) {
    const auto slash = topic.find('/', start);
    parts.push_back(topic.substr(start, slash == std::string::npos ? std::string::npos : slash - start));
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  if (topic.empty() || topic[0] != '/' || parts.size() != 3 || parts[2] != "state") return std::nullopt;
  return std::make_pair(parts[0], parts[1]);
}

// The hub file of `hub`, changed as the options say, written into `dir`.
Expected<std::string> write_hub_file(const StationHub& hub, const StationOptions& options,
                                     const std::string& dir) {
  const fs::path source = fs::path(HUBRT_SOURCE_DIR) / (options.full ? hub.full_file : hub.cell_file);
  try {
    YAML::Node root = YAML::LoadFile(source.string());
    if (options.layout == StationLayout::kHub) {
      root["layout"] = "hub";
      // Another hub's node State is now a field of that hub's State.
      for (auto entry : root["subscriptions"]) {
        YAML::Node subscription = entry.second;
        const auto target = node_state_topic(subscription["topic"].as<std::string>());
        if (!target || kHubStateTypes.count(target->first) == 0) continue;
        subscription["topic"] = fmt::format("/{}/state", target->first);
        subscription["type"] = kHubStateTypes.at(target->first);
        subscription["field"] = target->second;
      }
    }
    if (!options.ros_namespace.empty()) {
      root["namespace"] = options.ros_namespace;
      for (auto entry : root["subscriptions"]) {
        entry.second["topic"] = options.ros_namespace + entry.second["topic"].as<std::string>();
      }
    }
    for (auto node : root["nodes"]) {
      if (options.lift_speed_mm_s > 0 && node.second["type"].as<std::string>() == "lift")
        node.second["speed_mm_s"] = options.lift_speed_mm_s;
      // The copy lives elsewhere: a relative allow-list stays the one next to the source.
      if (node.second["allow_list"] && fs::path(node.second["allow_list"].as<std::string>()).is_relative())
        node.second["allow_list"] =
            (source.parent_path() / node.second["allow_list"].as<std::string>()).string();
    }
    YAML::Emitter out;
    out << root;
    const std::string path = fmt::format("{}/{}.yaml", dir, hub.name);
    std::ofstream(path) << out.c_str() << "\n";
    return path;
  } catch (const YAML::Exception& e) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: {}", source.string(), e.what()));
  }
}

// The full station's world (hubsim --station), the mobile platform's State as the layout has it.
Expected<std::string> write_world_file(const StationOptions& options, const std::string& dir) {
  const std::string source = std::string(HUBRT_SOURCE_DIR) + "/hubs/station/full-station.yaml";
  try {
    YAML::Node root = YAML::LoadFile(source);
    if (options.layout == StationLayout::kHub) {
      root["mobile_platform"]["state"] = "/mir_com/state";
      root["mobile_platform"]["field"] = "mover";
    }
    YAML::Emitter out;
    out << root;
    const std::string path = dir + "/full-station.yaml";
    std::ofstream(path) << out.c_str() << "\n";
    return path;
  } catch (const YAML::Exception& e) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: {}", source, e.what()));
  }
}

}  // namespace

Expected<StationProcesses> StationProcesses::start(const test_support::TestDomain& domain,
                                                   const StationOptions& options) {
  std::string dir = (fs::temp_directory_path() / "hubrt-station-XXXXXX").string();
  if (::mkdtemp(dir.data()) == nullptr)
    return make_error(ErrorCode::kIo, fmt::format("mkdtemp {} failed", dir));
  StationProcesses station(domain, dir, options.security_dir, options.ros_namespace);
  const auto secured = [&options](std::vector<std::string> args, const std::string& identity) {
    if (!options.security_dir.empty())
      args.insert(args.end(), {"--security", options.security_dir, "--identity", identity});
    return args;
  };
  std::vector<std::pair<const StationHub*, std::string>> files;
  for (const StationHub& hub : kHubs) {
    if (!options.full && std::string_view(hub.cell_file).empty()) continue;
    auto file = write_hub_file(hub, options, dir);
    if (!file) return std::move(file).error();
    files.emplace_back(&hub, *file);
  }
  std::vector<std::string> hubsim_args = options.hubsim_args;
  if (!options.ros_namespace.empty())
    hubsim_args.insert(hubsim_args.end(), {"--namespace", options.ros_namespace});
  if (options.full) {
    auto world = write_world_file(options, dir);
    if (!world) return std::move(world).error();
    hubsim_args.insert(hubsim_args.end(), {"--station", *world});
  }
  // Start them all, then wait for each: start-ups overlap.
  std::vector<std::pair<std::string, test_support::ChildProcess>> starting;
  test_support::Environment env = domain.env();
  env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
  for (const auto& [hub, file] : files) {
    std::vector<std::string> args = {"--board", hub->board, "--hub", file};
    args.insert(args.end(), options.hubd_args.begin(), options.hubd_args.end());
    auto child = test_support::ChildProcess::start(test_support::hubd_path(), secured(args, hub->name), env);
    if (!child) return std::move(child).error();
    starting.emplace_back(hub->name, std::move(*child));
  }
  auto hubsim = test_support::ChildProcess::start(HUBRT_HUBSIM_PATH, secured(hubsim_args, "hubsim"), env);
  if (!hubsim) return std::move(hubsim).error();
  for (auto& [hub, child] : starting) {
    if (!child.wait_for_output("running hub", kStartPatience)) {
      return make_error(ErrorCode::kTimeout, fmt::format("hubd {} did not start; its output:\n{}{}", hub,
                                                         child.stdout_text(), child.stderr_text()));
    }
    station.hubs_.emplace_back(hub, std::move(child));
  }
  if (!hubsim->wait_for_output("running station model", kStartPatience)) {
    return make_error(ErrorCode::kTimeout, fmt::format("hubsim did not start; its output:\n{}{}",
                                                       hubsim->stdout_text(), hubsim->stderr_text()));
  }
  station.hubsim_.emplace(std::move(*hubsim));
  return station;
}

StationProcesses::~StationProcesses() {
  hubsim_.reset();
  hubs_.clear();
  if (!dir_.empty()) {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
}

Expected<Finished> StationProcesses::play(const std::string& scenario, Duration timeout) {
  test_support::Environment env = domain_->env();
  env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
  // --timeout: how long discovery may take on a loaded machine.
  std::vector<std::string> args = {"play", scenario, "--timeout", "20"};
  if (!security_dir_.empty()) args.insert(args.end(), {"--security", security_dir_, "--identity", "planner"});
  if (!ros_namespace_.empty()) args.insert(args.end(), {"--namespace", ros_namespace_});
  auto child = test_support::ChildProcess::start(HUBRT_HUBCTL_PATH, args, env);
  if (!child) return std::move(child).error();
  auto status = child->wait(timeout);
  if (!status) {
    return make_error(status.error().code,
                      fmt::format("{}; hubctl play's output so far:\n{}{}", status.error().message,
                                  child->stdout_text(), child->stderr_text()));
  }
  return Finished{*status, child->stdout_text() + child->stderr_text()};
}

std::string StationProcesses::logs() const {
  std::string out;
  for (const auto& [hub, process] : hubs_) {
    out += fmt::format("---- hubd {}:\n{}{}", hub, process.stdout_text(), process.stderr_text());
  }
  if (hubsim_) out += fmt::format("---- hubsim:\n{}{}", hubsim_->stdout_text(), hubsim_->stderr_text());
  return out;
}

}  // namespace hubrt::integration
