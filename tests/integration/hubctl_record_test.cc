// `hubctl record` as a process against a hubd: a hub that starts after the recorder is recorded;
// SIGINT and SIGTERM finish the file (its summary reads, its statistics count what a linear read
// finds); a recorder killed with SIGKILL leaves its whole chunks, and `--recover` makes the file
// whole with every one of them; --max-duration splits into complete files.
#include <csignal>
#include <filesystem>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/mcap/linear_reader.h"
#include "hubrt/mcap/summary.h"

#include "hubrt/test_support/hub_process.h"

namespace hubrt::integration {
namespace {

using test_support::HubProcess;

namespace fs = std::filesystem;
using std::chrono::seconds;
using test_support::ChildProcess;

// Generous: hubd and hubctl under sanitizers on a loaded 2-core machine start in seconds.
constexpr auto kPatience = seconds(60);

struct Read {
  std::uint64_t messages = 0;
  std::map<std::string, std::uint64_t> per_topic;
  mcap::StopReason stop = mcap::StopReason::kReading;
};

Read read_linear(const std::string& path) {
  Read r;
  auto source = mcap::open_file(path);
  EXPECT_TRUE(source) << path;
  if (!source) return r;
  auto reader = mcap::LinearReader::open(std::move(*source));
  EXPECT_TRUE(reader) << reader.error().message;
  if (!reader) return r;
  while (auto m = reader->next()) {
    ++r.messages;
    ++r.per_topic[reader->channels().at(m->channel_id).topic];
  }
  r.stop = reader->stop().reason;
  return r;
}

class HubctlRecordTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    dir_ = fs::temp_directory_path() /
           fmt::format("hubrt-record-{}-{}", getpid(),
                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  ChildProcess hubctl(const std::vector<std::string>& args) {
    auto child = ChildProcess::start(HUBRT_HUBCTL_PATH, args, domain_->env());
    EXPECT_TRUE(child) << child.error().message;
    return std::move(*child);
  }

  // Starts a recorder, then the Dock ECU's hubd, and waits until the file holds a chunk of the
  // hub's State: the hub came after the recorder.
  // `first_file`: the file to watch (the first part when splitting), until it holds `min_states`.
  std::pair<ChildProcess, HubProcess> record_a_hub(const std::string& file,
                                                   std::vector<std::string> extra = {},
                                                   std::string first_file = {},
                                                   std::uint64_t min_states = 20) {
    if (first_file.empty()) first_file = file;
    std::vector<std::string> args = {"record", "-o", file, "--quiet", "--chunk-seconds", "0.2"};
    args.insert(args.end(), extra.begin(), extra.end());
    ChildProcess recorder = hubctl(args);
    EXPECT_TRUE(recorder.wait_for_output("recording into", kPatience)) << recorder.stderr_text();
    auto hub = HubProcess::start(*domain_, {});
    EXPECT_TRUE(hub) << hub.error().message;
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    while (std::chrono::steady_clock::now() < deadline && read_linear_quiet(first_file) < min_states)
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    return {std::move(recorder), std::move(*hub)};
  }

  // States of the hub in the whole chunks written so far (0 while there are none).
  static std::uint64_t read_linear_quiet(const std::string& file) {
    auto source = mcap::open_file(file);
    if (!source) return 0;
    auto reader = mcap::LinearReader::open(std::move(*source));
    if (!reader) return 0;
    std::uint64_t states = 0;
    while (auto m = reader->next())
      states += reader->channels().at(m->channel_id).topic == "/dock_ecu/dock/state";
    return states;
  }

  std::optional<test_support::TestDomain> domain_;
  fs::path dir_;
};

class FinishingSignal : public HubctlRecordTest, public ::testing::WithParamInterface<int> {};

TEST_P(FinishingSignal, RecordsAHubThatCameLaterAndFinishesTheFile) {
  const std::string file = (dir_ / "run.mcap").string();
  auto [recorder, hub] = record_a_hub(file);
  ASSERT_TRUE(recorder.signal(GetParam()));
  auto status = recorder.wait(kPatience);
  ASSERT_TRUE(status);
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << recorder.stderr_text();
  EXPECT_NE(recorder.stdout_text().find("recorded "), std::string::npos) << recorder.stdout_text();
  auto source = mcap::open_file(file);
  ASSERT_TRUE(source);
  auto summary = mcap::read_summary(**source);
  ASSERT_TRUE(summary) << summary.error().message;
  Read read = read_linear(file);
  EXPECT_EQ(read.stop, mcap::StopReason::kDataEnd);
  EXPECT_GE(read.per_topic["/dock_ecu/dock/state"], 20U);
  EXPECT_GT(read.per_topic["/diagnostics"], 0U);
  EXPECT_EQ(summary->statistics->message_count, read.messages);
  bool state_channel = false;
  for (const auto& [id, channel] : summary->channels) {
    if (channel.topic != "/dock_ecu/dock/state") continue;
    state_channel = true;
    EXPECT_EQ(summary->schemas.at(channel.schema_id).name, "hub_msgs/msg/DockState");
    EXPECT_NE(channel.metadata.at("offered_qos_profiles").find("reliability: reliable"), std::string::npos);
  }
  EXPECT_TRUE(state_channel);
}

INSTANTIATE_TEST_SUITE_P(SigintAndSigterm, FinishingSignal, ::testing::Values(SIGINT, SIGTERM));

TEST_F(HubctlRecordTest, AKilledRecorderLeavesItsWholeChunksAndRecoverMakesTheFileWhole) {
  const std::string file = (dir_ / "killed.mcap").string();
  auto [recorder, hub] = record_a_hub(file);
  ASSERT_TRUE(recorder.signal(SIGKILL));
  ASSERT_TRUE(recorder.wait(kPatience));
  auto source = mcap::open_file(file);
  ASSERT_TRUE(source);
  EXPECT_FALSE(mcap::read_summary(**source)) << "a killed recorder wrote no summary";
  Read cut = read_linear(file);
  EXPECT_EQ(cut.stop, mcap::StopReason::kTruncated);
  EXPECT_GE(cut.per_topic["/dock_ecu/dock/state"], 20U);

  ChildProcess recover = hubctl({"record", "--recover", file});
  auto status = recover.wait(kPatience);
  ASSERT_TRUE(status);
  EXPECT_TRUE(status->exited_with(0)) << recover.stderr_text();
  auto whole = mcap::open_file(file);
  ASSERT_TRUE(whole);
  auto summary = mcap::read_summary(**whole);
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_EQ(summary->statistics->message_count, cut.messages);
  EXPECT_EQ(read_linear(file).per_topic, cut.per_topic);
  // A whole file is left alone.
  ChildProcess again = hubctl({"record", "--recover", file});
  ASSERT_TRUE(again.wait(kPatience));
  EXPECT_NE(again.stdout_text().find("nothing to recover"), std::string::npos) << again.stdout_text();
}

TEST_F(HubctlRecordTest, MaxDurationSplitsIntoCompleteFiles) {
  const std::string file = (dir_ / "split.mcap").string();
  auto [recorder, hub] = record_a_hub(file, {"--max-duration", "1"}, (dir_ / "split_0.mcap").string(), 3);
  // The first part is complete once the second begins; wait for a third to begin.
  const auto deadline = std::chrono::steady_clock::now() + kPatience;
  while (std::chrono::steady_clock::now() < deadline && !fs::exists(dir_ / "split_2.mcap"))
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ASSERT_TRUE(recorder.signal(SIGINT));
  auto status = recorder.wait(kPatience);
  ASSERT_TRUE(status && status->exited_with(0)) << recorder.stderr_text();
  std::size_t parts = 0;
  for (; fs::exists(dir_ / fmt::format("split_{}.mcap", parts)); ++parts) {
    const std::string part = (dir_ / fmt::format("split_{}.mcap", parts)).string();
    auto source = mcap::open_file(part);
    ASSERT_TRUE(source);
    auto summary = mcap::read_summary(**source);
    ASSERT_TRUE(summary) << part << ": " << summary.error().message;
    if (summary->statistics->message_count > 1) {
      EXPECT_LT(summary->statistics->message_end_time - summary->statistics->message_start_time,
                1'000'000'000U)
          << part;
    }
  }
  EXPECT_GE(parts, 3U);
  EXPECT_FALSE(fs::exists(file)) << "a split recording's parts are numbered";
}

}  // namespace
}  // namespace hubrt::integration
