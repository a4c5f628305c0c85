// The writer's files read back by the linear reader: every message, in order, with its bytes and
// times, for each compression; chunk boundaries where the writer promises them.
#include <gtest/gtest.h>

#include "hubrt/mcap/linear_reader.h"
#include "hubrt/mcap/summary.h"
#include "hubrt/mcap/writer.h"

#include "mcap_test_files.h"

namespace hubrt::mcap {
namespace {

using test::RecordedMessage;
using test::ScratchDir;

class RoundTrip : public ::testing::TestWithParam<Compression> {};

TEST_P(RoundTrip, EveryMessageComesBackInOrderWithItsBytesAndTimes) {
  ScratchDir dir;
  WriterOptions options;
  options.compression = GetParam();
  options.chunk_bytes = 2048;
  const auto written = test::write_sample_file(dir.file("a.mcap"), options, 300);
  auto source = open_file(dir.file("a.mcap"));
  ASSERT_TRUE(source) << source.error().message;
  auto reader = LinearReader::open(std::move(*source));
  ASSERT_TRUE(reader) << reader.error().message;
  EXPECT_EQ(reader->header().profile, "ros2");
  EXPECT_EQ(reader->header().library, "hubrt");
  EXPECT_EQ(test::read_all(*reader), written);
  EXPECT_EQ(reader->stop().reason, StopReason::kDataEnd) << reader->stop().message;
  EXPECT_GT(reader->whole_chunks(), 5U);  // 300 messages of ~100 bytes in chunks of 2 KiB
  ASSERT_EQ(reader->channels().size(), 3U);
  ASSERT_EQ(reader->schemas().size(), 2U);
  for (const auto& [id, channel] : reader->channels()) {
    EXPECT_EQ(channel.message_encoding, "cdr");
    EXPECT_EQ(reader->schemas().at(channel.schema_id).encoding, "ros2msg");
  }
  EXPECT_EQ(reader->channels().at(0).metadata.at("offered_qos_profiles"),
            "- history: keep_last\n  depth: 10\n");
  // Every chunk carries the compression asked for.
  auto again = open_file(dir.file("a.mcap"));
  ASSERT_TRUE(again);
  auto summary = read_summary(**again);
  ASSERT_TRUE(summary) << summary.error().message;
  for (const ChunkIndex& index : summary->chunk_indexes)
    EXPECT_EQ(index.compression, compression_name(GetParam()));
}

INSTANTIATE_TEST_SUITE_P(Compressions, RoundTrip,
                         ::testing::Values(Compression::kZstd, Compression::kLz4, Compression::kNone),
                         [](const ::testing::TestParamInfo<Compression>& param) {
                           const auto name = compression_name(param.param);
                           return name.empty() ? std::string("none") : std::string(name);
                         });

TEST(Compression, ZstdShrinksStateLikeRecords) {
  ScratchDir dir;
  WriterOptions zstd;
  WriterOptions none;
  none.compression = Compression::kNone;
  test::write_sample_file(dir.file("z.mcap"), zstd, 2000);
  test::write_sample_file(dir.file("n.mcap"), none, 2000);
  EXPECT_LT(test::read_bytes(dir.file("z.mcap")).size() * 2, test::read_bytes(dir.file("n.mcap")).size());
}

// The records of the chunk `index` locates, as (opcode, content) views into `records`.
std::vector<RecordView> records_of(const std::vector<std::uint8_t>& records) {
  std::vector<RecordView> out;
  RecordCursor cursor(records);
  RecordView record;
  while (true) {
    auto more = cursor.next(record);
    EXPECT_TRUE(more);
    if (!more || !*more) break;
    out.push_back(record);
  }
  return out;
}

TEST(ChunkBoundaries, AChunkStaysWithinItsSizeUnlessOneMessageIsLarger) {
  ScratchDir dir;
  WriterOptions options;
  options.chunk_bytes = 1000;
  auto writer = Writer::create(dir.file("b.mcap"), options);
  ASSERT_TRUE(writer);
  const auto schema = writer->add_schema({0, "pkg/msg/T", "ros2msg", "uint8[] data\n"});
  const auto channel = writer->add_channel({0, *schema, "/t", "cdr", {}});
  for (std::uint32_t n = 0; n < 60; ++n) {
    const auto data = test::payload(n, n == 30 ? 3000 : 90);  // one message three times a chunk
    ASSERT_TRUE(writer->write({*channel, n, 1000 + n, 1000 + n, data}));
  }
  ASSERT_TRUE(writer->finish());
  auto source = open_file(dir.file("b.mcap"));
  ASSERT_TRUE(source);
  auto summary = read_summary(**source);
  ASSERT_TRUE(summary) << summary.error().message;
  bool large_alone = false;
  for (const ChunkIndex& index : summary->chunk_indexes) {
    auto records = read_chunk_records(**source, index);
    ASSERT_TRUE(records) << records.error().message;
    std::size_t messages = 0;
    for (const RecordView& r : records_of(*records))
      messages += r.opcode == static_cast<std::uint8_t>(Opcode::kMessage);
    if (index.uncompressed_size > options.chunk_bytes) {
      EXPECT_EQ(messages, 1U) << "a chunk over its size must hold one message only";
      large_alone = true;
    }
  }
  EXPECT_TRUE(large_alone);
}

TEST(ChunkBoundaries, CloseChunkEndsTheChunkAndAChannelComesWithItsFirstMessage) {
  ScratchDir dir;
  auto writer = Writer::create(dir.file("c.mcap"));
  ASSERT_TRUE(writer);
  const auto schema = writer->add_schema({0, "pkg/msg/T", "ros2msg", "string text\n"});
  const auto early = writer->add_channel({0, *schema, "/early", "cdr", {}});
  const auto late = writer->add_channel({0, *schema, "/late", "cdr", {}});
  const auto data = test::payload(1, 20);
  ASSERT_TRUE(writer->write({*early, 0, 10, 10, data}));
  ASSERT_TRUE(writer->close_chunk());
  EXPECT_EQ(writer->open_chunk_bytes(), 0U);
  const std::uint64_t after_first = writer->file_bytes();
  ASSERT_TRUE(writer->write({*late, 1, 20, 20, data}));
  ASSERT_TRUE(writer->finish());
  auto source = open_file(dir.file("c.mcap"));
  ASSERT_TRUE(source);
  auto summary = read_summary(**source);
  ASSERT_TRUE(summary);
  ASSERT_EQ(summary->chunk_indexes.size(), 2U);
  EXPECT_EQ(summary->chunk_indexes[1].chunk_start_offset, after_first);
  // The second chunk defines /late (and not /early again) before its message.
  auto records = read_chunk_records(**source, summary->chunk_indexes[1]);
  ASSERT_TRUE(records);
  const auto in_chunk = records_of(*records);
  ASSERT_EQ(in_chunk.size(), 2U);
  EXPECT_EQ(in_chunk[0].opcode, static_cast<std::uint8_t>(Opcode::kChannel));
  EXPECT_EQ(parse_channel(in_chunk[0].content)->topic, "/late");
  EXPECT_EQ(in_chunk[1].opcode, static_cast<std::uint8_t>(Opcode::kMessage));
}

TEST(Writer, RefusesToOverwriteAFileAndUnknownIds) {
  ScratchDir dir;
  test::write_bytes(dir.file("taken.mcap"), {1, 2, 3});
  auto taken = Writer::create(dir.file("taken.mcap"));
  ASSERT_FALSE(taken);
  EXPECT_EQ(taken.error().code, ErrorCode::kFailedPrecondition);
  EXPECT_EQ(test::read_bytes(dir.file("taken.mcap")).size(), 3U);
  auto writer = Writer::create(dir.file("w.mcap"));
  ASSERT_TRUE(writer);
  EXPECT_FALSE(writer->add_channel({0, 7, "/x", "cdr", {}}));
  const std::uint8_t byte = 0;
  EXPECT_FALSE(writer->write({3, 0, 0, 0, Bytes(&byte, 1)}));
  const auto first = writer->add_schema({0, "a/msg/B", "ros2msg", "int8 x\n"});
  const auto again = writer->add_schema({0, "a/msg/B", "ros2msg", "int8 x\n"});
  const auto other = writer->add_schema({0, "a/msg/B", "ros2msg", "int16 x\n"});
  ASSERT_TRUE(first && again && other);
  EXPECT_EQ(*first, *again);
  EXPECT_NE(*first, *other);
  EXPECT_FALSE(writer->add_channel({0, *first, std::string("/bad\xff"), "cdr", {}}));
  ASSERT_TRUE(writer->finish());
  EXPECT_FALSE(writer->finish());
}

TEST(LinearReader, RefusesWhatIsNotMcap) {
  const std::vector<std::uint8_t> text = {'h', 'e', 'l', 'l', 'o', ' ', 'w', 'o', 'r', 'l', 'd', '\n'};
  auto reader = LinearReader::open(memory_source(text));
  ASSERT_FALSE(reader);
  EXPECT_NE(reader.error().message.find("not an MCAP file"), std::string::npos) << reader.error().message;
}

}  // namespace
}  // namespace hubrt::mcap
