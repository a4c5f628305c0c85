// hubctl play FILE: run a scenario — commands as the planner sends them, waits on States, acts on
// the simulated world — and report each step; the exit code says whether all passed (0), a step
// failed (1), the file is wrong (2) or Ctrl-C/SIGTERM stopped the run (130/143).
// hubctl play FILE.mcap: replay a recording's commands (or the topics chosen) at the recorded pace
// (recording_player.h).
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command_channel.h"
#include "commands.h"
#include "recording_player.h"
#include "scenario.h"
#include "scenario_runner.h"
#include "session.h"

namespace hubrt::hubctl {
namespace {

struct PlayCommandOptions {
  DomainOptions domain;
  std::vector<std::string> files;
  double rate_hz = 0.0;  // a scenario's repeat rate; a recording's pace factor
  TapChoice topics;      // recordings: which topics (default: the commands)
  double start_s = 0;
  std::optional<double> end_s;
  int rounds = 1;
  bool quiet = false;
  bool check_only = false;
  std::uint32_t lifespan_ms = kDefaultCommandLifespanMs;
  std::string ros_namespace;  // a scenario's station: its hubs' namespace and its simulation's
};

int run_recording(const PlayCommandOptions& options) {
  if (options.check_only) {
    fmt::print("{}: an MCAP recording\n", options.files.front());
    return kExitOk;
  }
  auto participant = join_domain(options.domain, "hubctl");
  if (!participant) {
    fmt::print(stderr, "hubctl play: {}\n", participant.error().message);
    return kExitUsage;
  }
  RecordingPlayOptions play;
  play.files = options.files;
  play.rate = options.rate_hz > 0 ? options.rate_hz : 1.0;
  play.start_s = options.start_s;
  play.end_s = options.end_s;
  play.choice = options.topics;
  play.discovery_timeout = seconds(options.domain.timeout_s);
  play.quiet = options.quiet;
  play.command_lifespan_ms = options.lifespan_ms;
  return play_recording(*participant, play, stdout);
}

int run_play(const PlayCommandOptions& options) {
  install_stop_handler();
  if (is_mcap_file(options.files.front())) return run_recording(options);
  if (options.files.size() > 1) {
    fmt::print(stderr, "hubctl play: one scenario at a time ({} given)\n", options.files.size());
    return kExitUsage;
  }
  auto scenario = load_scenario(options.files.front());
  if (!scenario) {
    fmt::print(stderr, "hubctl play: {}\n", scenario.error().message);
    return kExitUsage;
  }
  if (options.check_only) {
    fmt::print("{}: {} step(s), OK\n", options.files.front(), scenario->steps.size());
    return kExitOk;
  }
  auto participant = join_domain(options.domain, "hubctl");
  if (!participant) {
    fmt::print(stderr, "hubctl play: {}\n", participant.error().message);
    return kExitUsage;
  }
  PlayOptions play;
  play.rate_hz = options.rate_hz;
  play.discovery_timeout = seconds(options.domain.timeout_s);
  play.rounds = options.rounds;
  play.quiet = options.quiet;
  play.command_lifespan_ms = options.lifespan_ms;
  play.ros_namespace = options.ros_namespace;
  ScenarioRunner runner(*participant, *scenario, play, stdout);
  switch (runner.run()) {
    case PlayOutcome::kPassed:
      return kExitOk;
    case PlayOutcome::kFailed:
      return kExitFailed;
    case PlayOutcome::kInterrupted:
      return interrupted_exit_status();
  }
  return kExitFailed;
}

}  // namespace

void add_play_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<PlayCommandOptions>();
  CLI::App* cmd = app.add_subcommand("play",
                                     "Run a scenario (YAML steps: commands, waits on States, sim actions) "
                                     "and report each step, or replay a recording (FILE.mcap)");
  cmd->footer(
      "Exit status: 0 every step passed; 1 a step failed; 2 the scenario file or the options are wrong; "
      "130 (143) interrupted by Ctrl-C (SIGTERM): the step cut short is reported as STOP and the run as "
      "\"play: interrupted at step N\", never as failed. A recording: 0 played; 1 nothing to play or a "
      "write failed; 2 the file is not one; 130 (143) interrupted.");
  cmd->add_option("file", options->files,
                  "Scenario file, e.g. hubs/station/scenarios/use-case.yaml; or a recording (hubctl record, "
                  "the parts of a split one in order)")
      ->required();
  cmd->add_option("--rate,-r", options->rate_hz,
                  "Scenario: command repeat rate in Hz (default: the scenario's). Recording: the pace as a "
                  "factor of the recorded one (default 1; 2 = twice as fast)")
      ->check(CLI::Range(0.01, 1000.0));
  cmd->add_option("--topics", options->topics.topics, "Recording: play these topics (default: its commands)");
  cmd->add_option("--regex", options->topics.regex, "Recording: play the topics whose whole name matches");
  cmd->add_option("--start", options->start_s, "Recording: begin this many seconds after its first message")
      ->check(CLI::Range(0.0, 1e9));
  cmd->add_option("--end", options->end_s, "Recording: stop this many seconds after its first message")
      ->check(CLI::Range(0.0, 1e9));
  cmd->add_option("--rounds", options->rounds, "Run the steps this many times; 0 = until Ctrl-C")
      ->check(CLI::Range(0, 1'000'000));
  cmd->add_flag("--quiet,-q", options->quiet, "Report failures and the summary only");
  cmd->add_flag("--check", options->check_only, "Only load and check the file (a scenario)");
  add_lifespan_option(*cmd, options->lifespan_ms);
  add_namespace_option(
      *cmd, options->ros_namespace,
      "Scenario: the station's ROS namespace, e.g. /cell_a: its hubs are found under it (their "
      "hub files' namespace:) and the simulation's topics are under it (hubsim --namespace); for "
      "stations that share one domain (docs/plant.md)");
  add_domain_options(*cmd, options->domain);
  cmd->callback([options, &exit_code] { exit_code = run_play(*options); });
}

}  // namespace hubrt::hubctl
