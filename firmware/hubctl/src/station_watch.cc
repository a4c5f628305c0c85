#include "station_watch.h"

#include "hubrt/dds/discovery.h"
#include "hubrt/dds/ros_names.h"
#include "hubrt/msgs/all_types.h"
#include "hubrt/runtime/lifecycle.h"

#include "conformance_target.h"  // is_state_type: the same test as hubctl conformance

namespace hubrt::hubctl {

std::string lifecycle(const nlohmann::ordered_json& state) {
  if (!state.contains("header") || !state["header"].contains("lifecycle")) return "-";
  const auto& value = state["header"]["lifecycle"];
  if (!value.is_number_unsigned() || value.get<std::uint64_t>() > 255) return "unknown";
  return std::string(runtime::lifecycle_name(static_cast<std::uint8_t>(value.get<std::uint64_t>())));
}

void StationWatch::discover(const dds::Participant& participant, bool& changed) {
  auto snapshot = dds::discover(participant);
  if (!snapshot) return;
  for (const auto& topic : snapshot->topics()) {
    // Our own readers are no hub; a topic only we use has nobody else's writer.
    if (topic.writers <= topic.local_writers) continue;
    const msgs::TypeInfo* type = msgs::all_types().find_by_dds_name(topic.type_name);
    const auto ros = dds::dds_to_ros_topic(topic.topic_name);
    if (type == nullptr || !ros || !is_state_type(*type) || watched_.count(*ros) != 0) continue;
    WatchedState w;
    w.topic = *ros;
    w.type = type;
    auto t = dds::UntypedTopic::create(participant, *type->descriptor, *ros);
    if (!t) continue;
    w.dds_topic.emplace(std::move(*t));
    auto r = dds::UntypedReader::create(participant, *w.dds_topic);
    if (!r) continue;
    w.reader.emplace(std::move(*r));
    w.sample.emplace(*type->descriptor);
    w.decoder.emplace(tool_, *ros);
    watched_.emplace(*ros, std::move(w));
    changed = true;
  }
}

bool StationWatch::poll(const dds::Participant& participant, std::chrono::steady_clock::time_point now) {
  bool changed = false;
  if (now >= next_discovery_) {
    next_discovery_ = now + std::chrono::milliseconds(500);
    discover(participant, changed);
  }
  for (auto& [topic, w] : watched_) {
    while (true) {
      const Result<bool> taken = w.reader->take_next(w.sample->data());
      if (!taken.is_ok() || !taken.value()) break;
      // A sample that cannot be shown is reported and skipped; the others keep coming.
      auto value = w.decoder->decode(*w.type, w.sample->data());
      if (!value) continue;
      w.last = std::move(*value);
      w.last_seen = std::chrono::steady_clock::now();
      ++w.received;
      changed = true;
    }
  }
  return changed;
}

}  // namespace hubrt::hubctl
