// The bridges' health on /diagnostics (diagnostic_msgs/DiagnosticArray, as hubd publishes its
// own: firmware/assembly/diagnostics_stage.h): one status per bridge, named
// "hubbridge <name>: <dds topic>", with the counts and the age of the last sample. The message
// says the worst first: ERROR after type errors; WARN "dropped N over a bound" while the ROS 1
// side sends messages the bridge drops (within `silent_after_s`: ahead of silence, which is what
// it looks like on DDS); WARN "silent" when a ros1_to_dds bridge's ROS 1 side has sent nothing
// for `silent_after_s`; WARN when a publisher it hears is not registered with the ROS master.
#pragma once

#include <span>

#include <nlohmann/json.hpp>

#include "hubrt/dds/participant.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"

#include "bridge_runner.h"

namespace hubrt::hubbridge {

// The DiagnosticArray (as msgs::to_json writes it) for the bridges at monotonic time `now_ns`
// and wall time `wall_ns`; `sync[i]` is bridge i's state at the master (MasterSync::status(),
// empty or as long as `bridges`). Thread-safe with respect to the forwarding threads (reads
// counters).
nlohmann::ordered_json bridge_diagnostics(const BridgeFile& file,
                                          std::vector<std::unique_ptr<Bridge>>& bridges,
                                          std::span<const EndpointSync> sync, std::uint64_t registrations,
                                          std::int64_t now_ns, std::int64_t wall_ns);

class DiagnosticsPublisher {
 public:
  // Errors: the DDS topic or writer of /diagnostics could not be created.
  static Expected<DiagnosticsPublisher> create(dds::Participant& participant);
  // Writes one DiagnosticArray. Errors: an array the type refuses (a bug) or the write's.
  Expected<void> publish(const nlohmann::ordered_json& array);

 private:
  DiagnosticsPublisher(dds::UntypedTopic topic, dds::UntypedWriter writer)
      : topic_(std::move(topic)), writer_(std::move(writer)) {}
  dds::UntypedTopic topic_;
  dds::UntypedWriter writer_;
};

}  // namespace hubrt::hubbridge
