// hubd — one hub: its board, its nodes, its fixed-rate cycle, its DDS topics.
//
//   hubd --board host-sim --hub dock_ecu              simulated Dock ECU on this machine
//   hubd --board rpi4-dock-ecu                       the real thing (backend from the board)
//   hubd --board host-sim --hub dock_ecu --check      validate the files and exit
#include <csignal>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "hubrt/assembly/hub_assembly.h"
#include "hubrt/dds/domain.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/runtime/cycle_runner.h"

#include "config_files.h"
#include "logging.h"
#include "systemd_notifier.h"

namespace hubrt::hubd {
namespace {

struct Options {
  std::string board;
  std::string hub;
  std::string backend = "auto";
  std::optional<std::uint32_t> domain;
  std::string dds_config;
  bool loopback = false;
  std::optional<std::string> name;
  std::optional<double> rate_hz;
  std::string log_level = "info";
  bool check_only = false;
  std::uint32_t twin_check_ms = static_cast<std::uint32_t>(
      std::chrono::duration_cast<std::chrono::milliseconds>(assembly::kDefaultTwinCheckWindow).count());
};

// Exit codes: 0 clean stop, 1 runtime failure, 2 bad command line or configuration.
constexpr int kExitRuntime = 1;
constexpr int kExitConfig = 2;

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "a signal";
  }
}

int fail(const std::string& message, int code) {
  spdlog::error("{}", message);
  return code;
}

Expected<dds::DomainConfig> domain_config(const Options& options) {
  auto config = dds::domain_config_from_environment();
  if (!config) return config;
  if (options.domain) config->domain_id = *options.domain;
  if (options.loopback) config->cyclone_xml = dds::loopback_config_xml();
  if (!options.dds_config.empty()) config->cyclone_xml = options.dds_config;
  return config;
}

// The hub to run when --hub is not given: the board's, if it is wired for exactly one.
Expected<std::string> default_hub(const std::string& board_file) {
  auto board = hal::load_board(board_file);
  if (!board) return std::move(board).error();
  if (board->hubs.size() != 1) {
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("{} is wired for {} hubs: say which with --hub", board_file, board->hubs.size()));
  }
  return board->hubs.front();
}

Expected<assembly::BackendKind> backend_kind(const Options& options, const std::string& board_file) {
  if (options.backend == "fake") return assembly::BackendKind::kFake;
  if (options.backend == "linux") return assembly::BackendKind::kLinux;
  // auto: boards with a simulation section are simulation boards.
  auto board = hal::load_board(board_file);
  if (!board) return std::move(board).error();
  return board->simulation ? assembly::BackendKind::kFake : assembly::BackendKind::kLinux;
}

int run(const Options& options) {
  auto logger = make_logger("hubd", options.log_level);
  if (!logger) return fail(logger.error().message, kExitConfig);

  // Before any thread exists: blocks SIGINT/SIGTERM for every thread DDS will start.
  auto runner = runtime::CycleRunner::create();
  if (!runner) return fail(runner.error().message, kExitRuntime);

  auto board_file = find_config_file("boards", options.board);
  if (!board_file) return fail(board_file.error().message, kExitConfig);
  std::string hub_name = options.hub;
  if (hub_name.empty()) {
    auto hub = default_hub(*board_file);
    if (!hub) return fail(hub.error().message, kExitConfig);
    hub_name = *hub;
  }
  auto hub_file = find_config_file("hubs", hub_name);
  if (!hub_file) return fail(hub_file.error().message, kExitConfig);
  auto backend = backend_kind(options, *board_file);
  if (!backend) return fail(backend.error().message, kExitConfig);
  auto domain = domain_config(options);
  if (!domain) return fail(domain.error().message, kExitConfig);

  assembly::AssemblyRequest request;
  request.board_file = *board_file;
  request.hub_file = *hub_file;
  request.backend = *backend;
  request.domain = *domain;
  request.name = options.name;
  request.rate_hz = options.rate_hz;
  request.log = *logger;
  request.waker = runner->waker();
  // A --check never joins the watch window: it runs nothing that a twin could collide with.
  if (!options.check_only) request.twin_check = std::chrono::milliseconds(options.twin_check_ms);
  request.request_stop = [&runner] { runner->request_stop(); };
  SystemClock clock;
  auto assembled = assembly::assemble_hub(request, clock);
  if (!assembled) {
    return fail(assembled.error().message, assembled.error().code == ErrorCode::kInvalidArgument ||
                                                   assembled.error().code == ErrorCode::kNotFound ||
                                                   assembled.error().code == ErrorCode::kFailedPrecondition
                                               ? kExitConfig
                                               : kExitRuntime);
  }
  const auto& hub_config = (*assembled)->config;
  const std::string summary =
      fmt::format("hub '{}' ({}) on board '{}' with the {} backend, {} node(s), {:.1f} Hz, DDS domain {}",
                  hub_config.name, hub_config.type, (*assembled)->board.name,
                  *backend == assembly::BackendKind::kFake ? "fake" : "linux", hub_config.nodes.size(),
                  hub_config.rate_hz, domain->domain_id);
  if (options.check_only) {
    spdlog::info("configuration OK: {}", summary);
    return 0;
  }

  SystemdNotifier systemd;
  spdlog::info("running {}", summary);
  systemd.ready(summary);
  runtime::RunHooks hooks;
  hooks.after_cycle = [&systemd](const Instant& now) { systemd.cycle_done(now.mono); };
  runtime::Hub& hub = *(*assembled)->hub;
  auto stopped = runner->run(hub, clock, hooks);

  systemd.stopping();
  hub.enter_safe_state();
  if (!stopped) {
    spdlog::error("cycle failed: {}; outputs driven to their safe state", stopped.error().message);
    return kExitRuntime;
  }
  if ((*assembled)->twins != nullptr && (*assembled)->twins->yielded()) {
    spdlog::error("{}; outputs driven to their safe state", (*assembled)->twins->yield_message());
    return kExitRuntime;
  }
  const runtime::CycleStats& stats = hub.stats();
  spdlog::info("stopping on {}: outputs driven to their safe state after {} cycles ({} overruns)",
               *stopped == runtime::StopReason::kSignal ? signal_name(runner->last_signal()) : "request",
               stats.cycles, stats.overruns);
  return 0;
}

}  // namespace
}  // namespace hubrt::hubd

int main(int argc, char** argv) {
  hubrt::hubd::Options options;
  CLI::App app{"hubd — runs one hub: reads its devices, runs its nodes at a fixed rate, talks DDS"};
  app.add_option("--board", options.board, "Board name (file in the boards folder) or path to a board file")
      ->required();
  app.add_option("--hub", options.hub, "Hub type or hub file (default: the board's only hub)");
  app.add_option("--backend", options.backend, "HAL backend (auto: fake for simulation boards)")
      ->check(CLI::IsMember({"auto", "fake", "linux"}));
  app.add_option("--domain", options.domain, "DDS domain id (default: $ROS_DOMAIN_ID or 0)")
      ->check(CLI::Range(0, 232));
  app.add_option("--dds-config", options.dds_config,
                 "Cyclone DDS XML configuration (default: $CYCLONEDDS_URI)");
  app.add_flag("--loopback", options.loopback,
               "Keep DDS on the loopback interface (single-machine simulation)");
  app.add_option("--name", options.name, "Instance name, overriding the hub file's (unique on the domain)");
  app.add_option("--rate", options.rate_hz, "Cycle and heartbeat rate in Hz, overriding the hub file's")
      ->check(CLI::Range(0.01, 1000.0));
  app.add_option("--log-level", options.log_level, "trace, debug, info, warn, error, critical or off");
  app.add_option("--twin-check-ms", options.twin_check_ms,
                 "Discovery window at start-up in which another hub publishing this hub's States makes "
                 "this one refuse to run (0: no start-up check; a twin is still caught while running)")
      ->check(CLI::Range(0, 60000));
  app.add_flag("--check", options.check_only, "Load and validate the board and hub files, then exit");
  CLI11_PARSE(app, argc, argv);
  return hubrt::hubd::run(options);
}
