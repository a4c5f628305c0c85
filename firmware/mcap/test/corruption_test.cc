// Damaged files: a changed byte is caught by the CRC that covers it, the chunks before it still
// read, and sizes a file claims cannot make the reader allocate beyond its limits.
#include <gtest/gtest.h>

#include "hubrt/mcap/linear_reader.h"
#include "hubrt/mcap/summary.h"

#include "mcap_test_files.h"

namespace hubrt::mcap {
namespace {

struct Damaged {
  std::vector<std::uint8_t> bytes;
  std::vector<test::RecordedMessage> written;
  Summary summary;
};

// A file of several uncompressed chunks (so that a changed byte still decompresses and only the
// CRC can tell).
Damaged sample(Compression compression) {
  test::ScratchDir dir;
  WriterOptions options;
  options.compression = compression;
  options.chunk_bytes = 1024;
  Damaged d;
  d.written = test::write_sample_file(dir.file("d.mcap"), options, 120);
  d.bytes = test::read_bytes(dir.file("d.mcap"));
  auto source = memory_source(d.bytes);
  auto summary = read_summary(*source);
  EXPECT_TRUE(summary) << summary.error().message;
  d.summary = *summary;
  return d;
}

std::vector<test::RecordedMessage> messages_before_chunk(const Damaged& d, std::size_t chunk) {
  // The messages are written in log-time order: those of the chunks before `chunk` are those
  // logged up to the end time of chunk - 1.
  std::size_t count = 0;
  const std::uint64_t end = chunk == 0 ? 0 : d.summary.chunk_indexes[chunk - 1].message_end_time;
  for (const auto& m : d.written) count += m.log_time <= end ? 1 : 0;
  return {d.written.begin(), d.written.begin() + static_cast<std::ptrdiff_t>(count)};
}

TEST(Corruption, AChangedByteInAChunkStopsReadingThereWithTheChunksBeforeIt) {
  for (const Compression compression : {Compression::kNone, Compression::kZstd, Compression::kLz4}) {
    Damaged d = sample(compression);
    ASSERT_GE(d.summary.chunk_indexes.size(), 4U);
    const ChunkIndex& third = d.summary.chunk_indexes[2];
    // A byte inside the chunk's records (past its fields).
    d.bytes[static_cast<std::size_t>(third.chunk_start_offset + third.chunk_length -
                                     third.compressed_size / 2)] ^= 0x5a;
    auto reader = LinearReader::open(memory_source(d.bytes));
    ASSERT_TRUE(reader);
    EXPECT_EQ(test::read_all(*reader), messages_before_chunk(d, 2)) << compression_name(compression);
    EXPECT_EQ(reader->stop().reason, StopReason::kCorrupt);
    EXPECT_EQ(reader->stop().offset, third.chunk_start_offset);
    EXPECT_EQ(reader->whole_chunks(), 2U);
    if (compression == Compression::kNone) {
      EXPECT_NE(reader->stop().message.find("CRC"), std::string::npos) << reader->stop().message;
    }
  }
}

TEST(Corruption, AChangedByteInTheSummaryFailsItsCrc) {
  Damaged d = sample(Compression::kZstd);
  d.bytes[static_cast<std::size_t>(d.summary.footer.summary_start + 20)] ^= 0x01;
  auto summary = read_summary(*memory_source(d.bytes));
  ASSERT_FALSE(summary);
  EXPECT_NE(summary.error().message.find("summary CRC"), std::string::npos) << summary.error().message;
}

TEST(Corruption, AChangedByteInAMessageIndexFailsTheDataSectionCrc) {
  Damaged d = sample(Compression::kZstd);
  const ChunkIndex& first = d.summary.chunk_indexes[0];
  // The last byte of the first chunk's last message index: an offset, which a linear read skips.
  d.bytes[static_cast<std::size_t>(first.chunk_start_offset + first.chunk_length +
                                   first.message_index_length - 1)] ^= 0x10;
  auto reader = LinearReader::open(memory_source(d.bytes));
  ASSERT_TRUE(reader);
  EXPECT_EQ(test::read_all(*reader), d.written);           // every chunk is whole ...
  EXPECT_EQ(reader->stop().reason, StopReason::kCorrupt);  // ... but DataEnd's CRC says not all is
  EXPECT_NE(reader->stop().message.find("data section's CRC"), std::string::npos) << reader->stop().message;
}

// magic, Header{"", ""}, then `record`.
std::vector<std::uint8_t> file_with(const std::vector<std::uint8_t>& record) {
  std::vector<std::uint8_t> bytes(kMagic.begin(), kMagic.end());
  append_record(bytes, Header{});
  bytes.insert(bytes.end(), record.begin(), record.end());
  return bytes;
}

TEST(Corruption, ClaimedSizesBeyondTheLimitsAreRefusedUnread) {
  // A chunk that says it holds 1 TiB uncompressed.
  const std::uint8_t tiny[4] = {1, 2, 3, 4};
  ChunkView huge;
  huge.uncompressed_size = std::uint64_t{1} << 40;
  huge.compression = "zstd";
  huge.records = tiny;
  auto record = chunk_record_head(huge);
  record.insert(record.end(), std::begin(tiny), std::end(tiny));
  const auto huge_file = file_with(record);
  auto reader = LinearReader::open(memory_source(huge_file));
  ASSERT_TRUE(reader);
  EXPECT_FALSE(reader->next());
  EXPECT_EQ(reader->stop().reason, StopReason::kCorrupt);
  EXPECT_NE(reader->stop().message.find("more than"), std::string::npos) << reader->stop().message;

  // A record whose length is beyond the file: truncated, not read.
  std::vector<std::uint8_t> beyond = {
      static_cast<std::uint8_t>(Opcode::kSchema), 0xff, 0xff, 0xff, 0xff, 0, 0, 0, 0};
  const auto beyond_file = file_with(beyond);
  auto cut = LinearReader::open(memory_source(beyond_file));
  ASSERT_TRUE(cut);
  EXPECT_FALSE(cut->next());
  EXPECT_EQ(cut->stop().reason, StopReason::kTruncated);

  // A record within the file but beyond max_record_bytes.
  std::vector<std::uint8_t> big(kRecordPrefixBytes + 5000, 0);
  big[0] = static_cast<std::uint8_t>(Opcode::kMetadata);
  big[1] = 0x88;  // 5000 = 0x1388
  big[2] = 0x13;
  ReaderOptions small;
  small.max_record_bytes = 4096;
  const auto big_file = file_with(big);
  auto limited = LinearReader::open(memory_source(big_file), small);
  ASSERT_TRUE(limited);
  EXPECT_FALSE(limited->next());
  EXPECT_EQ(limited->stop().reason, StopReason::kCorrupt);
}

// Found by the fuzz harness (UBSan): a record of no content made the memory source memcpy into
// the null data() of an empty buffer.
TEST(Corruption, ARecordWithoutContentIsSkipped) {
  std::vector<std::uint8_t> records = {0x80, 0, 0, 0, 0, 0, 0, 0, 0};  // a private record, empty
  append_record(records, DataEnd{0});
  const auto bytes = file_with(records);
  auto reader = LinearReader::open(memory_source(bytes));
  ASSERT_TRUE(reader);
  EXPECT_FALSE(reader->next());
  EXPECT_EQ(reader->stop().reason, StopReason::kDataEnd) << reader->stop().message;
}

TEST(Corruption, AMessageBeforeItsChannelAndTextThatIsNotUtf8AreRefused) {
  std::vector<std::uint8_t> message;
  const std::uint8_t data[2] = {9, 9};
  append_record(message, Message{4, 0, 1, 1, data});
  const auto message_file = file_with(message);
  auto reader = LinearReader::open(memory_source(message_file));
  ASSERT_TRUE(reader);
  EXPECT_FALSE(reader->next());
  EXPECT_EQ(reader->stop().reason, StopReason::kCorrupt);
  EXPECT_NE(reader->stop().message.find("channel 4"), std::string::npos) << reader->stop().message;

  std::vector<std::uint8_t> channel;
  append_record(channel, Channel{1, 0, "/ok", "cdr", {}});
  channel[kRecordPrefixBytes + 2 + 2 + 4] = 0xff;  // the topic's first byte
  const auto channel_file = file_with(channel);
  auto bad_text = LinearReader::open(memory_source(channel_file));
  ASSERT_TRUE(bad_text);
  EXPECT_FALSE(bad_text->next());
  EXPECT_NE(bad_text->stop().message.find("UTF-8"), std::string::npos) << bad_text->stop().message;
}

}  // namespace
}  // namespace hubrt::mcap
