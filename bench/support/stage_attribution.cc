#include "stage_attribution.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace hubrt::bench {

Expected<std::vector<TracedStep>> read_stage_trace(const std::string& path) {
  std::ifstream in(path);
  if (!in) return make_error(ErrorCode::kIo, fmt::format("{}: cannot read the stage trace", path));
  std::vector<TracedStep> steps;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    // The comment line, and the header "listener_ns,woke_ns,stepped_ns,written_ns".
    if (line.empty() || line[0] == '#' || line[0] == 'l') continue;
    TracedStep s;
    char c1 = 0;
    char c2 = 0;
    char c3 = 0;
    std::istringstream fields(line);
    fields >> s.listener >> c1 >> s.woke >> c2 >> s.stepped >> c3 >> s.written;
    if (fields.fail() || c1 != ',' || c2 != ',' || c3 != ',' || !(fields >> std::ws).eof()) {
      return make_error(ErrorCode::kIo, fmt::format("{}:{}: not four numbers: '{}'", path, number, line));
    }
    if (s.listener != 0 && s.woke != 0 && s.stepped != 0 && s.written != 0) steps.push_back(s);
  }
  std::sort(steps.begin(), steps.end(),
            [](const TracedStep& a, const TracedStep& b) { return a.listener < b.listener; });
  return steps;
}

Attribution attribute(const TimedRoundTrip& rtt, const std::vector<TracedStep>& steps) {
  Attribution a;
  auto it = std::lower_bound(steps.begin(), steps.end(), rtt.sent,
                             [](const TracedStep& s, std::int64_t t) { return s.listener < t; });
  for (; it != steps.end() && it->listener <= rtt.echo; ++it) {
    if (it->written > rtt.echo) continue;
    a.traced = true;
    a.to_listener = it->listener - rtt.sent;
    a.wake = it->woke - it->listener;
    a.step = it->stepped - it->woke;
    a.write = it->written - it->stepped;
    a.from_written = rtt.echo - it->written;
    return a;
  }
  return a;
}

namespace {

std::int64_t median_ns(std::vector<std::int64_t> values) {
  if (values.empty()) return 0;
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

}  // namespace

Attribution typical_of(const std::vector<Attribution>& round_trips) {
  std::vector<std::int64_t> parts[5];
  for (const Attribution& a : round_trips) {
    if (!a.traced) continue;
    parts[0].push_back(a.to_listener);
    parts[1].push_back(a.wake);
    parts[2].push_back(a.step);
    parts[3].push_back(a.write);
    parts[4].push_back(a.from_written);
  }
  Attribution t;
  t.traced = !parts[0].empty();
  t.to_listener = median_ns(std::move(parts[0]));
  t.wake = median_ns(std::move(parts[1]));
  t.step = median_ns(std::move(parts[2]));
  t.write = median_ns(std::move(parts[3]));
  t.from_written = median_ns(std::move(parts[4]));
  return t;
}

LateStage late_stage(const Attribution& slow, const Attribution& typical) {
  const std::int64_t excess[5] = {slow.to_listener - typical.to_listener, slow.wake - typical.wake,
                                  slow.step - typical.step, slow.write - typical.write,
                                  slow.from_written - typical.from_written};
  return static_cast<LateStage>(std::max_element(std::begin(excess), std::end(excess)) - std::begin(excess));
}

}  // namespace hubrt::bench
