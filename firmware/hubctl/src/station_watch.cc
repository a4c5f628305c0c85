#include "station_watch.h"

#include "hubrt/runtime/lifecycle.h"

#include "conformance_target.h"  // is_state_type: the same test as hubctl conformance

namespace hubrt::hubctl {

std::string lifecycle(const nlohmann::ordered_json& state) {
  if (!state.contains("header") || !state["header"].contains("lifecycle")) return "-";
  const auto& value = state["header"]["lifecycle"];
  if (!value.is_number_unsigned() || value.get<std::uint64_t>() > 255) return "unknown";
  return std::string(runtime::lifecycle_name(static_cast<std::uint8_t>(value.get<std::uint64_t>())));
}

bool StationWatch::on_event(const TapEvent& event, TapDecoder& decoder,
                            std::chrono::steady_clock::time_point now) {
  const TapTopic& topic = *event.topic;
  if (topic.type == nullptr || !is_state_type(*topic.type)) return false;
  if (event.kind == TapEvent::Kind::kTopic) {
    if (watched_.count(topic.ros_name) != 0) return false;
    WatchedState w;
    w.topic = topic.ros_name;
    w.type = topic.type;
    watched_.emplace(topic.ros_name, std::move(w));
    return true;
  }
  if (event.kind != TapEvent::Kind::kSample) return false;
  // A sample that cannot be shown is reported by the decoder and skipped; the others keep coming.
  auto value = decoder.decode(*event.sample);
  if (!value) return false;
  WatchedState& w = watched_[topic.ros_name];
  w.topic = topic.ros_name;
  w.type = topic.type;
  w.last = std::move(*value);
  w.last_seen = now;
  ++w.received;
  return true;
}

bool StationWatch::drain(TapSource& source, TapDecoder& decoder) {
  bool changed = false;
  while (auto event = source.next(Duration::zero())) {
    changed = on_event(*event, decoder, std::chrono::steady_clock::now()) || changed;
  }
  return changed;
}

}  // namespace hubrt::hubctl
