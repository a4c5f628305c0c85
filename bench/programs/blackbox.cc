// The black box's cost (issue 30 point 3): CPU and RSS of a hub with its black box recording
// against the same hub with it off (hubd --no-black-box), side by side in one run.
//
// Two hubd (Dock ECU, fake backend, same rate, --name dock_on / dock_off) in one private domain on
// loopback take the same planner's commands (hubctl send /dock/command at 100 Hz: both hubs read that
// topic) and this process reads both hubs' States, so both record and publish the same traffic. CPU:
// in turns (cpu_turns.h: each hub measured while the other is stopped), the median of the rounds'
// on / off ratios and each side's mean; RSS: each hub's resident set after the turns, once the ring
// is full (the warm-up runs until the "on" hub's ring has wrapped at least once at 1 kHz, and for the
// 60 s default at 100 Hz the ring is touched in full at start anyway).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "bench_common.h"
#include "cpu_turns.h"
#include "dock.h"
#include "proc_stats.h"
#include "raw_dds.h"

namespace hubrt::bench {
namespace {

double mean_of(const std::vector<double>& values) {
  double sum = 0;
  for (const double v : values) sum += v;
  return values.empty() ? 0 : sum / static_cast<double>(values.size());
}

Expected<nlohmann::ordered_json> measure(dds_entity_t participant, double rate, double warmup_s,
                                         const CpuTurnsOptions& turns) {
  const std::string hz = fmt::format("{}", rate);
  auto on = start_hubd({"--hub", "dock_ecu", "--name", "dock_on", "--rate", hz});
  if (!on) return std::move(on).error();
  auto off = start_hubd({"--hub", "dock_ecu", "--name", "dock_off", "--rate", hz, "--no-black-box"});
  if (!off) return std::move(off).error();
  auto planner = test_support::ChildProcess::start(
      hubctl_path(), {"send", "/dock/command", "target_type=dock", "target_name=dock", "action=monitor",
                      "--rate", "100", "-q", "--timeout", "60"});
  if (!planner) return std::move(planner).error();
  auto on_reader = raw_reader(participant, hub_msgs_msg_dds__DockState__desc, "rt/dock_on/dock/state");
  auto off_reader = raw_reader(participant, hub_msgs_msg_dds__DockState__desc, "rt/dock_off/dock/state");
  if (!on_reader || !off_reader) return make_error(ErrorCode::kUnavailable, "readers of the hubs' States");
  const dds_entity_t waitset = dds_create_waitset(participant);
  dds_waitset_attach(waitset, dds_create_readcondition(*on_reader, DDS_ANY_STATE), 0);
  dds_waitset_attach(waitset, dds_create_readcondition(*off_reader, DDS_ANY_STATE), 1);
  std::uint64_t states[2] = {0, 0};
  const auto drain = [&](dds_entity_t reader, std::uint64_t& count) {
    void* samples[64] = {};
    dds_sample_info_t infos[64];
    for (;;) {
      const dds_return_t n = dds_take(reader, samples, infos, 64, 64);
      if (n <= 0) return;
      count += static_cast<std::uint64_t>(n);
      dds_return_loan(reader, samples, n);
    }
  };
  const auto idle = [&](double seconds) {
    const double until = mono_now() + seconds;
    for (double now = mono_now(); now < until; now = mono_now()) {
      dds_attach_t fired[2];
      dds_waitset_wait(waitset, fired, 2, static_cast<dds_duration_t>(std::min(until - now, 0.1) * 1e9));
      drain(*on_reader, states[0]);
      drain(*off_reader, states[1]);
    }
  };
  progress(fmt::format("black box {} Hz: warm-up {} s (both hubs commanded and read)", rate, warmup_s));
  idle(warmup_s);
  if (states[0] == 0 || states[1] == 0) {
    return make_error(ErrorCode::kUnavailable,
                      fmt::format("no States from a hub (on {}, off {})", states[0], states[1]));
  }
  progress(
      fmt::format("black box {} Hz: CPU in turns, {} rounds of {} s each", rate, turns.rounds, turns.turn_s));
  auto in_turns = measure_cpu_in_turns(*on, *off, turns, idle);
  auto on_proc = read_proc(on->pid());
  auto off_proc = read_proc(off->pid());
  dds_delete(waitset);
  dds_delete(*on_reader);
  dds_delete(*off_reader);
  stop(*planner);
  stop(*on);
  stop(*off);
  if (!in_turns) return std::move(in_turns).error();
  if (!on_proc || !off_proc) return make_error(ErrorCode::kUnavailable, "a hub died");
  nlohmann::ordered_json out;
  out["rate_hz"] = rate;
  out["warmup_s"] = warmup_s;
  out["states_read"] = {{"on", states[0]}, {"off", states[1]}};
  out["cpu_on_pct"] = mean_of(in_turns->a_pct);
  out["cpu_off_pct"] = mean_of(in_turns->b_pct);
  out["ratio_cpu"] = in_turns->median;
  out["ratio_cpu_min"] = in_turns->min;
  out["ratio_cpu_max"] = in_turns->max;
  out["same_program_change"] = in_turns->same_program_change;
  out["turns"] = {{"rounds", turns.rounds}, {"turn_s", turns.turn_s}, {"ratios", in_turns->ratios}};
  out["rss_on_mb"] = on_proc->rss_mb;
  out["rss_off_mb"] = off_proc->rss_mb;
  out["anon_on_mb"] = on_proc->anon_mb;
  out["anon_off_mb"] = off_proc->anon_mb;
  return out;
}

int run(const std::string& out_file, const std::vector<double>& rates, double warmup_s,
        const CpuTurnsOptions& turns) {
  auto domain = join_private_domain();
  if (!domain) return fmt::print(stderr, "{}\n", domain.error().message), 1;
  auto participant = raw_participant(domain_from_environment());
  if (!participant) return fmt::print(stderr, "{}\n", participant.error().message), 1;
  nlohmann::ordered_json result;
  result["hub"] = "Dock ECU, development build, host-sim, fake backend; planner at 100 Hz";
  result["black_box"] = "hub file defaults: the last 60 s, in a ring sized from the hub's rates";
  result["rates"] = nlohmann::ordered_json::array();
  for (const double rate : rates) {
    auto measured = measure(*participant, rate, warmup_s, turns);
    if (!measured) return fmt::print(stderr, "{}\n", measured.error().message), 1;
    progress(
        fmt::format("black box {} Hz: CPU on {:.2f} %, off {:.2f} % (on / off in turns {:.2f}x); RSS on "
                    "{:.1f} MB, off {:.1f} MB",
                    rate, (*measured)["cpu_on_pct"].get<double>(), (*measured)["cpu_off_pct"].get<double>(),
                    (*measured)["ratio_cpu"].get<double>(), (*measured)["rss_on_mb"].get<double>(),
                    (*measured)["rss_off_mb"].get<double>()));
    result["rates"].push_back(std::move(*measured));
  }
  dds_delete(*participant);
  if (auto ok = write_json(out_file, result); !ok) return fmt::print(stderr, "{}\n", ok.error().message), 1;
  return 0;
}

}  // namespace
}  // namespace hubrt::bench

int main(int argc, char** argv) {
  CLI::App app{"The black box's cost: a hub's CPU and RSS with it on and off, side by side"};
  std::string out = "blackbox.json";
  std::vector<double> rates{100, 1000};
  double warmup_s = 10;
  hubrt::bench::CpuTurnsOptions turns;
  app.add_option("--out", out, "Result file (JSON)");
  app.add_option("--rates", rates, "Hub rates in Hz");
  app.add_option("--warmup", warmup_s, "Seconds both hubs run before anything is measured")
      ->check(CLI::Range(1.0, 600.0));
  app.add_option("--cpu-turns", turns.rounds, "Rounds of CPU measured in turns")->check(CLI::Range(1, 1000));
  app.add_option("--cpu-turn-seconds", turns.turn_s, "Length of each turn")->check(CLI::Range(0.1, 600.0));
  CLI11_PARSE(app, argc, argv);
  return hubrt::bench::run(out, rates, warmup_s, turns);
}
