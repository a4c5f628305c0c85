// hubctl play FILE: run a scenario — commands as the planner sends them, waits on States, acts on
// the simulated world — and report each step; the exit code says whether all passed (0), a step
// failed (1), the file is wrong (2) or Ctrl-C/SIGTERM stopped the run (130/143).
#include <fmt/format.h>

#include "command_channel.h"
#include "commands.h"
#include "scenario.h"
#include "scenario_runner.h"
#include "session.h"

namespace hubrt::hubctl {
namespace {

struct PlayCommandOptions {
  DomainOptions domain;
  std::string file;
  double rate_hz = 0.0;
  int rounds = 1;
  bool quiet = false;
  bool check_only = false;
  std::uint32_t lifespan_ms = kDefaultCommandLifespanMs;
};

int run_play(const PlayCommandOptions& options) {
  install_stop_handler();
  auto scenario = load_scenario(options.file);
  if (!scenario) {
    fmt::print(stderr, "hubctl play: {}\n", scenario.error().message);
    return kExitUsage;
  }
  if (options.check_only) {
    fmt::print("{}: {} step(s), OK\n", options.file, scenario->steps.size());
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
                                     "and report each step");
  cmd->footer(
      "Exit status: 0 every step passed; 1 a step failed; 2 the scenario file or the options are wrong; "
      "130 (143) interrupted by Ctrl-C (SIGTERM): the step cut short is reported as STOP and the run as "
      "\"play: interrupted at step N\", never as failed.");
  cmd->add_option("file", options->file, "Scenario file, e.g. hubs/station/scenarios/use-case.yaml")
      ->required();
  cmd->add_option("--rate,-r", options->rate_hz, "Command repeat rate in Hz (default: the scenario's)")
      ->check(CLI::Range(0.1, 1000.0));
  cmd->add_option("--rounds", options->rounds, "Run the steps this many times; 0 = until Ctrl-C")
      ->check(CLI::Range(0, 1'000'000));
  cmd->add_flag("--quiet,-q", options->quiet, "Report failures and the summary only");
  cmd->add_flag("--check", options->check_only, "Only load and check the file");
  add_lifespan_option(*cmd, options->lifespan_ms);
  add_domain_options(*cmd, options->domain);
  cmd->callback([options, &exit_code] { exit_code = run_play(*options); });
}

}  // namespace hubrt::hubctl
