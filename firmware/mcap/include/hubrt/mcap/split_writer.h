// A recording in several files: a new one is begun before the current one would grow beyond a
// size, or once it spans a duration (`hubctl record --max-size / --max-duration`). Every file is a
// complete MCAP file on its own, with the schemas and channels its messages use under the same
// ids in every file.
//
// Names: "run.mcap" without a limit; with one, "run_0.mcap", "run_1.mcap", ... (what rosbag2's
// splits look like), so that a directory listing sorts them in order.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/mcap/writer.h"

namespace hubrt::mcap {

struct SplitOptions {
  // 0: no limit. A file is closed before its bytes, with the open chunk counted uncompressed, would
  // pass this; its summary then adds a few kilobytes. At least 64 KiB.
  std::uint64_t max_bytes = 0;
  // 0: no limit. Measured in message log times from the file's first message.
  std::chrono::nanoseconds max_duration{0};
};

// The file names: `path` itself, or `path` with "_<index>" before its extension when split.
std::string split_file_name(const std::string& path, std::size_t index);

// Not thread-safe; move-only.
class SplitWriter {
 public:
  // Creates the first file. Errors: as Writer::create; kInvalidArgument for max_bytes under 64 KiB.
  static Expected<SplitWriter> create(std::string path, WriterOptions options, SplitOptions split);

  // As Writer's; the ids hold in every file.
  Expected<std::uint16_t> add_schema(const Schema& schema);
  Expected<std::uint16_t> add_channel(const Channel& channel);
  // Begins the next file first when this message would take the current one beyond a limit.
  // Errors: as Writer::write and Writer::create.
  Expected<void> write(const Message& message);
  Expected<void> close_chunk() { return writer_->close_chunk(); }
  // Finishes the current file.
  Expected<void> finish() { return writer_->finish(); }

  // Every file begun so far, the current one last.
  [[nodiscard]] const std::vector<std::string>& files() const noexcept { return files_; }
  // Bytes in all files so far (the current one's open chunk not counted).
  [[nodiscard]] std::uint64_t bytes() const noexcept { return closed_bytes_ + writer_->file_bytes(); }
  [[nodiscard]] std::uint64_t messages() const noexcept {
    return closed_messages_ + writer_->statistics().message_count;
  }
  [[nodiscard]] const Writer& current() const noexcept { return *writer_; }

 private:
  SplitWriter(std::string path, WriterOptions options, SplitOptions split, Writer first);
  bool splitting() const noexcept { return split_.max_bytes != 0 || split_.max_duration.count() != 0; }
  Expected<void> next_file();

  std::string path_;
  WriterOptions options_;
  SplitOptions split_;
  std::optional<Writer> writer_;
  std::vector<std::string> files_;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::uint64_t closed_bytes_ = 0;
  std::uint64_t closed_messages_ = 0;
  std::optional<std::uint64_t> file_first_log_time_;
};

}  // namespace hubrt::mcap
