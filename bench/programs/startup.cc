// Start -> first State: from spawning hubd to its first State arriving at a subscriber that was
// already listening, side by side with a raw Cyclone program (the bare heartbeat: create a
// participant and a writer, write at the same rate). Both include process start, DDS start-up and
// discovery; the hub adds loading its board and hub files, its twin check's discovery window and
// building its nodes. States written before discovery completes reach nobody (volatile
// durability), so the raw writer's first one received is the first written after it: at 10 Hz that
// rounds its figure up to the next 100 ms period. The hub publishes its State at once when the
// subscriber's reader matches, so its figure is when it became reachable at every rate. Both rates
// are measured; runs alternate hub and raw.
#include <ctime>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "bench_common.h"
#include "dock.h"
#include "raw_dds.h"

namespace hubrt::bench {
namespace {

double wall_now() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

struct FirstState {
  double after_s = -1;        // spawn -> arrival here
  double built_after_s = -1;  // spawn -> the publisher's stamp of that State
  std::uint64_t seq = 0;
};

void drain(dds_entity_t reader) {
  void* samples[16] = {};
  dds_sample_info_t infos[16];
  for (dds_return_t n = dds_take(reader, samples, infos, 16, 16); n > 0;
       n = dds_take(reader, samples, infos, 16, 16))
    dds_return_loan(reader, samples, n);
}

template <class Start>
Expected<FirstState> time_first_state(dds_entity_t reader, dds_entity_t waitset, Start&& start) {
  drain(reader);
  const double wall0 = wall_now();
  const double t0 = mono_now();
  auto child = start();
  if (!child) return std::move(child).error();
  FirstState first;
  while (first.after_s < 0 && mono_now() - t0 < 15.0) {
    dds_attach_t fired = 0;
    if (dds_waitset_wait(waitset, &fired, 1, DDS_MSECS(100)) <= 0) continue;
    const double arrived = mono_now();
    void* samples[16] = {};
    dds_sample_info_t infos[16];
    const dds_return_t n = dds_take(reader, samples, infos, 16, 16);
    for (dds_return_t i = 0; i < n && first.after_s < 0; ++i) {
      if (!infos[i].valid_data) continue;
      const auto* state = static_cast<const hub_msgs_msg_dds__DockState_*>(samples[i]);
      first.after_s = arrived - t0;
      first.seq = state->header.seq;
      first.built_after_s = static_cast<double>(state->header.stamp.sec) +
                            static_cast<double>(state->header.stamp.nanosec) * 1e-9 - wall0;
    }
    if (n > 0) dds_return_loan(reader, samples, n);
  }
  stop(*child);
  if (first.after_s < 0) return make_error(ErrorCode::kTimeout, "no State within 15 s of the start");
  return first;
}

struct Series {
  std::vector<double> after_ms;
  std::vector<double> built_ms;
  std::size_t saw_first_seq = 0;
  void add(const FirstState& f) {
    after_ms.push_back(f.after_s * 1e3);
    if (f.seq == 1) {
      built_ms.push_back(f.built_after_s * 1e3);
      ++saw_first_seq;
    }
  }
  nlohmann::ordered_json json() const {
    nlohmann::ordered_json out;
    out["first_state_ms"] = summary_json(after_ms);
    out["first_built_ms"] = summary_json(built_ms);
    out["runs_that_got_seq_1"] = saw_first_seq;
    return out;
  }
};

Expected<nlohmann::ordered_json> measure(dds_entity_t hub_reader, dds_entity_t hub_waitset,
                                         dds_entity_t raw_reader_, dds_entity_t raw_waitset_, double rate,
                                         std::size_t runs, const std::vector<std::string>& hubd_args) {
  Series hub;
  Series raw;
  const std::string rate_text = fmt::format("{}", rate);
  progress(
      fmt::format("start -> first State at {} Hz: {} runs each of hubd and the raw program", rate, runs));
  for (std::size_t i = 0; i < runs; ++i) {
    auto h = time_first_state(hub_reader, hub_waitset, [&] {
      std::vector<std::string> args = {"--hub", "dock_ecu", "--rate", rate_text};
      args.insert(args.end(), hubd_args.begin(), hubd_args.end());
      return start_hubd(args);
    });
    if (!h) return make_error(h.error().code, "hubd: " + h.error().message);
    hub.add(*h);
    auto r = time_first_state(raw_reader_, raw_waitset_, [&] {
      return test_support::ChildProcess::start(HUBRT_RAW_PEER_PATH, {"heartbeat", "--rate", rate_text});
    });
    if (!r) return make_error(r.error().code, "raw: " + r.error().message);
    raw.add(*r);
  }
  nlohmann::ordered_json result;
  result["rate_hz"] = rate;
  result["runs"] = runs;
  result["hubd_args"] = hubd_args;
  result["hub"] = hub.json();
  result["raw"] = raw.json();
  const auto hub_p50 = summary_of(hub.after_ms).p50;
  const auto raw_p50 = summary_of(raw.after_ms).p50;
  result["ratio_p50"] = raw_p50 > 0 ? hub_p50 / raw_p50 : 0.0;
  progress(fmt::format("start -> first State at {} Hz, p50: hub {:.1f} ms, raw {:.1f} ms", rate, hub_p50,
                       raw_p50));
  return result;
}

int run(const std::string& out, std::size_t runs, const std::vector<double>& rates,
        const std::vector<std::string>& hubd_args) {
  auto domain = join_private_domain();
  if (!domain) return fmt::print(stderr, "{}\n", domain.error().message), 1;
  auto participant = raw_participant(domain->domain_id());
  if (!participant) return fmt::print(stderr, "{}\n", participant.error().message), 1;
  auto hub_reader = raw_reader(*participant, hub_msgs_msg_dds__DockState__desc, "rt/dock_ecu/dock/state");
  auto raw_reader_ = raw_reader(*participant, hub_msgs_msg_dds__DockState__desc, "rt/bench/heartbeat");
  if (!hub_reader || !raw_reader_) return fmt::print(stderr, "cannot create readers\n"), 1;
  auto hub_waitset = raw_waitset(*participant, *hub_reader);
  auto raw_waitset_ = raw_waitset(*participant, *raw_reader_);
  if (!hub_waitset || !raw_waitset_) return fmt::print(stderr, "cannot create waitsets\n"), 1;
  nlohmann::ordered_json result;
  result["rates"] = nlohmann::ordered_json::array();
  for (const double rate : rates) {
    auto measured = measure(*hub_reader, *hub_waitset, *raw_reader_, *raw_waitset_, rate, runs, hubd_args);
    if (!measured) return fmt::print(stderr, "{}\n", measured.error().message), 1;
    result["rates"].push_back(std::move(*measured));
  }
  dds_delete(*participant);
  if (auto ok = write_json(out, result); !ok) return fmt::print(stderr, "{}\n", ok.error().message), 1;
  return 0;
}

}  // namespace
}  // namespace hubrt::bench

int main(int argc, char** argv) {
  CLI::App app{"Start -> first State: hubd vs a raw Cyclone writer"};
  std::string out = "startup.json";
  std::size_t runs = 10;
  std::vector<double> rates{10, 1000};
  app.add_option("--out", out, "Result file (JSON)");
  app.add_option("--runs", runs, "Starts of each, per rate");
  app.add_option("--rates", rates, "Rates in Hz (the shipped Dock ECU runs at 10)");
  std::vector<std::string> hubd_args;
  app.add_option(
      "--hubd-arg", hubd_args,
      "One more argument for hubd (repeatable), e.g. --hubd-arg=--twin-check-ms=0 to see the start-up "
      "without the twin check's discovery window");
  std::string hubd;
  app.add_option("--hubd", hubd,
                 "The hubd program to start (default: this build's), e.g. another build's to compare")
      ->check(CLI::ExistingFile);
  CLI11_PARSE(app, argc, argv);
  if (!hubd.empty()) hubrt::bench::use_hubd(hubd);
  return hubrt::bench::run(out, runs, rates, hubd_args);
}
