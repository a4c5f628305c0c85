// `hubctl play FILE.mcap`: a recording's messages written onto the domain again at the recorded pace
// (or `rate` times it) — by default its commands, so that a planner's session recorded at the
// station re-runs against the simulated one; any topics chosen otherwise. Each message goes out as
// the bytes that were recorded (UntypedWriter::write_serialized); commands with hubctl's command
// QoS (command_qos.h), other topics with the QoS their recorded writers offered.
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "hubrt/base/time.h"
#include "hubrt/dds/participant.h"

#include "command_qos.h"
#include "tap_selection.h"

namespace hubrt::hubctl {

struct RecordingPlayOptions {
  std::vector<std::string> files;  // the recording, or the parts of a split one in order
  double rate = 1.0;
  double start_s = 0;  // from the recording's first message
  std::optional<double> end_s;
  TapChoice choice;  // nothing chosen: the commands
  Duration discovery_timeout = std::chrono::seconds(5);
  bool quiet = false;
  std::uint32_t command_lifespan_ms = kDefaultCommandLifespanMs;  // the commands' LIFESPAN (0: none)
};

// True when `path` holds an MCAP file (its magic), whatever its name. Never throws.
bool is_mcap_file(const std::string& path) noexcept;

// Plays the recording; reports topics as they start and a summary on `out`, problems on stderr.
// Returns the exit status: 0 played, 1 nothing to play or a write failed, 2 the file or options are
// wrong, 130/143 interrupted.
int play_recording(const dds::Participant& participant, const RecordingPlayOptions& options, std::FILE* out);

}  // namespace hubrt::hubctl
