// The summary a seeking reader uses agrees with the data: statistics count what is there, every
// chunk is where its index says, every message index entry points at a message of its channel
// and time, and the summary offsets locate each group of records.
#include "hubrt/mcap/summary.h"

#include <set>

#include <gtest/gtest.h>

#include "hubrt/mcap/linear_reader.h"

#include "mcap_test_files.h"

namespace hubrt::mcap {
namespace {

TEST(Summary, StatisticsIndexesAndOffsetsAgreeWithTheData) {
  test::ScratchDir dir;
  WriterOptions options;
  options.chunk_bytes = 1500;
  const auto written = test::write_sample_file(dir.file("s.mcap"), options, 400);
  auto source = open_file(dir.file("s.mcap"));
  ASSERT_TRUE(source);
  auto summary = read_summary(**source);
  ASSERT_TRUE(summary) << summary.error().message;
  ASSERT_TRUE(summary->statistics);
  const Statistics& stats = *summary->statistics;
  EXPECT_EQ(stats.message_count, written.size());
  EXPECT_EQ(stats.schema_count, 2U);
  EXPECT_EQ(stats.channel_count, 3U);
  EXPECT_EQ(stats.chunk_count, summary->chunk_indexes.size());
  EXPECT_EQ(stats.message_start_time, written.front().log_time);
  EXPECT_EQ(stats.message_end_time, written.back().log_time);
  std::map<std::string, std::uint64_t> per_topic;
  for (const auto& m : written) ++per_topic[m.topic];
  ASSERT_EQ(summary->channels.size(), 3U);
  for (const auto& [id, channel] : summary->channels)
    EXPECT_EQ(stats.channel_message_counts.at(id), per_topic[channel.topic]);

  // The summary's schemas and channels are copies of those in the data section.
  auto linear_source = open_file(dir.file("s.mcap"));
  auto linear = LinearReader::open(std::move(*linear_source));
  ASSERT_TRUE(linear);
  test::read_all(*linear);
  EXPECT_EQ(summary->schemas, linear->schemas());
  EXPECT_EQ(summary->channels, linear->channels());

  std::uint64_t indexed = 0;
  std::uint64_t previous_end = 0;
  for (const ChunkIndex& index : summary->chunk_indexes) {
    EXPECT_GT(index.chunk_start_offset, previous_end);
    previous_end = index.chunk_start_offset;
    auto records = read_chunk_records(**source, index);
    ASSERT_TRUE(records) << records.error().message;
    EXPECT_EQ(records->size(), index.uncompressed_size);
    auto indexes = read_message_indexes(**source, index);
    ASSERT_TRUE(indexes) << indexes.error().message;
    EXPECT_EQ(indexes->size(), index.message_index_offsets.size());
    std::uint64_t earliest = UINT64_MAX;
    std::uint64_t latest = 0;
    std::size_t messages_in_chunk = 0;
    RecordCursor all(*records);
    RecordView r;
    while (*all.next(r)) messages_in_chunk += r.opcode == static_cast<std::uint8_t>(Opcode::kMessage);
    std::set<std::uint64_t> offsets;
    for (const MessageIndex& message_index : *indexes) {
      for (const MessageIndexEntry& entry : message_index.records) {
        // The offset is that of a Message record of this channel and log time.
        RecordCursor at(Bytes(*records).subspan(static_cast<std::size_t>(entry.offset)));
        RecordView record;
        ASSERT_TRUE(*at.next(record));
        ASSERT_EQ(record.opcode, static_cast<std::uint8_t>(Opcode::kMessage));
        auto message = parse_message(record.content);
        ASSERT_TRUE(message);
        EXPECT_EQ(message->channel_id, message_index.channel_id);
        EXPECT_EQ(message->log_time, entry.log_time);
        offsets.insert(entry.offset);
        earliest = std::min(earliest, entry.log_time);
        latest = std::max(latest, entry.log_time);
        ++indexed;
      }
    }
    EXPECT_EQ(offsets.size(), messages_in_chunk) << "every message of the chunk indexed once";
    EXPECT_EQ(index.message_start_time, earliest);
    EXPECT_EQ(index.message_end_time, latest);
  }
  EXPECT_EQ(indexed, written.size());

  // One SummaryOffset per group, each group holding only records of its opcode.
  const auto bytes = test::read_bytes(dir.file("s.mcap"));
  std::set<Opcode> groups;
  for (const SummaryOffset& offset : summary->summary_offsets) {
    groups.insert(offset.group_opcode);
    RecordCursor cursor(Bytes(bytes).subspan(static_cast<std::size_t>(offset.group_start),
                                             static_cast<std::size_t>(offset.group_length)));
    RecordView record;
    std::size_t n = 0;
    while (*cursor.next(record)) {
      EXPECT_EQ(record.opcode, static_cast<std::uint8_t>(offset.group_opcode));
      ++n;
    }
    EXPECT_GT(n, 0U);
  }
  EXPECT_EQ(groups,
            (std::set<Opcode>{Opcode::kSchema, Opcode::kChannel, Opcode::kStatistics, Opcode::kChunkIndex}));
}

TEST(Summary, AnEmptyRecordingIsComplete) {
  test::ScratchDir dir;
  {
    auto writer = Writer::create(dir.file("e.mcap"));
    ASSERT_TRUE(writer);
    ASSERT_TRUE(writer->finish());
  }
  auto source = open_file(dir.file("e.mcap"));
  auto summary = read_summary(**source);
  ASSERT_TRUE(summary) << summary.error().message;
  ASSERT_TRUE(summary->statistics);
  EXPECT_EQ(summary->statistics->message_count, 0U);
  EXPECT_TRUE(summary->chunk_indexes.empty());
  auto again = open_file(dir.file("e.mcap"));
  auto reader = LinearReader::open(std::move(*again));
  ASSERT_TRUE(reader);
  EXPECT_FALSE(reader->next());
  EXPECT_EQ(reader->stop().reason, StopReason::kDataEnd);
}

}  // namespace
}  // namespace hubrt::mcap
