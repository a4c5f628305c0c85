// What the black box writes: a dump of the last span as a complete ros2-profile MCAP file (a
// channel per stream, the received samples with their source time, the sent ones stamped as they
// left), the directory kept under its cap, and the crash path's file (no index) read by the linear
// reader and made whole by mcap::recover.
#include "hubrt/blackbox/black_box.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/mcap/linear_reader.h"
#include "hubrt/mcap/recover.h"
#include "hubrt/mcap/summary.h"

namespace hubrt::blackbox {
namespace {

namespace fs = std::filesystem;

class BlackBoxTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           fmt::format("hubrt-blackbox-{}-{}", getpid(),
                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::unique_ptr<BlackBox> make(std::uint64_t directory_bytes = 64 << 20) {
    BlackBoxOptions options;
    options.hub_name = "dock_ecu";
    options.directory = (dir_ / "box").string();
    options.directory_bytes = directory_bytes;
    options.memory_bytes = 256 * 1024;
    auto box = BlackBox::create(options);
    EXPECT_TRUE(box) << box.error().message;
    commands_ =
        &(*box)->add_stream({"/dock/command", "hub_msgs/msg/DockCommand", "string action\n", "[]\n", true});
    states_ = &(*box)->add_stream(
        {"/dock_ecu/dock/state", "hub_msgs/msg/DockState", "bool docked\n", "[]\n", false});
    (*box)->seal();
    return std::move(*box);
  }

  // 20 commands with a source time 1 ms in the past, 40 States.
  void feed() {
    const std::vector<std::uint8_t> command = {0, 1, 0, 0, 8, 0, 0, 0, 'm', 'o', 'n', 'i', 't', 'o', 'r', 0};
    const std::vector<std::uint8_t> state = {0, 1, 0, 0, 1, 0, 0, 0};
    for (int n = 0; n < 40; ++n) {
      if (n % 2 == 0) {
        const auto now = std::chrono::system_clock::now().time_since_epoch();
        commands_->on_sample(
            command, WallTime{std::chrono::duration_cast<std::chrono::nanoseconds>(now).count() - 1'000'000});
      }
      states_->on_sample(state, WallTime{});
    }
  }

  fs::path dir_;
  dds::SampleHook* commands_ = nullptr;
  dds::SampleHook* states_ = nullptr;
};

TEST_F(BlackBoxTest, ADumpIsACompleteRos2FileOfTheStreams) {
  auto box = make();
  feed();
  auto written = box->dump("request");
  ASSERT_TRUE(written) << written.error().message;
  EXPECT_TRUE(written->path.ends_with("_request.mcap")) << written->path;
  EXPECT_TRUE(fs::path(written->path).filename().string().starts_with("dock_ecu_"));
  EXPECT_EQ(written->messages, 60U);
  EXPECT_EQ(fs::file_size(written->path), written->bytes);
  for (const auto& entry : fs::directory_iterator(dir_ / "box"))
    EXPECT_FALSE(entry.path().string().ends_with(".part")) << entry.path();
  auto source = mcap::open_file(written->path);
  ASSERT_TRUE(source);
  auto summary = mcap::read_summary(**source);
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_EQ(summary->statistics->message_count, 60U);
  ASSERT_EQ(summary->channels.size(), 2U);
  auto again = mcap::open_file(written->path);
  auto reader = mcap::LinearReader::open(std::move(*again));
  ASSERT_TRUE(reader);
  EXPECT_EQ(reader->header().profile, "ros2");
  std::size_t commands = 0;
  while (auto m = reader->next()) {
    const auto& channel = reader->channels().at(m->channel_id);
    EXPECT_EQ(channel.message_encoding, "cdr");
    EXPECT_EQ(reader->schemas().at(channel.schema_id).encoding, "ros2msg");
    if (channel.topic == "/dock/command") {
      ++commands;
      // Received: arrival (log time) after the source time, by the millisecond fed.
      EXPECT_GE(m->log_time, m->publish_time + 1'000'000);
    } else {
      EXPECT_EQ(m->log_time, m->publish_time);  // sent: stamped as it left
    }
  }
  EXPECT_EQ(commands, 20U);
}

TEST_F(BlackBoxTest, TheDirectoryKeepsTheNewestFilesUnderItsCap) {
  auto box = make(1);  // 1 byte: only the newest file stays
  feed();
  auto first = box->dump("fault");
  ASSERT_TRUE(first);
  feed();
  auto second = box->dump("request");
  ASSERT_TRUE(second);
  EXPECT_NE(first->path, second->path);
  EXPECT_FALSE(fs::exists(first->path));
  EXPECT_TRUE(fs::exists(second->path));
  // Another hub's file in the same directory is not this hub's to remove.
  std::ofstream(dir_ / "box" / "rsp_ecu_x.mcap") << "other";
  feed();
  ASSERT_TRUE(box->dump("exit-SIGTERM"));
  EXPECT_TRUE(fs::exists(dir_ / "box" / "rsp_ecu_x.mcap"));
  EXPECT_FALSE(box->dump("no spaces"));
}

TEST_F(BlackBoxTest, TheCrashPathWritesAnUnindexedFileThatRecoverMakesWhole) {
  auto box = make();
  feed();
  box->crash_dump();
  std::string crash;
  for (const auto& entry : fs::directory_iterator(dir_ / "box"))
    if (entry.path().string().ends_with("_crash.mcap")) crash = entry.path().string();
  ASSERT_FALSE(crash.empty());
  auto source = mcap::open_file(crash);
  ASSERT_TRUE(source);
  auto reader = mcap::LinearReader::open(std::move(*source));
  ASSERT_TRUE(reader) << reader.error().message;
  std::size_t messages = 0;
  while (reader->next()) ++messages;
  EXPECT_EQ(messages, 60U);
  EXPECT_EQ(reader->stop().reason, mcap::StopReason::kDataEnd) << reader->stop().message;
  auto recovered = mcap::recover(crash, crash + ".whole.mcap");
  ASSERT_TRUE(recovered) << recovered.error().message;
  EXPECT_EQ(recovered->messages, 60U);
  auto whole = mcap::open_file(crash + ".whole.mcap");
  EXPECT_TRUE(mcap::read_summary(**whole));
}

}  // namespace
}  // namespace hubrt::blackbox
