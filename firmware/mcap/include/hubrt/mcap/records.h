// The records of an MCAP file (https://mcap.dev/spec, major version 0; the specification's text
// is website/docs/spec/index.md in github.com/foxglove/mcap), as plain structs, with their
// serialisation and parsing. Every record on disk is <opcode uint8><content length uint64><content>;
// integers are little-endian; a String is a uint32 byte length and UTF-8 bytes; a Map and an Array
// are a uint32 byte length and their entries (spec, "Serialization").
//
// Parsing is for bytes from outside (a file someone hands us): every length is checked against
// what is left of the record, strings must be valid UTF-8, and a field the record does not have
// room for is an error, never a read past the end. Fields after the known ones are ignored, as the
// spec asks ("Records may be extended by adding new fields at the end").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "hubrt/base/status.h"

namespace hubrt::mcap {

using Bytes = std::span<const std::uint8_t>;

// 0x89 "MCAP" 0x30 "\r\n": the first and the last 8 bytes of every file (spec, "Magic").
inline constexpr std::array<std::uint8_t, 8> kMagic = {0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};
// Opcode (1) and content length (8) in front of every record's content.
inline constexpr std::size_t kRecordPrefixBytes = 9;

enum class Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

struct Header {
  std::string profile;  // "ros2" for the ros2 profile (spec, registry.md "Profiles")
  std::string library;
  bool operator==(const Header&) const = default;
};

// The Footer's content is fixed: 8 + 8 + 4 bytes, and the record is never extended.
inline constexpr std::size_t kFooterContentBytes = 20;
struct Footer {
  std::uint64_t summary_start = 0;         // 0: no summary section
  std::uint64_t summary_offset_start = 0;  // 0: no summary offset section
  std::uint32_t summary_crc = 0;           // 0: not available
  bool operator==(const Footer&) const = default;
};

struct Schema {
  std::uint16_t id = 0;  // never 0 in a valid file
  std::string name;      // ros2msg: "hub_msgs/msg/DockState"
  std::string encoding;  // "ros2msg"
  std::string data;      // the schema text (bytes; ros2msg text is UTF-8)
  bool operator==(const Schema&) const = default;
};

struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;  // 0: no schema
  std::string topic;
  std::string message_encoding;  // "cdr" for ROS 2
  std::map<std::string, std::string> metadata;
  bool operator==(const Channel&) const = default;
};

// A message as it is written or read; `data` points into the caller's (writing) or the reader's
// (reading) memory.
struct Message {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;      // ns since the Unix epoch (hubrt: when it was received)
  std::uint64_t publish_time = 0;  // ns since the Unix epoch (hubrt: the DDS source timestamp)
  Bytes data;
};

// A Chunk's fields; `records` points into the record's content (still compressed).
struct ChunkView {
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;  // 0: not available
  std::string compression;             // "", "zstd" or "lz4"
  Bytes records;
};

struct MessageIndexEntry {
  std::uint64_t log_time = 0;
  std::uint64_t offset = 0;  // into the chunk's uncompressed records
  bool operator==(const MessageIndexEntry&) const = default;
};
struct MessageIndex {
  std::uint16_t channel_id = 0;
  std::vector<MessageIndexEntry> records;
  bool operator==(const MessageIndex&) const = default;
};

struct ChunkIndex {
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::uint64_t chunk_start_offset = 0;
  std::uint64_t chunk_length = 0;  // the whole record, opcode and length included
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;
  std::uint64_t message_index_length = 0;
  std::string compression;
  std::uint64_t compressed_size = 0;
  std::uint64_t uncompressed_size = 0;
  bool operator==(const ChunkIndex&) const = default;
};

struct Statistics {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0;
  std::uint32_t attachment_count = 0;
  std::uint32_t metadata_count = 0;
  std::uint32_t chunk_count = 0;
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
  bool operator==(const Statistics&) const = default;
};

struct SummaryOffset {
  Opcode group_opcode = Opcode::kSchema;
  std::uint64_t group_start = 0;
  std::uint64_t group_length = 0;
  bool operator==(const SummaryOffset&) const = default;
};

struct DataEnd {
  std::uint32_t data_section_crc = 0;  // 0: not available
};

// Appends the whole record (opcode, content length, content) to `out`; returns the bytes
// appended. Allocates (grows `out`). Thread-safe (no shared state).
// Precondition: strings are valid UTF-8 and each string, map and array fits a uint32 length.
std::size_t append_record(std::vector<std::uint8_t>& out, const Header& record);
std::size_t append_record(std::vector<std::uint8_t>& out, const Footer& record);
std::size_t append_record(std::vector<std::uint8_t>& out, const Schema& record);
std::size_t append_record(std::vector<std::uint8_t>& out, const Channel& record);
std::size_t append_record(std::vector<std::uint8_t>& out, const Message& record);
std::size_t append_record(std::vector<std::uint8_t>& out, const MessageIndex& record);
std::size_t append_record(std::vector<std::uint8_t>& out, const ChunkIndex& record);
std::size_t append_record(std::vector<std::uint8_t>& out, const Statistics& record);
std::size_t append_record(std::vector<std::uint8_t>& out, const SummaryOffset& record);
std::size_t append_record(std::vector<std::uint8_t>& out, const DataEnd& record);
// A Chunk's prefix and fields up to its records' uint64 length (the records follow): the writer
// hands the compressed records to write() separately instead of copying them.
std::vector<std::uint8_t> chunk_record_head(const ChunkView& chunk);
// Bytes a Message record takes: prefix, 22 bytes of fields, the data.
std::size_t message_record_size(std::size_t data_bytes) noexcept;

// Parse a record's content (what follows its opcode and length). Errors: kProtocol naming the
// record and the field that does not fit or is not valid UTF-8, e.g. "Channel: topic: length
// 300 beyond the record's 41 bytes". Thread-safe.
Expected<Header> parse_header(Bytes content);
Expected<Footer> parse_footer(Bytes content);
Expected<Schema> parse_schema(Bytes content);
Expected<Channel> parse_channel(Bytes content);
// `data` of the result points into `content`.
Expected<Message> parse_message(Bytes content);
// `records` of the result points into `content`.
Expected<ChunkView> parse_chunk(Bytes content);
Expected<MessageIndex> parse_message_index(Bytes content);
Expected<ChunkIndex> parse_chunk_index(Bytes content);
Expected<Statistics> parse_statistics(Bytes content);
Expected<SummaryOffset> parse_summary_offset(Bytes content);
Expected<DataEnd> parse_data_end(Bytes content);

// One record of a sequence of records in memory (a chunk's records, a summary section).
struct RecordView {
  std::uint8_t opcode = 0;
  Bytes content;
  std::uint64_t offset = 0;  // of the opcode, from the start of the sequence
};

// Walks `records` one record at a time. Not thread-safe; the views point into `records`.
class RecordCursor {
 public:
  explicit RecordCursor(Bytes records) noexcept : records_(records) {}
  // The next record, false at the end. Errors: kProtocol when the rest is not a whole record
  // (a prefix cut short, a length beyond the end, opcode 0), with its offset.
  Expected<bool> next(RecordView& record);
  [[nodiscard]] std::uint64_t offset() const noexcept { return offset_; }

 private:
  Bytes records_;
  std::uint64_t offset_ = 0;
};

// CRC-32 (ISO-HDLC, zlib's and MCAP's: spec "Chunk", uncompressed_crc) of `bytes`, continuing
// from `crc` (0 to start). Thread-safe.
std::uint32_t crc32(Bytes bytes, std::uint32_t crc = 0) noexcept;

}  // namespace hubrt::mcap
