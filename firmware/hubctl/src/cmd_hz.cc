// hubctl hz TOPIC: the rate a topic really has, its period jitter, and gaps in its State
// sequence numbers — what the heartbeat looks like from the planner's side of the wire.
#include <thread>

#include <fmt/format.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"

#include "commands.h"
#include "field_path.h"
#include "session.h"
#include "stats.h"

namespace hubrt::hubctl {
namespace {

struct HzOptions {
  DomainOptions domain;
  std::string topic;
  std::string type;
  double window_s = 0;  // 0 = until stopped
  bool json = false;
};

struct HzResult {
  std::size_t samples = 0;
  double rate_hz = 0;
  Summary period_ms;        // between arrivals here: what a planner sees, this host's delays included
  Summary stamp_period_ms;  // between the States' header stamps: when the hub itself published
  bool has_stamp = false;
  std::uint64_t gaps = 0;      // missing sequence numbers
  std::uint64_t reorders = 0;  // sequence numbers that went backwards
  bool has_seq = false;
};

std::string summary_json(const Summary& s) {
  return fmt::format(R"({{"min":{:.3f},"p50":{:.3f},"p90":{:.3f},"p99":{:.3f},"max":{:.3f}}})", s.min, s.p50,
                     s.p90, s.p99, s.max);
}

void print(const HzResult& r, bool json) {
  if (json) {
    fmt::print(
        R"({{"samples":{},"rate_hz":{:.3f},"period_ms":{},"stamp_period_ms":{},"seq_gaps":{},"seq_backwards":{}}})"
        "\n",
        r.samples, r.rate_hz, summary_json(r.period_ms),
        r.has_stamp ? summary_json(r.stamp_period_ms) : std::string("null"), r.gaps, r.reorders);
    return;
  }
  fmt::print(
      "rate {:8.3f} Hz  period ms: min {:.3f} p50 {:.3f} p90 {:.3f} p99 {:.3f} max {:.3f}{}  {}  ({} "
      "samples)\n",
      r.rate_hz, r.period_ms.min, r.period_ms.p50, r.period_ms.p90, r.period_ms.p99, r.period_ms.max,
      r.has_stamp
          ? fmt::format("  by stamps: p99 {:.3f} max {:.3f}", r.stamp_period_ms.p99, r.stamp_period_ms.max)
          : std::string(),
      r.has_seq ? fmt::format("seq gaps {} backwards {}", r.gaps, r.reorders) : std::string("no seq field"),
      r.samples);
}

int run_hz(const HzOptions& options) {
  install_stop_handler();
  auto ros_name = ros_topic(options.topic);
  if (!ros_name) {
    fmt::print(stderr, "hubctl hz: {}\n", ros_name.error().message);
    return kExitUsage;
  }
  auto participant = join_domain(options.domain, "hubctl");
  if (!participant) {
    fmt::print(stderr, "hubctl hz: {}\n", participant.error().message);
    return kExitUsage;
  }
  auto type = topic_type(*participant, *ros_name, options.type, seconds(options.domain.timeout_s));
  if (!type) {
    fmt::print(stderr, "hubctl hz: {}\n", type.error().message);
    return kExitUsage;
  }
  const msgs::TypeInfo& info = **type;
  auto topic = dds::UntypedTopic::create(*participant, *info.descriptor, *ros_name);
  if (!topic) return fmt::print(stderr, "hubctl hz: {}\n", topic.error().message), kExitFailed;
  // A deep history: a receiver that stalls (a loaded host) takes the States late instead of losing
  // them, so a sequence gap is a State the hub did not publish or the network lost. 1000: over
  // a second at 1 kHz, 100 s at 10 Hz.
  auto reader = dds::UntypedReader::create(*participant, *topic, dds::Qos::ros2_default(1000));
  if (!reader) return fmt::print(stderr, "hubctl hz: {}\n", reader.error().message), kExitFailed;
  const auto seq_field = locate(info, "header.seq");
  const auto stamp_sec = locate(info, "header.stamp.sec");
  const auto stamp_nanosec = locate(info, "header.stamp.nanosec");

  dds::UntypedSample sample(*info.descriptor);
  std::vector<double> periods_ms;
  std::vector<double> stamp_periods_ms;
  HzResult result;
  result.has_seq = seq_field.has_value();
  result.has_stamp = stamp_sec && stamp_nanosec;
  std::optional<double> last_stamp_ms;
  std::optional<double> last_seq;
  std::optional<std::chrono::steady_clock::time_point> first;
  std::optional<std::chrono::steady_clock::time_point> last;
  const auto start = std::chrono::steady_clock::now();
  auto next_report = start + std::chrono::seconds(1);
  while (!stop_requested()) {
    const auto now = std::chrono::steady_clock::now();
    if (options.window_s > 0 && now - start >= seconds(options.window_s)) break;
    if (!first && now - start > seconds(options.domain.timeout_s)) {
      fmt::print(stderr, "hubctl hz: no sample on {} within {:.1f} s\n", *ros_name, options.domain.timeout_s);
      return kExitFailed;
    }
    const Result<bool> taken = reader->take_next(sample.data());
    if (!taken.is_ok()) return fmt::print(stderr, "hubctl hz: take failed\n"), kExitFailed;
    if (!taken.value()) {
      if (options.window_s == 0 && !options.json && now >= next_report && result.samples > 1) {
        result.period_ms = summarize(periods_ms);
        result.stamp_period_ms = summarize(stamp_periods_ms);
        result.rate_hz =
            static_cast<double>(result.samples - 1) / std::chrono::duration<double>(*last - *first).count();
        print(result, false);
        next_report += std::chrono::seconds(1);
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      continue;
    }
    // Arrival time, measured here: what the planner experiences, transport included.
    const auto arrived = std::chrono::steady_clock::now();
    if (last) periods_ms.push_back(std::chrono::duration<double, std::milli>(arrived - *last).count());
    if (!first) first = arrived;
    last = arrived;
    ++result.samples;
    if (seq_field) {
      const double seq = read_number(sample.data(), *seq_field).value_or(0);
      if (last_seq) {
        if (seq > *last_seq + 1) result.gaps += static_cast<std::uint64_t>(seq - *last_seq - 1);
        if (seq <= *last_seq) ++result.reorders;
      }
      last_seq = seq;
    }
    if (result.has_stamp) {
      // The hub's own clock: a late period here is the hub's, one only in the arrivals is the
      // path's or this host's (a stalled receiver), as conformance judges it.
      const double stamp_ms = read_number(sample.data(), *stamp_sec).value_or(0) * 1e3 +
                              read_number(sample.data(), *stamp_nanosec).value_or(0) * 1e-6;
      if (last_stamp_ms) stamp_periods_ms.push_back(stamp_ms - *last_stamp_ms);
      last_stamp_ms = stamp_ms;
    }
  }
  if (result.samples > 1) {
    result.period_ms = summarize(periods_ms);
    result.stamp_period_ms = summarize(stamp_periods_ms);
    result.rate_hz =
        static_cast<double>(result.samples - 1) / std::chrono::duration<double>(*last - *first).count();
  }
  print(result, options.json);
  return result.samples > 1 ? kExitOk : kExitFailed;
}

}  // namespace

void add_hz_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<HzOptions>();
  CLI::App* cmd = app.add_subcommand("hz", "Measure a topic's rate, period jitter and State sequence gaps");
  cmd->add_option("topic", options->topic, "ROS topic name, e.g. /dock_ecu/dock/state")->required();
  cmd->add_option("--type", options->type, "Message type, when no one has announced the topic yet");
  cmd->add_option("--window,-w", options->window_s, "Measure for this many seconds, then print one summary")
      ->check(CLI::Range(0.0, 86400.0));
  cmd->add_flag("--json", options->json, "Print the summary as JSON");
  add_domain_options(*cmd, options->domain);
  cmd->callback([options, &exit_code] { exit_code = run_hz(*options); });
}

}  // namespace hubrt::hubctl
