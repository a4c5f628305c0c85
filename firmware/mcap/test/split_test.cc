// A recording split by size or by duration: every file complete on its own, within its limit,
// with the same channel ids; together they hold every message once, in order.
#include <gtest/gtest.h>

#include "hubrt/mcap/linear_reader.h"
#include "hubrt/mcap/split_writer.h"
#include "hubrt/mcap/summary.h"

#include "mcap_test_files.h"

namespace hubrt::mcap {
namespace {

struct Written {
  std::vector<std::string> files;
  std::vector<test::RecordedMessage> messages;
};

Written write_split(const std::string& path, SplitOptions split, std::uint32_t count, std::size_t size) {
  WriterOptions options;
  options.compression = Compression::kNone;  // so that a file's size follows the bytes written
  auto writer = SplitWriter::create(path, options, split);
  EXPECT_TRUE(writer) << writer.error().message;
  const auto schema = writer->add_schema({0, "pkg/msg/T", "ros2msg", "uint8[] data\n"});
  const auto a = writer->add_channel({0, *schema, "/a", "cdr", {}});
  const auto b = writer->add_channel({0, *schema, "/b", "cdr", {}});
  Written out;
  for (std::uint32_t n = 0; n < count; ++n) {
    const std::uint16_t channel = n % 4 == 0 ? *b : *a;
    auto data = test::payload(n, size);
    const std::uint64_t t = 1'000'000'000'000ULL + n * 10'000'000ULL;  // 100 messages a second
    EXPECT_TRUE(writer->write({channel, n, t, t, data}));
    out.messages.push_back({channel == *a ? "/a" : "/b", n, t, t, std::move(data)});
  }
  EXPECT_TRUE(writer->finish());
  out.files = writer->files();
  return out;
}

std::vector<test::RecordedMessage> read_files(const std::vector<std::string>& files) {
  std::vector<test::RecordedMessage> all;
  for (const std::string& file : files) {
    auto source = open_file(file);
    EXPECT_TRUE(source);
    EXPECT_TRUE(read_summary(**source)) << file << " is not complete";
    auto again = open_file(file);
    auto reader = LinearReader::open(std::move(*again));
    EXPECT_TRUE(reader);
    auto messages = test::read_all(*reader);
    EXPECT_EQ(reader->stop().reason, StopReason::kDataEnd);
    // The same ids in every file.
    for (const auto& [id, channel] : reader->channels()) EXPECT_EQ(channel.topic, id == 0 ? "/a" : "/b");
    all.insert(all.end(), messages.begin(), messages.end());
  }
  return all;
}

TEST(Split, BySizeEveryFileWithinTheLimitAndEveryMessageOnce) {
  test::ScratchDir dir;
  SplitOptions split;
  split.max_bytes = 64 * 1024;
  const Written w = write_split(dir.file("run.mcap"), split, 3000, 200);  // ~660 kB of messages
  ASSERT_GE(w.files.size(), 9U);
  for (std::size_t i = 0; i < w.files.size(); ++i) {
    EXPECT_EQ(w.files[i], dir.file("run_" + std::to_string(i) + ".mcap"));
    const auto size = test::read_bytes(w.files[i]).size();
    EXPECT_LE(size, split.max_bytes + 4096) << w.files[i];  // the summary's few kilobytes
    if (i + 1 < w.files.size()) {
      EXPECT_GE(size, split.max_bytes / 2) << w.files[i];
    }
  }
  EXPECT_EQ(read_files(w.files), w.messages);
}

TEST(Split, ByDurationEachFileSpansLessThanIt) {
  test::ScratchDir dir;
  SplitOptions split;
  split.max_duration = std::chrono::seconds(1);
  const Written w = write_split(dir.file("run.mcap"), split, 350, 60);  // 3.5 s at 100 Hz
  ASSERT_EQ(w.files.size(), 4U);
  for (const std::string& file : w.files) {
    auto source = open_file(file);
    auto summary = read_summary(**source);
    ASSERT_TRUE(summary);
    EXPECT_LT(summary->statistics->message_end_time - summary->statistics->message_start_time,
              1'000'000'000U);
  }
  EXPECT_EQ(read_files(w.files), w.messages);
}

TEST(Split, WithoutALimitOneFileOfTheGivenName) {
  test::ScratchDir dir;
  const Written w = write_split(dir.file("one.mcap"), SplitOptions{}, 50, 60);
  EXPECT_EQ(w.files, std::vector<std::string>{dir.file("one.mcap")});
  EXPECT_EQ(read_files(w.files), w.messages);
}

TEST(Split, FileNames) {
  EXPECT_EQ(split_file_name("a/run.mcap", 2), "a/run_2.mcap");
  EXPECT_EQ(split_file_name("a.d/run", 0), "a.d/run_0");
  EXPECT_EQ(split_file_name(".hidden", 1), ".hidden_1");
  EXPECT_FALSE(SplitWriter::create("x.mcap", WriterOptions{}, SplitOptions{1000, {}}));
}

}  // namespace
}  // namespace hubrt::mcap
