// hubd — one hub: its board, its nodes, its fixed-rate cycle, its DDS topics.
//
//   hubd --board host-sim --hub dock_ecu              simulated Dock ECU on this machine
//   hubd --board rpi4-dock-ecu                       the real thing (backend from the board)
//   hubd --board host-sim --hub dock_ecu --check      validate the files and exit
//   hubd --board rpi4-rsp-ecu --hub rsp_ecu --safe-outputs   drive the outputs safe and exit
//
// Exit statuses: hubrt/base/exit_codes.h. Every stop signal (runtime::stop_signals()) ends the
// cycle, drives the outputs safe, then exits: 0 for SIGTERM/SIGINT, 128+N for signal N otherwise.
#include <malloc.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <cstring>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "hubrt/assembly/hub_assembly.h"
#include "hubrt/base/exit_codes.h"
#include "hubrt/config/hub_config.h"
#include "hubrt/dds/domain.h"
#include "hubrt/dds/oversize_samples.h"
#include "hubrt/dds/ports.h"
#include "hubrt/dds/security_refusals.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/runtime/cycle_runner.h"
#include "hubrt/security/participant_security.h"

#include "config_files.h"
#include "crash_handlers.h"
#include "linked_simulation.h"
#include "logging.h"
#include "realtime.h"
#include "safe_outputs.h"
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
  bool safe_outputs = false;
  bool realtime = false;
  bool no_black_box = false;
  int realtime_priority = kDefaultRealtimePriority;
  std::string security_dir;  // DDS Security, overriding the hub file's security: section
  std::string identity;
  std::string trace_stages;  // hubd --trace-stages FILE: the command steps' stage stamps, at exit
  std::uint32_t twin_check_ms = static_cast<std::uint32_t>(
      std::chrono::duration_cast<std::chrono::milliseconds>(assembly::kDefaultTwinCheckWindow).count());
};

// The exit statuses are the table of hubrt/base/exit_codes.h, shared with hubctl.
constexpr int kExitRuntime = exit_codes::kFailure;
constexpr int kExitConfig = exit_codes::kUsage;
// How long systemd waits for the first cycle (SystemdNotifier::allow_startup): the unit's
// WatchdogSec= (2 s) is for a running cycle, not for loading files, opening devices and joining DDS.
constexpr Duration kStartupWatchdog = std::chrono::seconds(30);
// --trace-stages: command steps kept (32 B each, 512 KiB): a benchmark's whole run of commands.
constexpr std::size_t kStageTraceCapacity = 16384;

std::string signal_name(int signal) {
  const char* abbreviation = sigabbrev_np(signal);  // glibc >= 2.32
  return abbreviation != nullptr ? fmt::format("SIG{}", abbreviation) : fmt::format("signal {}", signal);
}

// Where black boxes go when the hub file names no directory: $HUBRT_BLACKBOX_DIR; else the board
// packages' /var/lib/hubrt/blackbox when it is there to write; else a folder in $TMPDIR (a
// development machine).
std::string default_black_box_directory() {
  // NOLINTNEXTLINE(concurrency-mt-unsafe): nothing in hubd changes its environment.
  if (const char* dir = std::getenv("HUBRT_BLACKBOX_DIR"); dir != nullptr && *dir != '\0') return dir;
  if (::access("/var/lib/hubrt/blackbox", W_OK) == 0) return "/var/lib/hubrt/blackbox";
  const char* tmp = std::getenv("TMPDIR");  // NOLINT(concurrency-mt-unsafe): as above
  return fmt::format("{}/hubrt-blackbox", tmp != nullptr && *tmp != '\0' ? tmp : "/tmp");
}

// The black box on the way out, after the outputs are safe: the last minute before the exit.
void write_black_box(assembly::AssembledHub& hub, const std::string& reason) {
  if (!hub.black_box) return;
  hub.black_box_service.reset();  // its thread writes no more
  auto written = hub.black_box->dump(reason);
  if (written) {
    spdlog::info("black box written: {} ({} messages, {:.1f} s)", written->path, written->messages,
                 written->seconds);
  } else {
    spdlog::error("black box not written: {}", written.error().message);
  }
}

int fail(const std::string& message, int code) {
  spdlog::error("{}", message);
  return code;
}

// The hub's DDS Security: --security/--identity, else the hub file's `security:` section, else
// none. The credentials are checked here, before Cyclone sees them, so that an expired or foreign
// certificate is refused with a message naming the file and the date (docs/deploy.md).
std::optional<security::SecurityChoice> security_choice(const Options& options,
                                                        const config::HubConfig& hub) {
  if (!options.security_dir.empty()) return security::SecurityChoice{options.security_dir, options.identity};
  if (!hub.security) return std::nullopt;
  return security::SecurityChoice{hub.security->dir, hub.security->identity};
}

Expected<dds::DomainConfig> domain_config(const Options& options,
                                          const std::optional<security::SecurityChoice>& secured) {
  auto config = dds::domain_config_from_environment();
  if (!config) return config;
  if (options.domain) config->domain_id = *options.domain;
  if (options.loopback) config->cyclone_xml = dds::loopback_config_xml();
  if (!options.dds_config.empty()) config->cyclone_xml = options.dds_config;
  // Whatever the configuration, a peer cannot make this hub receive and hold samples larger than
  // dds::kMaxSampleSizeBytes (README.md, "The wire contract").
  config->cyclone_xml = dds::with_sample_bounds(config->cyclone_xml);
  if (secured) {
    const auto now = std::chrono::system_clock::now().time_since_epoch();
    auto xml =
        security::security_xml_for(*secured, std::chrono::duration_cast<std::chrono::seconds>(now).count());
    if (!xml) return std::move(xml).error();
    config->cyclone_xml = security::with_security(config->cyclone_xml, *xml);
  }
  return config;
}

// The hub to run when --hub is not given: the board's, if it is wired for exactly one.
Expected<std::string> default_hub(const hal::BoardConfig& board) {
  if (board.hubs.size() != 1) {
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("{} is wired for {} hubs: say which with --hub", board.file, board.hubs.size()));
  }
  return board.hubs.front();
}

assembly::BackendKind backend_kind(const Options& options, const hal::BoardConfig& board) {
  if (options.backend == "fake") return assembly::BackendKind::kFake;
  if (options.backend == "linux") return assembly::BackendKind::kLinux;
  // auto: boards with a simulation section are simulation boards.
  return board.simulation ? assembly::BackendKind::kFake : assembly::BackendKind::kLinux;
}

int run(const Options& options) {
  auto logger = make_logger("hubd", options.log_level);
  if (!logger) return fail(logger.error().message, kExitConfig);

  auto board_file = find_config_file("boards", options.board);
  if (!board_file) return fail(board_file.error().message, kExitConfig);
  // Each file is read once (the assembly takes them as loaded): parsing YAML is a good part of
  // hubd's own start-up time.
  auto board = hal::load_board(*board_file);
  if (!board) return fail(board.error().message, kExitConfig);
  std::string hub_name = options.hub;
  if (hub_name.empty()) {
    auto hub = default_hub(*board);
    if (!hub) return fail(hub.error().message, kExitConfig);
    hub_name = *hub;
  }
  auto hub_file = find_config_file("hubs", hub_name);
  if (!hub_file) return fail(hub_file.error().message, kExitConfig);
  const assembly::BackendKind backend = backend_kind(options, *board);
  if (options.safe_outputs)
    return run_safe_outputs({*board_file, *hub_file, backend, linked_simulation()}, **logger);
  auto hub_config = config::load_hub_config(*hub_file);
  if (!hub_config) return fail(hub_config.error().message, kExitConfig);
  install_crash_handlers();
  SystemdNotifier systemd;
  systemd.allow_startup(kStartupWatchdog);
  // Before the first participant: /diagnostics counts the oversize samples Cyclone drops and,
  // secured, the peers DDS Security refuses (logged rate-limited: dds/security_refusals.h).
  dds::count_oversize_samples();
  const std::optional<security::SecurityChoice> secured = security_choice(options, *hub_config);
  if (secured) dds::count_security_refusals();
  auto domain = domain_config(options, secured);
  if (!domain) return fail(domain.error().message, kExitConfig);
  if (secured) {
    // Checked before joining (domain_config: security_xml_for); say against which CA, so that a
    // station's other participants can be told what they need.
    spdlog::info("DDS Security as '{}': {}: checked before joining", secured->identity,
                 security::describe_identity(security::credentials_in(secured->dir, secured->identity)));
  } else if (auto hazard = dds::ephemeral_port_hazard(domain->domain_id, dds::ephemeral_port_range())) {
    // Unsecured, a planner of this domain can be matched from another (dds/ports.h); secured, a
    // peer must authenticate and hold permissions for this domain.
    spdlog::warn("{}", *hazard);
  }

  assembly::AssemblyRequest request;
  request.board_file = *board_file;
  request.hub_file = *hub_file;
  request.backend = backend;
  request.simulation = linked_simulation();
  request.loaded_board = &*board;
  request.loaded_hub = &*hub_config;
  request.domain = *domain;
  request.name = options.name;
  request.rate_hz = options.rate_hz;
  request.log = *logger;
  request.log_lines_dropped = &log_lines_dropped();
  const auto describe = [&](const config::HubConfig& running, const std::string& board_name) {
    return fmt::format(
        "hub '{}' ({}) on board '{}' with the {} backend, {} node(s), {:.1f} Hz, DDS domain {}{}",
        running.name, running.type, board_name, backend == assembly::BackendKind::kFake ? "fake" : "linux",
        running.nodes.size(), running.rate_hz, domain->domain_id,
        secured ? fmt::format(", DDS Security as '{}'", secured->identity) : std::string());
  };
  if (options.check_only) {
    // Files and requirements only: no backend (a real board would request its GPIO outputs), no
    // DDS (it would join the network), no simulators.
    auto checked = assembly::check_hub(request);
    if (!checked) return fail(checked.error().message, kExitConfig);
    spdlog::info("configuration OK: {}", describe(checked->config, checked->board.name));
    return exit_codes::kOk;
  }

  // Before any thread exists, so that every thread hubd starts inherits the policy; after the
  // checks above, so that neither --check nor --safe-outputs ever runs real-time.
  if (options.realtime) {
    if (auto realtime = enter_realtime(options.realtime_priority); !realtime)
      return fail(realtime.error().message, kExitConfig);
    spdlog::info("real-time: SCHED_FIFO at priority {}, memory locked", options.realtime_priority);
  }
  // Before any thread exists: blocks the stop signals for every thread DDS will start.
  auto runner = runtime::CycleRunner::create();
  if (!runner) return fail(runner.error().message, kExitRuntime);
  // Only when asked for (the benchmarks): the ring is allocated here, before the first cycle.
  SystemClock trace_clock;
  std::optional<runtime::StageTrace> trace;
  if (!options.trace_stages.empty()) {
    trace.emplace(kStageTraceCapacity, trace_clock);
    runner->trace_stages(&*trace);
  }
  request.waker = runner->waker();
  // After --check returned: a check joins no network, so it has no twin to collide with.
  request.twin_check = std::chrono::milliseconds(options.twin_check_ms);
  request.request_stop = [&runner] { runner->request_stop(); };
  if (!options.no_black_box) request.black_box_directory = default_black_box_directory();
  SystemClock clock;
  auto assembled = assembly::assemble_hub(request, clock);
  if (!assembled) {
    const std::string& message = assembled.error().message;
    if (secured && message.find("create participant") != std::string::npos) {
      // Our own check passed the files: Cyclone's security plugins refused them and said why on
      // stderr just before (e.g. permissions that do not name this certificate's subject).
      return fail(
          fmt::format("{}; DDS Security identity '{}' refused by Cyclone (its reason is logged above)",
                      message, secured->identity),
          kExitConfig);
    }
    if (secured && message.find("NOT_ALLOWED_BY_SECURITY") != std::string::npos) {
      // Access control refused a topic, reader or writer: the identity's permissions do not
      // cover this hub file (hubctl security add --role hub --hub <this hub file>), or, on a
      // simulation board, the simulation's topics (--sim: docs/deploy.md, "Securing a station").
      const bool simulation = message.find("rt/sim/") != std::string::npos;
      return fail(
          fmt::format("{}; the permissions of DDS Security identity '{}' do not allow it{}", message,
                      secured->identity,
                      simulation ? fmt::format(" (a simulation board: give the identity the simulation's "
                                               "topics, hubctl security add <dir> {} --role hub --hub <hub> "
                                               "--sim)",
                                               secured->identity)
                                 : std::string()),
          kExitConfig);
    }
    return fail(assembled.error().message, assembled.error().code == ErrorCode::kInvalidArgument ||
                                                   assembled.error().code == ErrorCode::kNotFound ||
                                                   assembled.error().code == ErrorCode::kFailedPrecondition
                                               ? kExitConfig
                                               : kExitRuntime);
  }
  const std::string summary = describe((*assembled)->config, (*assembled)->board.name);
  // Start-up is over: what it freed (the YAML trees, the files' text, Cyclone's start-up
  // scratch) goes back to the system instead of staying in the resident set. malloc_trim(3)
  // releases the free pages inside the heap too (madvise), not only its top.
  malloc_trim(0);

  spdlog::info("running {}", summary);
  if (const auto& box = (*assembled)->black_box) {
    spdlog::info(
        "black box: the last {} s in {} KiB{}",
        std::chrono::duration_cast<std::chrono::seconds>((*assembled)->config.blackbox.span).count(),
        box->ring().capacity() / 1024,
        (*assembled)->config.blackbox.memory_bytes ? " (memory_kib)" : ", sized from the hub's rates");
  }
  systemd.ready(summary);
  runtime::RunHooks hooks;
  hooks.after_cycle = [&systemd](const Instant& now) { systemd.cycle_done(now.mono); };
  runtime::Hub& hub = *(*assembled)->hub;
  set_crash_black_box((*assembled)->black_box.get());
  auto stopped = runner->run(hub, clock, hooks);

  systemd.stopping();
  hub.enter_safe_state();
  hub.report_safe_state(clock.now());
  if (trace) {
    if (auto written = trace->write_csv(options.trace_stages); !written)
      spdlog::warn("{}", written.error().message);
  }
  if (!stopped) {
    spdlog::error("cycle failed: {}; outputs driven to their safe state", stopped.error().message);
    write_black_box(**assembled, "exit-error");
    set_crash_black_box(nullptr);
    return kExitRuntime;
  }
  if ((*assembled)->twins != nullptr && (*assembled)->twins->yielded()) {
    spdlog::error("{}; outputs driven to their safe state", (*assembled)->twins->yield_message());
    write_black_box(**assembled, "exit-twin");
    set_crash_black_box(nullptr);
    return kExitRuntime;
  }
  const runtime::CycleStats& stats = hub.stats();
  const bool by_signal = *stopped == runtime::StopReason::kSignal;
  const int signal = by_signal ? runner->last_signal() : 0;
  const int status = by_signal ? exit_codes::for_stop_signal(signal) : exit_codes::kOk;
  spdlog::info(
      "stopping on {}: outputs driven to their safe state after {} cycles ({} overruns, {} log "
      "lines dropped); exit status {}",
      by_signal ? signal_name(signal) : "request", stats.cycles, stats.overruns, log_lines_dropped().load(),
      status);
  write_black_box(**assembled, by_signal ? "exit-" + signal_name(signal) : "exit");
  set_crash_black_box(nullptr);
  return status;
}

}  // namespace
}  // namespace hubrt::hubd

int main(int argc, char** argv) {
  // A closed stdout/stderr (`hubd | head -1`, an SSH session gone) must never kill a hub: with
  // SIGPIPE ignored, a write to a pipe without reader fails with EPIPE (pipe(7)), and the log sink
  // drops and counts the line. Set before any thread exists, so it holds for all of them.
  std::signal(SIGPIPE, SIG_IGN);
  // One malloc arena for every thread (glibc's default is up to 8 per core, one per thread that
  // allocates): Cyclone's threads allocate a little each and every arena keeps its own free pages
  // resident. The cycle allocates nothing, so nothing real-time waits on the arena's lock; set
  // before any thread exists (mallopt(3), M_ARENA_MAX).
  mallopt(M_ARENA_MAX, 1);  // NOLINT(concurrency-mt-unsafe): no other thread exists yet
  hubrt::hubd::Options options;
  CLI::App app{"hubd — runs one hub: reads its devices, runs its nodes at a fixed rate, talks DDS"};
  app.add_option("--board", options.board, "Board name (file in the boards folder) or path to a board file")
      ->required();
  app.add_option("--hub", options.hub, "Hub type or hub file (default: the board's only hub)");
  app.add_option("--backend", options.backend,
                 "HAL backend (auto: fake for simulation boards; the board build that the packages install "
                 "has no fake backend)")
      ->check(CLI::IsMember({"auto", "fake", "linux"}));
  app.add_option("--domain", options.domain, "DDS domain id (default: $ROS_DOMAIN_ID or 0)")
      ->check(CLI::Range(0, 232));
  app.add_option("--dds-config", options.dds_config,
                 "Cyclone DDS XML configuration (default: $CYCLONEDDS_URI), read after hubd's own "
                 "bound on sample sizes (Internal/MaxSampleSize 65536 B)");
  auto* security = app.add_option(
      "--security", options.security_dir,
      "DDS Security: the station's security folder (e.g. /etc/hubrt/security), overriding the hub file's "
      "security: section; an expired or untrusted certificate is refused at start (exit 2)");
  auto* identity =
      app.add_option("--identity", options.identity, "DDS Security: the identity the hub joins as");
  security->needs(identity);
  identity->needs(security);
  app.add_flag("--loopback", options.loopback,
               "Keep DDS on the loopback interface (single-machine simulation)");
  app.add_option("--name", options.name, "Instance name, overriding the hub file's (unique on the domain)");
  app.add_option("--rate", options.rate_hz, "Cycle and heartbeat rate in Hz, overriding the hub file's")
      ->check(CLI::Range(0.01, 1000.0));
  app.add_option("--log-level", options.log_level, "trace, debug, info, warn, error, critical or off");
  app.add_option("--twin-check-ms", options.twin_check_ms,
                 "Longest discovery window at start-up in which another hub publishing this hub's States "
                 "(or announcing its name) makes this one refuse to run, before any device is opened; the "
                 "check ends earlier once discovery has been quiet for 15 ms and no hub of an older hubrt "
                 "is on the domain (0: no start-up check; a twin is still caught while running)")
      ->check(CLI::Range(0, 60000));
  app.add_flag("--no-black-box", options.no_black_box,
               "Run without the black box, whatever the hub file's blackbox: section says (what the "
               "benchmark compares the black box's cost with)");
  app.add_option("--trace-stages", options.trace_stages,
                 "Stamp every command step's stages (listener, wake, step, write) into a ring of the last "
                 "16384 and write it to this CSV file at exit (for the benchmarks; off by default)");
  app.add_flag("--realtime", options.realtime,
               "Run the cycle (and every thread of hubd) under SCHED_FIFO and lock its memory "
               "(mlockall); refused with exit status 2 where not permitted (needs CAP_SYS_NICE or "
               "LimitRTPRIO=, and CAP_IPC_LOCK or LimitMEMLOCK=)");
  app.add_option("--realtime-priority", options.realtime_priority,
                 "SCHED_FIFO priority for --realtime (1-99; default 40, below the kernel's threaded "
                 "interrupts at 50)")
      ->check(CLI::Range(1, 99));
  auto* check =
      app.add_flag("--check", options.check_only,
                   "Load and validate the board and hub files and the hub's needs against the board, "
                   "then exit; opens no device and no network");
  app.add_flag(
         "--safe-outputs", options.safe_outputs,
         "Drive the hub's GPIO outputs to their safe levels, then exit (no DDS; the unit's ExecStopPost). "
         "Exit 0: all safe; 1: some not (named in the log); 2: bad board or hub file")
      ->excludes(check);
  app.footer(hubrt::exit_codes::kHelpFooter);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11's own codes (105 validation, 106 required, 108 excludes, 109 extras...) mean "bad
    // command line": the table's 2, which the systemd unit does not restart. --help exits 0.
    return app.exit(e) == 0 ? hubrt::exit_codes::kOk : hubrt::exit_codes::kUsage;
  }
  const int status = hubrt::hubd::run(options);
  // The last lines (the stop message) get a bounded time to reach stderr: a reader that stopped
  // reading cannot hold the exit, which comes with the outputs already safe.
  hubrt::hubd::finish_logging(hubrt::hubd::kLogFinishTimeout);
  return status;
}
