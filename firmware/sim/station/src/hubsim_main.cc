// hubsim — the simulated station's physical world for hubs on the fake backend: it couples the
// Tool, RSP and Dock ECUs (each a hubd on the simulation board) the way the robot cell does.
//
//   hubsim --loopback                                  station of hubs/station/station.yaml
//   hubsim --station my-station.yaml --rsp-ecu rsp2    another description, another RSP instance
//   hubsim --loopback --station hubs/station/full-station.yaml
//                                                      the full station: a mobile platform (the
//                                                      mir_com hub's MiR) brings the kit
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/dds/domain.h"
#include "hubrt/dds/participant.h"
#include "hubrt/security/participant_security.h"
#include "hubrt/sim/station/station_bridge.h"
#include "hubrt/sim/station/station_config.h"
#include "hubrt/sim/station/station_model.h"

namespace hubrt::sim::station {
namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_stop_signal(int /*signal*/) {
  g_stop.store(true);
}

struct Options {
  std::string station;
  std::optional<std::uint32_t> domain;
  std::string dds_config;
  bool loopback = false;
  std::optional<std::string> tool_ecu, rsp_ecu, dock_ecu;
  std::optional<double> rate_hz;
  std::optional<int> travel_ms;
  std::string log_level = "info";
  std::string ros_namespace;  // --namespace: the station's, in front of every topic
  std::string security_dir;   // DDS Security (role simulator): station folder and identity
  std::string identity;
};

constexpr int kExitRuntime = 1;
constexpr int kExitConfig = 2;

// $HUBRT_CONFIG_DIR/hubs/station/station.yaml, then the installed places, then (development
// builds) this source tree's.
Expected<std::string> find_station_file() {
  std::vector<std::string> candidates;
  if (const char* dir = std::getenv("HUBRT_CONFIG_DIR");  // NOLINT(concurrency-mt-unsafe): at start-up
      dir != nullptr && *dir != '\0') {
    candidates.push_back(fmt::format("{}/hubs/station/station.yaml", dir));
  }
  candidates.emplace_back("/etc/hubrt/hubs/station/station.yaml");
  candidates.emplace_back("/usr/share/hubrt/hubs/station/station.yaml");
#ifdef HUBRT_SOURCE_DIR
  candidates.push_back(fmt::format("{}/hubs/station/station.yaml", HUBRT_SOURCE_DIR));
#endif
  std::error_code ec;
  for (const auto& candidate : candidates) {
    if (std::filesystem::is_regular_file(candidate, ec)) return candidate;
  }
  return make_error(ErrorCode::kNotFound,
                    fmt::format("no station description; looked for: {}", fmt::join(candidates, ", ")));
}

Expected<StationConfig> load(const Options& options) {
  std::string file = options.station;
  if (file.empty()) {
    auto found = find_station_file();
    if (!found) return std::move(found).error();
    file = *found;
  }
  auto config = load_station_config(file);
  if (!config) return config;
  const std::array<const std::optional<std::string>*, kHubRoles> names{&options.tool_ecu, &options.rsp_ecu,
                                                                       &options.dock_ecu};
  for (std::size_t role = 0; role < kHubRoles; ++role) {
    if (*names[role]) config->hubs[role] = **names[role];
  }
  if (options.rate_hz) config->rate_hz = *options.rate_hz;
  // The mobile platform's State is a hub's of the same station: under the same namespace.
  if (config->mobile_platform && !options.ros_namespace.empty())
    config->mobile_platform->state_topic = options.ros_namespace + config->mobile_platform->state_topic;
  if (options.travel_ms) config->robot_travel = std::chrono::milliseconds(*options.travel_ms);
  return config;
}

int run(const Options& options) {
  spdlog::set_level(spdlog::level::from_str(options.log_level));
  spdlog::set_pattern("[%H:%M:%S.%e] [hubsim] [%l] %v");
  auto config = load(options);
  if (!config) {
    spdlog::error("{}", config.error().message);
    return kExitConfig;
  }
  auto domain = dds::domain_config_from_environment();
  if (!domain) {
    spdlog::error("{}", domain.error().message);
    return kExitConfig;
  }
  if (options.domain) domain->domain_id = *options.domain;
  if (options.loopback) domain->cyclone_xml = dds::loopback_config_xml();
  if (!options.dds_config.empty()) domain->cyclone_xml = options.dds_config;
  if (!options.security_dir.empty()) {
    const auto now = std::chrono::system_clock::now().time_since_epoch();
    auto secured = security::security_xml_for({options.security_dir, options.identity},
                                              std::chrono::duration_cast<std::chrono::seconds>(now).count());
    if (!secured) {
      spdlog::error("{}", secured.error().message);
      return kExitConfig;
    }
    domain->cyclone_xml = security::with_security(domain->cyclone_xml, *secured);
  }
  auto participant = dds::Participant::create(*domain, "hubsim");
  if (!participant) {
    spdlog::error("{}", participant.error().message);
    return kExitRuntime;
  }
  StationModel model(*config);
  auto bridge = StationBridge::create(*participant, model, spdlog::default_logger(), options.ros_namespace);
  if (!bridge) {
    spdlog::error("{}", bridge.error().message);
    return kExitRuntime;
  }
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  spdlog::info("running station model of {} for hubs {} at {:.0f} Hz, DDS domain {}", config->file,
               fmt::join(config->hubs, ", "), config->rate_hz, domain->domain_id);
  SystemClock clock;
  const auto period = std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / config->rate_hz));
  Time next = clock.now().mono;
  while (!g_stop.load()) {
    (*bridge)->step(clock.now());
    next += period;
    const Time now = clock.now().mono;
    if (next < now) next = now;  // fell behind (a stalled machine): do not try to catch up
    std::this_thread::sleep_for(next - now);
  }
  spdlog::info("stopping");
  return 0;
}

}  // namespace
}  // namespace hubrt::sim::station

int main(int argc, char** argv) {
  hubrt::sim::station::Options options;
  CLI::App app{"hubsim — the simulated station's world: couples the simulated Tool, RSP and Dock ECUs"};
  app.add_option("--station", options.station,
                 "Station description (default: hubs/station/station.yaml; hubs/station/full-station.yaml "
                 "adds the mobile platform that brings the kit)");
  app.add_option("--domain", options.domain, "DDS domain id (default: $ROS_DOMAIN_ID or 0)")
      ->check(CLI::Range(0, 232));
  app.add_option("--dds-config", options.dds_config,
                 "Cyclone DDS XML configuration (default: $CYCLONEDDS_URI)");
  app.add_flag("--loopback", options.loopback, "Keep DDS on the loopback interface");
  auto* security = app.add_option("--security", options.security_dir,
                                  "DDS Security: the station's security folder (hubctl security init)");
  auto* identity = app.add_option("--identity", options.identity,
                                  "DDS Security: the identity to join as (role simulator)");
  security->needs(identity);
  identity->needs(security);
  app.add_option(
         "--namespace", options.ros_namespace,
         "The station's ROS namespace, e.g. /cell_a: in front of every simulation topic, as its hubs' "
         "namespace: is in front of theirs (a plant whose stations share one domain; docs/plant.md)")
      ->check([](const std::string& value) {
        auto valid = hubrt::config::check_ros_namespace(value);
        return valid ? std::string() : valid.error().message;
      });
  app.add_option("--tool-ecu", options.tool_ecu, "Instance name of the Tool ECU");
  app.add_option("--rsp-ecu", options.rsp_ecu, "Instance name of the RSP ECU");
  app.add_option("--dock-ecu", options.dock_ecu, "Instance name of the Dock ECU");
  app.add_option("--rate", options.rate_hz, "Model steps per second")->check(CLI::Range(1.0, 1000.0));
  app.add_option("--travel-ms", options.travel_ms, "How long every robot move takes")
      ->check(CLI::Range(0, 600000));
  app.add_option("--log-level", options.log_level, "trace, debug, info, warn, error, critical or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  CLI11_PARSE(app, argc, argv);
  return hubrt::sim::station::run(options);
}
