// Before `hubctl send` writes a sample it will not repeat (--once, --count), every reader that
// should get it must be matched: a volatile writer's sample never reaches a reader matched
// after it was written. With several hubs on the domain their readers match one by one, so
// "the first reader matched" is not "everyone is there".
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/dds/writer.h"

namespace hubrt::hubctl {

struct ReaderWait {
  // > 0: wait for this many matched readers (--wait N). 0: for one, then, when `settle`, until
  // no further reader has matched for `quiet`.
  std::uint32_t wanted = 0;
  bool settle = false;
  // Discovery answers within milliseconds on a LAN; a reader that has not matched half a second
  // after the last one did is not on its way. Generous for loaded machines, short for people.
  Duration quiet = std::chrono::milliseconds(500);
  Duration timeout = std::chrono::seconds(5);
  // Then announce the writer to the readers matched and wait, at most `timeout` again, until each
  // has heard it (greet_readers): for a sample written once. The writer's QoS must be
  // announceable().
  bool greet = false;
};

struct ReadersMatched {
  std::uint32_t count = 0;
  bool interrupted = false;  // SIGINT/SIGTERM arrived while waiting
};

// Polls `writer`'s matched-reader count (every 5 ms) as `wait` asks, until satisfied, stopped by
// SIGINT/SIGTERM (stop_requested) or `wait.timeout` passes. Settling that runs into the timeout
// with at least one reader matched counts as done. With `wait.greet`, greet_readers follows.
// Errors: kTimeout "only <n> of <wanted> reader(s) of <topic> matched within <t> s" (--wait), or
// "nobody reads <topic> (waited <t> s)"; Cyclone's code for a deleted writer; greet_readers'.
Expected<ReadersMatched> wait_for_readers(const dds::UntypedWriter& writer, const ReaderWait& wait,
                                          const std::string& ros_topic);

// Matching is two-sided: the writer can match a reader that starting up or a loaded machine keeps
// from matching the writer back for a while, and such a reader drops, and acknowledges, whatever
// the writer wrote before it heard the writer's first heartbeat (dds::UntypedWriter::announce).
// So before the first sample of a run that is not repeated, hubctl announces its writer and waits,
// at most `timeout`, until every reader matched has acknowledged that (polling, so that SIGINT and
// SIGTERM are heard, and `between` runs between polls: the scenarios keep their readers drained).
// The writer's QoS must not dispose on unregister (announceable, command_writer_qos).
// Errors: kTimeout "<n> reader(s) of <topic> matched, but not every one heard this writer within
// <t> s"; the announcement's refusal (kFailedPrecondition for a keyed topic or a disposing QoS).
// `qos` with unregistering that does not dispose, so that a writer of it can be announced.
inline dds::Qos announceable(dds::Qos qos) {
  qos.dispose_on_unregister(false);
  return qos;
}

Expected<ReadersMatched> greet_readers(const dds::UntypedWriter& writer, Duration timeout,
                                       const std::string& ros_topic,
                                       const std::function<void()>& between = {});

// Once heard, a reader can still lose a sample on the wire and ask for it again. Cyclone 0.10.2
// drops an unacknowledged sample from the writer's history LIFESPAN after the write
// (dds::Qos::lifespan), and a reader that asks for it later gets a gap, which it acknowledges like
// the sample. So "acknowledged" means "received" only when it came within LIFESPAN of the write;
// `ack_delay` is that time for the last sample written.
// Returns the warning to print when it did not (`lifespan_ms` 0: no LIFESPAN, never).
std::optional<std::string> late_acknowledgement(Duration ack_delay, std::uint32_t lifespan_ms);

}  // namespace hubrt::hubctl
