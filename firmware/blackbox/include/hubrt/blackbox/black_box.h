// A hub's black box: the last N seconds of what it received and published — each command as the
// bytes that arrived (arrival time and the DDS source time), each State and /diagnostics as the
// bytes it sent — kept in memory allocated at start (Ring), and written as an MCAP file of the ros2
// profile (what `hubctl record` writes; Foxglove and the ecosystem tier read it) when asked: a fault
// latched, the process exits, someone asks (`hubctl blackbox`). The States carry each lifecycle
// transition (header.lifecycle) and each device error (error_list) as they happen.
//
// Files go to one directory, named <hub>_<date>_<time>_<reason>.mcap, written to a .part file and
// renamed once complete; the oldest of the hub's files are removed while they take more than the
// directory's cap. A crash writes through crash_dump(), which does only async-signal-safe work.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/blackbox/ring.h"
#include "hubrt/dds/sample_hook.h"
#include "hubrt/mcap/compression.h"

namespace hubrt::blackbox {

struct BlackBoxOptions {
  std::string hub_name;                                     // "dock_ecu": the files' prefix
  Duration span = std::chrono::seconds(60);                 // how far back a file reaches
  std::size_t memory_bytes = std::size_t{8} << 20;          // the ring
  std::string directory;                                    // created when missing
  std::uint64_t directory_bytes = std::uint64_t{64} << 20;  // this hub's files there, at most
  mcap::Compression compression = mcap::Compression::kZstd;
};

// One recorded topic: what the file's Schema and Channel say of it.
struct StreamSpec {
  std::string topic;             // ROS name, "/dock/command"
  std::string type_name;         // "hub_msgs/msg/DockCommand"
  std::string schema;            // its ros2msg text
  std::string offered_qos_yaml;  // rosbag2's offered_qos_profiles of the hub's own writer ("[]\n": none)
  bool received = false;         // commands: arrival and source time; published: the time it left
};

struct DumpResult {
  std::string path;
  std::uint64_t bytes = 0;
  std::uint64_t messages = 0;
  double seconds = 0;  // from the first to the last message in the file
};

class BlackBox {
 public:
  // Allocates the ring and makes the directory. Errors: kInvalidArgument for an empty hub name or
  // directory; kIo when the directory cannot be made (errno's text).
  static Expected<std::unique_ptr<BlackBox>> create(BlackBoxOptions options);
  ~BlackBox();
  BlackBox(const BlackBox&) = delete;
  BlackBox& operator=(const BlackBox&) = delete;

  // Adds a stream; the returned hook records into it (set it on the topic's reader or writer: its
  // on_sample copies the bytes into the ring, allocation-free). Before seal() only; not
  // thread-safe. At most 65535 streams.
  dds::SampleHook& add_stream(StreamSpec spec);
  // No more streams: prepares what crash_dump() writes first (magic, header, schemas, channels).
  void seal();

  // Writes the last `span` now, on the caller's thread (not the cycle's: it allocates, compresses
  // and writes a file), then trims the directory to its cap. `reason`: letters, digits, '-'
  // ("fault", "request", "exit-SIGTERM"). Thread-safe (one dump at a time).
  // Errors: kIo naming the file (the .part file is removed).
  Expected<DumpResult> dump(std::string_view reason);

  // From a crash handler (SIGSEGV, std::terminate, ...) after the outputs are safe: writes what the
  // ring holds, without its lock, as an MCAP file of Message records outside chunks (no index, no
  // compression: a streamed reader or `hubctl record --recover` reads it), named
  // <hub>_<unix seconds>_crash.mcap. Uses open/write/close/clock_gettime only. After seal().
  void crash_dump() noexcept;

  [[nodiscard]] const Ring& ring() const noexcept { return ring_; }
  [[nodiscard]] const BlackBoxOptions& options() const noexcept { return options_; }
  [[nodiscard]] std::uint64_t dumps() const noexcept { return dumps_.load(std::memory_order_relaxed); }

 private:
  class StreamHook;
  explicit BlackBox(BlackBoxOptions options);
  void trim_directory(const std::string& keep) const;

  BlackBoxOptions options_;
  Ring ring_;
  std::vector<StreamSpec> streams_;
  std::vector<std::unique_ptr<StreamHook>> hooks_;
  std::vector<std::uint8_t> crash_prologue_;  // built by seal()
  std::string crash_prefix_;                  // <directory>/<hub>_
  std::mutex dump_mutex_;
  std::atomic<std::uint64_t> dumps_{0};
  bool sealed_ = false;
};

}  // namespace hubrt::blackbox
