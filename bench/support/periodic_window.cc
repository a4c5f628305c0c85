#include "periodic_window.h"

#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>

#include <fmt/format.h>

#include "dock.h"
#include "raw_dds.h"

namespace hubrt::bench {
namespace {

// Takes every State of `reader`; appends `now` per valid one when `arrivals` is given.
void take_into(dds_entity_t reader, double now, std::vector<double>* arrivals) {
  void* samples[16] = {};
  dds_sample_info_t infos[16];
  for (;;) {
    const dds_return_t n = dds_take(reader, samples, infos, 16, 16);
    if (n <= 0) return;
    for (dds_return_t i = 0; i < n && arrivals != nullptr; ++i) {
      if (infos[i].valid_data) arrivals->push_back(now);
    }
    dds_return_loan(reader, samples, n);
  }
}

std::vector<double> jitter_of(const std::vector<double>& arrivals, double period_s) {
  std::vector<double> out;
  for (std::size_t i = 1; i < arrivals.size(); ++i) {
    out.push_back(std::abs(arrivals[i] - arrivals[i - 1] - period_s) * 1e3);
  }
  return out;
}

}  // namespace

Expected<JitterWindow> jitter_window(dds_entity_t participant, const std::string& first,
                                     const std::string& second, double rate_hz, double settle_s,
                                     double window_s) {
  auto a = raw_reader(participant, hub_msgs_msg_dds__DockState__desc, first);
  if (!a) return std::move(a).error();
  auto b = raw_reader(participant, hub_msgs_msg_dds__DockState__desc, second);
  if (!b) return std::move(b).error();
  const dds_entity_t readers[2] = {*a, *b};
  const dds_entity_t waitset = dds_create_waitset(participant);
  for (int i = 0; i < 2; ++i) {
    dds_waitset_attach(waitset, dds_create_readcondition(readers[i], DDS_ANY_STATE),
                       static_cast<dds_attach_t>(i));
  }
  std::vector<double> arrivals[2];
  // Until `until`: wakes on each State and stamps it as it is taken (the subscriber's view).
  const auto run_until = [&](double until, bool record) {
    for (double now = mono_now(); now < until; now = mono_now()) {
      dds_attach_t fired[2];
      dds_waitset_wait(waitset, fired, 2, static_cast<dds_duration_t>(std::min(until - now, 0.1) * 1e9));
      const double at = mono_now();
      for (int i = 0; i < 2; ++i) take_into(readers[i], at, record ? &arrivals[i] : nullptr);
    }
  };
  // Both publishers seen before anything counts.
  const double give_up = mono_now() + 10.0;
  while ((arrivals[0].empty() || arrivals[1].empty()) && mono_now() < give_up)
    run_until(mono_now() + 0.05, true);
  const bool both = !arrivals[0].empty() && !arrivals[1].empty();
  if (both) {
    arrivals[0].clear();
    arrivals[1].clear();
    run_until(mono_now() + settle_s, false);
    run_until(mono_now() + window_s, true);
  }
  dds_delete(waitset);
  dds_delete(readers[0]);
  dds_delete(readers[1]);
  if (!both) {
    return make_error(ErrorCode::kTimeout,
                      fmt::format("no States within 10 s on {} ({} seen) or {} ({} seen)", first,
                                  arrivals[0].size(), second, arrivals[1].size()));
  }
  const double period = 1.0 / rate_hz;
  return JitterWindow{jitter_of(arrivals[0], period), jitter_of(arrivals[1], period)};
}

std::vector<double> bare_loop_lateness_ms(double rate_hz, double window_s) {
  const auto period_ns = static_cast<std::int64_t>(1e9 / rate_hz);
  const auto periods = static_cast<std::size_t>(window_s * rate_hz);
  std::vector<double> late;
  late.reserve(periods);
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  std::int64_t deadline = now.tv_sec * 1'000'000'000LL + now.tv_nsec;
  for (std::size_t i = 0; i < periods; ++i) {
    deadline += period_ns;
    const timespec at{static_cast<time_t>(deadline / 1'000'000'000LL),
                      static_cast<long>(deadline % 1'000'000'000LL)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &at, nullptr) == EINTR) {
    }
    clock_gettime(CLOCK_MONOTONIC, &now);
    late.push_back(static_cast<double>(now.tv_sec * 1'000'000'000LL + now.tv_nsec - deadline) * 1e-6);
  }
  return late;
}

}  // namespace hubrt::bench
