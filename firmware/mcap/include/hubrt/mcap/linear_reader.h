// Reading an MCAP file from its start, record after record, as far as it is whole: what
// `hubctl play`, `hubctl echo --from` and `hubctl record --recover` use, because a recording cut
// off by a crash, a full disk or SIGKILL has no summary to seek with. A chunk counts only when
// all of it is there, it decompresses to its stated size and its CRC matches; its messages are
// handed out only then, so a damaged chunk hides nothing but itself and what follows.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/mcap/records.h"
#include "hubrt/mcap/source.h"

namespace hubrt::mcap {

enum class StopReason : std::uint8_t {
  kReading,    // not stopped yet
  kDataEnd,    // the DataEnd record (or, in a file without one, the Footer): a complete file
  kTruncated,  // the file ends inside a record, or after a whole one with no DataEnd
  kCorrupt,    // a record that is whole but wrong (bad CRC, does not decompress or parse)
};

struct ReadStop {
  StopReason reason = StopReason::kReading;
  std::uint64_t offset = 0;  // where the record that was not read starts
  std::string message;       // why, for people: "chunk at byte 1234: CRC mismatch ..."
};

// Not thread-safe. Move-only.
class LinearReader {
 public:
  // Reads the magic and the Header. Errors: kProtocol "<name> is not an MCAP file" (no magic) or
  // an unreadable Header; kIo from the source.
  static Expected<LinearReader> open(std::unique_ptr<ByteSource> source, ReaderOptions options = {});

  // The next message in file order, or nullopt when reading stopped (see stop()). `data` points
  // into the reader and stays valid until the next call. Its channel is in channels().
  std::optional<Message> next();

  [[nodiscard]] const ReadStop& stop() const noexcept { return stop_; }
  [[nodiscard]] const Header& header() const noexcept { return header_; }
  // Schemas and channels seen so far (in whole records and whole chunks only).
  [[nodiscard]] const std::map<std::uint16_t, Schema>& schemas() const noexcept { return schemas_; }
  [[nodiscard]] const std::map<std::uint16_t, Channel>& channels() const noexcept { return channels_; }
  // Chunks read whole so far, and the offset just after the last whole record.
  [[nodiscard]] std::uint64_t whole_chunks() const noexcept { return whole_chunks_; }
  [[nodiscard]] std::uint64_t whole_bytes() const noexcept { return offset_; }
  [[nodiscard]] const ByteSource& source() const noexcept { return *source_; }

 private:
  LinearReader(std::unique_ptr<ByteSource> source, ReaderOptions options)
      : source_(std::move(source)), options_(options) {}
  // Reads the record at offset_ and acts on it; false when reading stopped.
  bool read_record();
  bool read_chunk(Bytes content);
  void stop_at(StopReason reason, std::string message);
  // Adds a schema or channel (from a whole record, or staged from a chunk); false when it
  // contradicts one of the same id or refers to an unknown schema (then stop_ says why).
  bool keep_schema(const Schema& schema, std::map<std::uint16_t, Schema>& into);
  bool keep_channel(const Channel& channel, std::map<std::uint16_t, Channel>& into,
                    const std::map<std::uint16_t, Schema>& staged_schemas);

  std::unique_ptr<ByteSource> source_;
  ReaderOptions options_;
  Header header_;
  std::uint64_t offset_ = 0;
  std::uint32_t data_crc_ = 0;  // of every byte before the current record
  ReadStop stop_;
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, Channel> channels_;
  std::uint64_t whole_chunks_ = 0;
  std::vector<std::uint8_t> record_;   // the current record's content
  std::vector<std::uint8_t> records_;  // the current chunk's records, decompressed
  std::vector<Message> pending_;       // the current chunk's messages, pointing into records_
  std::size_t next_pending_ = 0;
};

}  // namespace hubrt::mcap
