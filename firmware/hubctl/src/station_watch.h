// Every hub State on the domain, discovered as hubs appear and judged fresh or silent: what
// `hubctl watch` draws as a table and `hubctl serve` shows on the operator screen.
#pragma once

#include <chrono>
#include <cstddef>
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "hubrt/dds/participant.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/msgs/type_info.h"

#include "sample_decoder.h"

namespace hubrt::hubctl {

// The State header's lifecycle by name ("operational"), "-" when the State has none.
std::string lifecycle(const nlohmann::ordered_json& state);

// A node whose last State is older than this is "silent" (its heartbeat is 1 to 50 Hz).
inline constexpr std::chrono::milliseconds kSilentAfter{2000};

struct WatchedState {
  std::string topic;  // ROS name, e.g. "/dock/state"
  const msgs::TypeInfo* type = nullptr;
  std::optional<dds::UntypedTopic> dds_topic;
  std::optional<dds::UntypedReader> reader;
  std::optional<dds::UntypedSample> sample;
  std::optional<SampleDecoder> decoder;
  nlohmann::ordered_json last;  // the last State as JSON (valid UTF-8: SampleDecoder)
  std::chrono::steady_clock::time_point last_seen{};
  std::size_t received = 0;

  [[nodiscard]] bool silent(std::chrono::steady_clock::time_point now) const {
    return received == 0 || now - last_seen > kSilentAfter;
  }
};

// Not thread-safe: one thread polls it.
class StationWatch {
 public:
  // `tool` prefixes the decoder's reports ("hubctl watch").
  explicit StationWatch(std::string tool) : tool_(std::move(tool)) {}

  // Discovers new State topics (every 0.5 s at most) and takes every new sample. Returns true
  // when a State arrived or a topic was added.
  bool poll(const dds::Participant& participant, std::chrono::steady_clock::time_point now);

  [[nodiscard]] const std::map<std::string, WatchedState>& states() const noexcept { return watched_; }

 private:
  void discover(const dds::Participant& participant, bool& changed);

  std::string tool_;
  std::map<std::string, WatchedState> watched_;
  std::chrono::steady_clock::time_point next_discovery_{};
};

}  // namespace hubrt::hubctl
