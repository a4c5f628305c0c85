// Writing an MCAP file that readers can seek in and that survives its writer being killed.
//
// Layout (MCAP spec, website/docs/spec/index.md, "File Structure" and the diagram "Multiple
// Messages with Chunk Indices"): magic, Header, then Chunks, each followed by one MessageIndex
// record per channel with messages in it; DataEnd (with the CRC of everything before it); the
// summary section — Schema and Channel copies, Statistics, a ChunkIndex per chunk, grouped by
// opcode — and one SummaryOffset per group; Footer (with the CRC of the summary); magic.
//
// A Schema and its Channel records are written into the chunk that holds the channel's first
// message (as the reference writer does), so that every whole chunk of a cut-off file has what
// its messages need before them. Chunks go to the file as they close — when their uncompressed
// records reach `chunk_bytes`, or when the caller closes one (close_chunk(), e.g. once a second)
// — so a writer killed with SIGKILL leaves every closed chunk readable: at most the open chunk is
// lost. finish() writes the summary; `hubrt::mcap::recover` rebuilds it for a file that has none.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/mcap/compression.h"
#include "hubrt/mcap/records.h"

namespace hubrt::mcap {

struct WriterOptions {
  std::string profile = "ros2";
  std::string library = "hubrt";
  Compression compression = Compression::kZstd;
  // A chunk is closed once its uncompressed records reach this (and before a message that would
  // take it beyond, unless it is the chunk's first). MCAP's reference writer uses 768 KiB.
  std::size_t chunk_bytes = 768 * 1024;
};

// Move-only. Not thread-safe: one thread writes. Allocates (not for a control cycle).
class Writer {
 public:
  // Creates `path` (which must not exist: a recording is never overwritten) and writes the magic
  // and the Header. Errors: kFailedPrecondition when the file exists; kIo with errno's text.
  static Expected<Writer> create(const std::string& path, WriterOptions options = {});

  // Finishes the file if finish() was not called (errors then go unreported).
  ~Writer();
  Writer(Writer&& other) noexcept;
  Writer& operator=(Writer&& other) = delete;
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Registers a schema (its `id` is ignored) and returns the id it gets (1, 2, ...); the same
  // name, encoding and data again return the same id. Errors: kOutOfRange beyond 65535 schemas;
  // kInvalidArgument for a name or encoding that is not valid UTF-8.
  Expected<std::uint16_t> add_schema(const Schema& schema);
  // Registers a channel (its `id` is ignored) and returns its id (0, 1, ...). Errors:
  // kInvalidArgument for an unknown schema id or text that is not valid UTF-8; kOutOfRange
  // beyond 65535 channels.
  Expected<std::uint16_t> add_channel(const Channel& channel);

  // Appends a message to the open chunk (writing the chunk when full). Errors: kInvalidArgument
  // for an unknown channel id; kIo when writing failed (then every later call fails too).
  Expected<void> write(const Message& message);

  // Writes the open chunk, if it has records, and its MessageIndex records. Errors: kIo.
  Expected<void> close_chunk();

  // Closes the open chunk and writes DataEnd, the summary, the Footer and the magic, then syncs
  // and closes the file. Nothing may be written afterwards. Errors: kIo; kFailedPrecondition
  // when called twice.
  Expected<void> finish();

  // Bytes in the file so far: what a reader finds if the process dies now.
  [[nodiscard]] std::uint64_t file_bytes() const noexcept { return file_offset_; }
  // Uncompressed bytes of the open chunk (not in the file yet).
  [[nodiscard]] std::size_t open_chunk_bytes() const noexcept { return chunk_.size(); }
  [[nodiscard]] const Statistics& statistics() const noexcept { return statistics_; }
  [[nodiscard]] const std::string& path() const noexcept { return path_; }

 private:
  Writer(int fd, std::string path, WriterOptions options);
  Expected<void> write_bytes(Bytes bytes, bool in_data_crc);
  Expected<void> failed() const;
  void write_schema_and_channel(std::uint16_t channel_id);

  int fd_ = -1;
  std::string path_;
  WriterOptions options_;
  Compressor compressor_;
  std::uint64_t file_offset_ = 0;
  std::uint32_t data_crc_ = 0;
  bool finished_ = false;
  std::optional<Error> error_;  // the first write error: the file cannot be finished after it

  std::vector<Schema> schemas_;  // id = index + 1
  std::vector<bool> schema_written_;
  std::vector<Channel> channels_;  // id = index
  std::vector<bool> channel_written_;

  std::vector<std::uint8_t> chunk_;  // the open chunk's uncompressed records
  std::vector<std::uint8_t> compressed_;
  std::map<std::uint16_t, std::vector<MessageIndexEntry>> chunk_index_entries_;
  std::uint64_t chunk_start_time_ = 0;
  std::uint64_t chunk_end_time_ = 0;
  bool chunk_has_messages_ = false;

  std::vector<ChunkIndex> chunk_indexes_;
  Statistics statistics_;
};

}  // namespace hubrt::mcap
