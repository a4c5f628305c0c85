// A file cut off at every byte, as a killed writer or a full disk leaves it: the reader hands out
// exactly the messages of the chunks that are whole, never one of a cut chunk, never crashes; the
// summary reader refuses every cut file; recover() makes each cut file whole again.
#include <gtest/gtest.h>

#include "hubrt/mcap/linear_reader.h"
#include "hubrt/mcap/recover.h"
#include "hubrt/mcap/summary.h"

#include "mcap_test_files.h"

namespace hubrt::mcap {
namespace {

struct Sample {
  std::vector<std::uint8_t> bytes;
  std::vector<test::RecordedMessage> written;
  Summary summary;
  std::uint64_t header_end = 0;  // magic and Header
  std::uint64_t data_end = 0;    // just after the DataEnd record
};

Sample small_file(const test::ScratchDir& dir) {
  WriterOptions options;
  options.chunk_bytes = 250;
  Sample s;
  s.written = test::write_sample_file(dir.file("full.mcap"), options, 20);
  s.bytes = test::read_bytes(dir.file("full.mcap"));
  auto summary = read_summary(*memory_source(s.bytes));
  EXPECT_TRUE(summary) << summary.error().message;
  s.summary = *summary;
  s.header_end =
      kMagic.size() + kRecordPrefixBytes + 4 + 4 + std::string("ros2").size() + std::string("hubrt").size();
  s.data_end = s.summary.footer.summary_start;
  return s;
}

// The messages a reader must hand out from the first `length` bytes: those of the chunks whose
// record ends within them (written in log-time order, so a prefix of `written`).
std::vector<test::RecordedMessage> whole_chunk_messages(const Sample& s, std::uint64_t length) {
  std::uint64_t last_end_time = 0;
  bool any = false;
  for (const ChunkIndex& index : s.summary.chunk_indexes) {
    if (index.chunk_start_offset + index.chunk_length > length) break;
    last_end_time = index.message_end_time;
    any = true;
  }
  std::vector<test::RecordedMessage> out;
  for (const auto& m : s.written)
    if (any && m.log_time <= last_end_time) out.push_back(m);
  return out;
}

TEST(Truncation, EveryPrefixReadsExactlyItsWholeChunks) {
  test::ScratchDir dir;
  const Sample s = small_file(dir);
  ASSERT_GE(s.summary.chunk_indexes.size(), 5U);
  for (std::uint64_t length = 0; length < s.bytes.size(); ++length) {
    SCOPED_TRACE(::testing::Message() << "cut after " << length << " of " << s.bytes.size() << " bytes");
    const Bytes prefix = Bytes(s.bytes).first(static_cast<std::size_t>(length));
    EXPECT_FALSE(read_summary(*memory_source(prefix)));
    auto reader = LinearReader::open(memory_source(prefix));
    if (length < s.header_end) {
      EXPECT_FALSE(reader);
      continue;
    }
    ASSERT_TRUE(reader) << reader.error().message;
    const auto read = test::read_all(*reader);
    if (length >= s.data_end) {
      // The data section is all there; only the summary is cut.
      EXPECT_EQ(read, s.written);
      EXPECT_EQ(reader->stop().reason, StopReason::kDataEnd);
    } else {
      EXPECT_EQ(read, whole_chunk_messages(s, length));
      EXPECT_EQ(reader->stop().reason, StopReason::kTruncated) << reader->stop().message;
    }
  }
}

TEST(Truncation, RecoverMakesACutFileWholeWithEveryWholeChunk) {
  test::ScratchDir dir;
  const Sample s = small_file(dir);
  std::vector<std::uint64_t> cuts;
  for (const ChunkIndex& index : s.summary.chunk_indexes) {
    const std::uint64_t end = index.chunk_start_offset + index.chunk_length;
    cuts.insert(cuts.end(), {index.chunk_start_offset + 3, end - 1, end, end + 5});
  }
  cuts.push_back(s.data_end - 1);
  cuts.push_back(s.bytes.size() - 1);
  for (const std::uint64_t length : cuts) {
    SCOPED_TRACE(::testing::Message() << "cut after " << length << " bytes");
    const std::string cut = dir.file("cut_" + std::to_string(length) + ".mcap");
    const std::string whole = dir.file("whole_" + std::to_string(length) + ".mcap");
    test::write_bytes(cut, std::vector<std::uint8_t>(s.bytes.begin(),
                                                     s.bytes.begin() + static_cast<std::ptrdiff_t>(length)));
    auto recovered = recover(cut, whole);
    ASSERT_TRUE(recovered) << recovered.error().message;
    const auto expected = length >= s.data_end ? s.written : whole_chunk_messages(s, length);
    EXPECT_EQ(recovered->messages, expected.size());
    EXPECT_EQ(recovered->bytes_kept + recovered->bytes_dropped, length);
    auto source = open_file(whole);
    ASSERT_TRUE(source);
    auto summary = read_summary(**source);
    ASSERT_TRUE(summary) << summary.error().message;
    EXPECT_EQ(summary->statistics->message_count, expected.size());
    auto again = open_file(whole);
    auto reader = LinearReader::open(std::move(*again));
    ASSERT_TRUE(reader);
    EXPECT_EQ(test::read_all(*reader), expected);
    EXPECT_EQ(reader->stop().reason, StopReason::kDataEnd);
    EXPECT_EQ(reader->header().profile, "ros2");
  }
}

TEST(Truncation, RecoverRefusesToOverwriteAndSaysWhatIsNotMcap) {
  test::ScratchDir dir;
  const Sample s = small_file(dir);
  auto over = recover(dir.file("full.mcap"), dir.file("full.mcap"));
  ASSERT_FALSE(over);
  EXPECT_EQ(test::read_bytes(dir.file("full.mcap")), s.bytes);
  test::write_bytes(dir.file("text.mcap"), {'n', 'o', 't', ' ', 'm', 'c', 'a', 'p', '!', '!'});
  auto text = recover(dir.file("text.mcap"), dir.file("out.mcap"));
  ASSERT_FALSE(text);
  EXPECT_NE(text.error().message.find("not an MCAP file"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.mcap")));
}

}  // namespace
}  // namespace hubrt::mcap
