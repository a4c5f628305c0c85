#include "reader_wait.h"

#include <algorithm>
#include <thread>

#include <fmt/format.h>

#include "session.h"

namespace hubrt::hubctl {

namespace {

Expected<ReadersMatched> await_matches(const dds::UntypedWriter& writer, const ReaderWait& wait,
                                       const std::string& ros_topic) {
  using Clock = std::chrono::steady_clock;
  constexpr auto kPoll = std::chrono::milliseconds(5);
  const auto start = Clock::now();
  const auto deadline = start + wait.timeout;
  std::uint32_t seen = 0;
  auto last_change = start;
  for (;;) {
    const Result<std::uint32_t> matched = writer.matched_readers();
    if (!matched.is_ok()) {
      return make_error(matched.status().code(), fmt::format("cannot count the readers of {}: {}", ros_topic,
                                                             to_string(matched.status().code())));
    }
    const auto now = Clock::now();
    if (matched.value() != seen) {
      seen = matched.value();
      last_change = now;
    }
    if (wait.wanted > 0) {
      if (seen >= wait.wanted) return ReadersMatched{seen, false};
    } else if (seen > 0 && (!wait.settle || now - last_change >= wait.quiet)) {
      return ReadersMatched{seen, false};
    }
    if (stop_requested()) return ReadersMatched{seen, true};
    if (now >= deadline) {
      if (wait.wanted > 0) {
        return make_error(ErrorCode::kTimeout,
                          fmt::format("only {} of {} reader(s) of {} matched within {:.1f} s", seen,
                                      wait.wanted, ros_topic, to_seconds(wait.timeout)));
      }
      if (seen > 0) return ReadersMatched{seen, false};
      return make_error(ErrorCode::kTimeout, fmt::format("nobody reads {} (waited {:.1f} s)", ros_topic,
                                                         to_seconds(wait.timeout)));
    }
    std::this_thread::sleep_for(kPoll);
  }
}

}  // namespace

Expected<ReadersMatched> greet_readers(const dds::UntypedWriter& writer, Duration timeout,
                                       const std::string& ros_topic, const std::function<void()>& between) {
  using Clock = std::chrono::steady_clock;
  constexpr auto kSlice = std::chrono::milliseconds(50);
  if (const Status announced = writer.announce(); !announced.is_ok()) {
    return make_error(announced.code(), fmt::format("cannot announce the writer of {} to its readers: {}",
                                                    ros_topic, to_string(announced.code())));
  }
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    const auto left = deadline - Clock::now();
    auto acked = writer.wait_for_acks(std::min<Duration>(kSlice, std::max<Duration>(left, Duration::zero())));
    const Result<std::uint32_t> matched = writer.matched_readers();
    const std::uint32_t count = matched.is_ok() ? matched.value() : 0;
    if (acked) return ReadersMatched{count, false};
    if (acked.error().code != ErrorCode::kTimeout) return std::move(acked).error();
    if (stop_requested()) return ReadersMatched{count, true};
    if (between) between();
    if (Clock::now() >= deadline) {
      return make_error(
          ErrorCode::kTimeout,
          fmt::format("{} reader(s) of {} matched, but not every one heard this writer within {:.1f} s",
                      count, ros_topic, to_seconds(timeout)));
    }
  }
}

Expected<ReadersMatched> wait_for_readers(const dds::UntypedWriter& writer, const ReaderWait& wait,
                                          const std::string& ros_topic) {
  auto matched = await_matches(writer, wait, ros_topic);
  if (!matched || matched->interrupted || !wait.greet) return matched;
  return greet_readers(writer, wait.timeout, ros_topic);
}

std::optional<std::string> late_acknowledgement(Duration ack_delay, std::uint32_t lifespan_ms) {
  if (lifespan_ms == 0 || ack_delay < std::chrono::milliseconds(lifespan_ms)) return std::nullopt;
  return fmt::format(
      "warning: the last sample was acknowledged {:.2f} s after it was written, past its {} ms LIFESPAN: the "
      "reader that was late may have got a gap in its place (--lifespan-ms 0 for a sample that must reach "
      "every reader)",
      to_seconds(ack_delay), lifespan_ms);
}

}  // namespace hubrt::hubctl
