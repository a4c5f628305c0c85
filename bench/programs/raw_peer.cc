// The baselines, written directly on the Cyclone DDS C API with the hub's message types and QoS:
//   hubrt_bench_raw_peer pong                 answers every DockCommand on rt/bench/ping with a DockState
//                                            echoing it on rt/bench/pong (a ping-pong of the hub's payload)
//   hubrt_bench_raw_peer sink --topic T       takes and drops every DockState on DDS topic T (a subscriber
//                                            in another process); says "raw sink matched" once a writer is
//   hubrt_bench_raw_peer heartbeat --rate R   a bare clock_nanosleep loop (absolute deadlines) that writes
//                                            a DockState on rt/bench/heartbeat at each wake-up, stamped with
//                                            the wake-up time, as a hub stamps its cycle
// Domain from ROS_DOMAIN_ID, configuration from CYCLONEDDS_URI. Runs until SIGTERM or SIGINT.
#include <csignal>
#include <cstring>
#include <ctime>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hubrt/msgs/typed.h"

#include "dock.h"
#include "raw_dds.h"

namespace hubrt::bench {
namespace {

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_signal(int /*signal*/) {
  g_stop = 1;
}

// A DockState shaped like the Dock ECU's: name, echo, four slots (their names in fixed buffers).
struct StateShape {
  std::array<hub_msgs_msg_dds__DockSlot_, 4> slots{};
  hub_msgs_msg_dds__DockState_ state{};
  StateShape() {
    static const char* names[] = {"ladder_frame_tool", "filter_tool", "smart_tool", "spare"};
    for (std::size_t i = 0; i < slots.size(); ++i) hubrt::msgs::typed::assign(slots[i].name, names[i]);
    hubrt::msgs::typed::assign(state.name, "dock");
    state.slots._buffer = slots.data();
    state.slots._length = state.slots._maximum = static_cast<std::uint32_t>(slots.size());
  }
  void stamp(std::uint64_t seq) {
    timespec wall{};
    clock_gettime(CLOCK_REALTIME, &wall);
    state.header.seq = seq;
    state.header.stamp.sec = static_cast<std::int32_t>(wall.tv_sec);
    state.header.stamp.nanosec = static_cast<std::uint32_t>(wall.tv_nsec);
  }
};

int fail(const Error& error) {
  fmt::print(stderr, "raw_peer: {}\n", error.message);
  return 1;
}

int run_pong() {
  auto participant = raw_participant(domain_from_environment());
  if (!participant) return fail(participant.error());
  auto reader = raw_reader(*participant, hub_msgs_msg_dds__DockCommand__desc, "rt/bench/ping");
  if (!reader) return fail(reader.error());
  auto writer = raw_writer(*participant, hub_msgs_msg_dds__DockState__desc, "rt/bench/pong");
  if (!writer) return fail(writer.error());
  auto waitset = raw_waitset(*participant, *reader);
  if (!waitset) return fail(waitset.error());
  fmt::print("raw pong ready\n");
  std::fflush(stdout);
  StateShape shape;
  std::uint64_t seq = 0;
  while (g_stop == 0) {
    dds_attach_t fired = 0;
    if (dds_waitset_wait(*waitset, &fired, 1, DDS_MSECS(100)) <= 0) continue;
    void* samples[1] = {nullptr};
    dds_sample_info_t info{};
    while (dds_take(*reader, samples, &info, 1, 1) > 0) {
      if (info.valid_data) {
        const auto* command = static_cast<const hub_msgs_msg_dds__DockCommand_*>(samples[0]);
        shape.state.echo = *command;  // borrowed strings, written before they are returned
        shape.state.fresh_msg = true;
        shape.stamp(++seq);
        dds_write(*writer, &shape.state);
      }
      dds_return_loan(*reader, samples, 1);
      samples[0] = nullptr;
    }
  }
  dds_delete(*participant);
  return 0;
}

int run_sink(const std::string& topic) {
  auto participant = raw_participant(domain_from_environment());
  if (!participant) return fail(participant.error());
  auto reader = raw_reader(*participant, hub_msgs_msg_dds__DockState__desc, topic);
  if (!reader) return fail(reader.error());
  auto waitset = raw_waitset(*participant, *reader);
  if (!waitset) return fail(waitset.error());
  bool matched = false;
  while (g_stop == 0) {
    if (!matched) {
      dds_subscription_matched_status_t status{};
      if (dds_get_subscription_matched_status(*reader, &status) >= 0 && status.current_count > 0) {
        matched = true;
        fmt::print("raw sink matched\n");
        std::fflush(stdout);
      }
    }
    dds_attach_t fired = 0;
    if (dds_waitset_wait(*waitset, &fired, 1, DDS_MSECS(100)) <= 0) continue;
    void* samples[16] = {};
    dds_sample_info_t infos[16];
    for (dds_return_t n = dds_take(*reader, samples, infos, 16, 16); n > 0;
         n = dds_take(*reader, samples, infos, 16, 16)) {
      dds_return_loan(*reader, samples, n);
    }
  }
  dds_delete(*participant);
  return 0;
}

int run_heartbeat(double rate_hz) {
  auto participant = raw_participant(domain_from_environment());
  if (!participant) return fail(participant.error());
  auto writer = raw_writer(*participant, hub_msgs_msg_dds__DockState__desc, "rt/bench/heartbeat");
  if (!writer) return fail(writer.error());
  fmt::print("raw heartbeat running at {} Hz\n", rate_hz);
  std::fflush(stdout);
  StateShape shape;
  const auto period_ns = static_cast<std::int64_t>(1e9 / rate_hz);
  timespec next{};
  clock_gettime(CLOCK_MONOTONIC, &next);
  std::uint64_t seq = 0;
  while (g_stop == 0) {
    shape.stamp(++seq);
    dds_write(*writer, &shape.state);
    std::int64_t ns = next.tv_nsec + period_ns;
    next.tv_sec += static_cast<time_t>(ns / 1'000'000'000);
    next.tv_nsec = static_cast<long>(ns % 1'000'000'000);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr) == EINTR && g_stop == 0) {
    }
  }
  dds_delete(*participant);
  return 0;
}

}  // namespace
}  // namespace hubrt::bench

int main(int argc, char** argv) {
  CLI::App app{"Raw Cyclone DDS baselines for the hubrt benchmarks"};
  app.require_subcommand(1);
  double rate_hz = 100;
  std::string topic;
  CLI::App* sink = app.add_subcommand("sink", "Take and drop every DockState on a DDS topic");
  sink->add_option("--topic", topic, "DDS topic name, e.g. rt/dock_ecu/dock/state")->required();
  CLI::App* pong = app.add_subcommand("pong", "Answer each DockCommand on rt/bench/ping with a DockState");
  CLI::App* heartbeat =
      app.add_subcommand("heartbeat", "Write a DockState at a fixed rate (clock_nanosleep)");
  heartbeat->add_option("--rate", rate_hz, "Hz")->check(CLI::Range(0.1, 10000.0));
  CLI11_PARSE(app, argc, argv);
  std::signal(SIGTERM, hubrt::bench::on_signal);
  std::signal(SIGINT, hubrt::bench::on_signal);
  if (pong->parsed()) return hubrt::bench::run_pong();
  if (sink->parsed()) return hubrt::bench::run_sink(topic);
  return hubrt::bench::run_heartbeat(rate_hz);
}
