// What `hubctl record` does with the tap's events (tap.h): each sample becomes an MCAP message of
// the ros2 profile (MCAP spec registry.md, "ROS2"; rosbag2_storage_mcap's writer) — one Schema per
// type (ros2msg: the .msg text with its dependencies), one Channel per topic (message encoding
// cdr, the writers' offered QoS as offered_qos_profiles), the bytes as they were on the wire,
// log_time = when the tap took it, publish_time = the DDS source timestamp — in files split by size
// or duration, with a chunk closed at least every `chunk_period` so that a killed recorder loses at
// most that much.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/mcap/split_writer.h"

#include "tap.h"

namespace hubrt::hubctl {

struct RecorderOptions {
  std::string path;  // "run.mcap"; split parts "run_0.mcap", ...
  mcap::WriterOptions writer;
  mcap::SplitOptions split;
  std::chrono::nanoseconds chunk_period = std::chrono::seconds(1);
};

struct RecorderProgress {
  std::uint64_t messages = 0;
  std::uint64_t bytes = 0;  // in the files, the open chunk not counted
  std::size_t topics = 0;   // with at least one message recorded
  std::vector<std::string> files;
};

// Not thread-safe: the consumer's thread. Move-only.
class Recorder {
 public:
  // Creates the first file. Errors: as mcap::SplitWriter::create (the file exists, cannot be made).
  static Expected<Recorder> create(RecorderOptions options);

  // Writes a sample (registering its type's schema and its topic's channel with the first one);
  // ignores the other events. A topic whose type has no .msg definition cannot be recorded: it is
  // skipped and listed in unrecordable() (topic -> type). `now` is the steady clock, for the chunk period.
  // Errors: writing failed (kIo: a full disk...); the files so far stay readable.
  Expected<void> take(const TapEvent& event, std::chrono::steady_clock::time_point now);
  // Closes the open chunk if it is older than the chunk period; call this when idle as well.
  Expected<void> tick(std::chrono::steady_clock::time_point now);
  // Writes what is left and the summary of the current file.
  Expected<void> finish();

  [[nodiscard]] RecorderProgress progress() const;
  [[nodiscard]] const std::map<std::string, std::string>& unrecordable() const noexcept {
    return unrecordable_;
  }

 private:
  Recorder(RecorderOptions options, mcap::SplitWriter writer)
      : options_(std::move(options)), writer_(std::move(writer)) {}
  Expected<std::uint16_t> channel_of(const TapTopic& topic);

  RecorderOptions options_;
  mcap::SplitWriter writer_;
  std::map<std::string, std::uint16_t> schemas_;   // by type name
  std::map<std::string, std::uint16_t> channels_;  // by topic
  std::map<std::string, std::string> unrecordable_;
  std::chrono::steady_clock::time_point chunk_opened_{};
  bool chunk_open_ = false;
};

}  // namespace hubrt::hubctl
