// Every hub State the tap (tap.h) hands out, judged fresh or silent: what `hubctl watch` draws as a
// table and `hubctl serve` shows on the operator screen, live or from a recording.
#pragma once

#include <chrono>
#include <cstddef>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "hubrt/msgs/type_info.h"

#include "tap.h"
#include "tap_decoder.h"

namespace hubrt::hubctl {

// The State header's lifecycle by name ("operational"), "-" when the State has none.
std::string lifecycle(const nlohmann::ordered_json& state);

// A node whose last State is older than this is "silent" (its heartbeat is 1 to 50 Hz).
inline constexpr std::chrono::milliseconds kSilentAfter{2000};

struct WatchedState {
  std::string topic;  // ROS name, e.g. "/dock/state"
  const msgs::TypeInfo* type = nullptr;
  nlohmann::ordered_json last;  // the last State as JSON (valid UTF-8: SampleDecoder)
  std::chrono::steady_clock::time_point last_seen{};
  std::size_t received = 0;

  [[nodiscard]] bool silent(std::chrono::steady_clock::time_point now) const {
    return received == 0 || now - last_seen > kSilentAfter;
  }
};

// Not thread-safe: one thread feeds it.
class StationWatch {
 public:
  // Takes one event of a tap: a State topic appearing adds a row, a State sample (decoded through
  // `decoder`; one that cannot be shown is reported there and skipped) updates it, seen at `now`.
  // Other topics are ignored. Returns true when the table changed.
  bool on_event(const TapEvent& event, TapDecoder& decoder, std::chrono::steady_clock::time_point now);

  // Every event `source` has now (without waiting), through on_event. Returns true when the table
  // changed.
  bool drain(TapSource& source, TapDecoder& decoder);

  [[nodiscard]] const std::map<std::string, WatchedState>& states() const noexcept { return watched_; }

 private:
  std::map<std::string, WatchedState> watched_;
};

}  // namespace hubrt::hubctl
