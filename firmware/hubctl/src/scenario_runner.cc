#include "scenario_runner.h"

#include <fmt/format.h>

#include "scenario_steps.h"
#include "scenario_traffic.h"
#include "session.h"

namespace hubrt::hubctl {

// The run itself: rounds and steps in order, each reported as it ends, stopping at the first that
// fails or on Ctrl-C. What a step does is StepExecutor's; the DDS traffic is ScenarioTraffic's.
class ScenarioRunner::Impl {
 public:
  Impl(const dds::Participant& participant, const Scenario& scenario, PlayOptions options, std::FILE* out)
      : scenario_(scenario),
        options_(options),
        out_(out),
        traffic_(participant, options.discovery_timeout,
                 seconds(1.0 / (options.rate_hz > 0 ? options.rate_hz : scenario.rate_hz)),
                 options.command_lifespan_ms, options.ros_namespace),
        steps_(traffic_) {}

  PlayOutcome run() {
    const auto start = SteadyClock::now();
    const auto since_start = [&start] {
      return std::chrono::duration<double>(SteadyClock::now() - start).count();
    };
    if (!scenario_.description.empty() && !options_.quiet)
      fmt::print(out_, "play: {}\n", scenario_.description);
    std::fflush(out_);  // a pipe or a file sees the run begin, not only its first step's end
    traffic_.start();
    std::size_t done = 0;
    for (int round = 1; options_.rounds == 0 || round <= options_.rounds; ++round) {
      if (options_.rounds != 1 && !options_.quiet) fmt::print(out_, "play: round {}\n", round);
      for (std::size_t i = 0; i < scenario_.steps.size(); ++i) {
        const Step& step = scenario_.steps[i];
        const auto step_start = SteadyClock::now();
        StepResult result = stop_requested() ? failed("") : steps_.execute(step);
        const double took = std::chrono::duration<double>(SteadyClock::now() - step_start).count();
        // A step that did not pass because Ctrl-C cut it short (a wait that stopped waiting) has
        // not failed: what it waited for may still have come.
        const bool interrupted = !result.ok && stop_requested();
        if (!result.ok || !options_.quiet) {
          fmt::print(out_, "  {}  {:6.2f} s  [{:>3}] {}  {}\n",
                     result.ok ? "PASS" : (interrupted ? "STOP" : "FAIL"), took, i + 1, step.where,
                     step.describe());
          // Each step's line as it ends, also into a file or a pipe (a log someone follows, a
          // test waiting for a step: tests/net/run).
          std::fflush(out_);
        }
        if (interrupted) {
          fmt::print(out_, "play: interrupted at step {} of {} ({}){} after {:.1f} s; {} step(s) passed\n",
                     i + 1, scenario_.steps.size(), step.where,
                     options_.rounds != 1 ? fmt::format(" in round {}", round) : std::string(), since_start(),
                     done);
          std::fflush(out_);
          return PlayOutcome::kInterrupted;
        }
        if (!result.ok) {
          fmt::print(out_, "{}", indent(result.detail, "        "));
          fmt::print(out_, "play: FAILED at step {} of {} ({}) after {:.1f} s\n", i + 1,
                     scenario_.steps.size(), step.where, since_start());
          std::fflush(out_);
          return PlayOutcome::kFailed;
        }
        ++done;
        std::fflush(out_);
      }
      const bool more_rounds = options_.rounds == 0 || round < options_.rounds;
      if (stop_requested() && more_rounds) {  // all rounds done: it passed, signal or not
        fmt::print(out_, "play: interrupted after round {}; {} step(s) passed in {:.1f} s\n", round, done,
                   since_start());
        std::fflush(out_);
        return PlayOutcome::kInterrupted;
      }
    }
    fmt::print(out_, "play: PASSED: {} step(s) in {:.1f} s\n", done, since_start());
    std::fflush(out_);
    return PlayOutcome::kPassed;
  }

 private:
  const Scenario& scenario_;
  PlayOptions options_;
  std::FILE* out_;
  ScenarioTraffic traffic_;
  StepExecutor steps_;
};

ScenarioRunner::ScenarioRunner(const dds::Participant& participant, const Scenario& scenario,
                               PlayOptions options, std::FILE* out)
    : impl_(std::make_unique<Impl>(participant, scenario, options, out)) {}

ScenarioRunner::~ScenarioRunner() = default;

PlayOutcome ScenarioRunner::run() {
  return impl_->run();
}

}  // namespace hubrt::hubctl
