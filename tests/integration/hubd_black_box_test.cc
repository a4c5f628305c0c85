// hubd's black box (issue 30 point 3) as the process runs it: a fault latching writes a file whose
// last RSP State shows the fault; `hubctl blackbox` writes one on request and a second request
// within 10 s is refused; SIGTERM writes the last minute — the planner's commands with their source
// time before their arrival, the States, /diagnostics; a crash (SIGSEGV) writes through the crash
// path a file the linear reader reads.
#include <csignal>
#include <filesystem>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/dds/cdr_codec.h"
#include "hubrt/dds/domain.h"
#include "hubrt/dds/sample.h"
#include "hubrt/mcap/linear_reader.h"
#include "hubrt/mcap/summary.h"
#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/json.h"
#include "hubrt/test_support/hub_process.h"

namespace hubrt::integration {
namespace {

namespace fs = std::filesystem;
using std::chrono::seconds;
using test_support::ChildProcess;
using test_support::HubProcess;
using test_support::HubProcessOptions;

// Start-up and discovery under sanitizers on a loaded 2-core machine; only reached when broken.
constexpr auto kPatience = seconds(60);

class HubdBlackBoxTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    dir_ = fs::temp_directory_path() /
           fmt::format("hubrt-hubd-blackbox-{}-{}", getpid(),
                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  HubProcess start_rsp() {
    HubProcessOptions options;
    options.hub = "rsp_ecu";
    options.extra_env = {{"HUBRT_BLACKBOX_DIR", dir_.string()}};
    auto hub = HubProcess::start(*domain_, options);
    EXPECT_TRUE(hub) << hub.error().message;
    return std::move(*hub);
  }

  ChildProcess hubctl(const std::vector<std::string>& args) {
    auto child = ChildProcess::start(HUBRT_HUBCTL_PATH, args, domain_->env());
    EXPECT_TRUE(child) << child.error().message;
    return std::move(*child);
  }

  // The files whose name ends with `suffix`, waiting up to kPatience for the first.
  std::vector<std::string> files_ending(const std::string& suffix, Duration wait = kPatience) const {
    const auto deadline = std::chrono::steady_clock::now() + wait;
    for (;;) {
      std::vector<std::string> found;
      std::error_code error;
      for (const auto& entry : fs::directory_iterator(dir_, error)) {
        if (entry.path().string().ends_with(suffix)) found.push_back(entry.path().string());
      }
      if (!found.empty() || std::chrono::steady_clock::now() >= deadline) return found;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }

  std::optional<test_support::TestDomain> domain_;
  fs::path dir_;
};

struct Contents {
  std::map<std::string, std::uint64_t> per_topic;
  std::vector<std::vector<std::uint8_t>> rsp_states;  // their bytes, in order
  bool commands_source_before_arrival = true;
  mcap::StopReason stop = mcap::StopReason::kReading;
};

Contents read(const std::string& path) {
  Contents c;
  auto source = mcap::open_file(path);
  EXPECT_TRUE(source) << path;
  if (!source) return c;
  auto reader = mcap::LinearReader::open(std::move(*source));
  EXPECT_TRUE(reader) << reader.error().message;
  if (!reader) return c;
  while (auto m = reader->next()) {
    const std::string& topic = reader->channels().at(m->channel_id).topic;
    ++c.per_topic[topic];
    if (topic == "/rsp_ecu/rsp/state") c.rsp_states.emplace_back(m->data.begin(), m->data.end());
    if (topic == "/tool_changer/command" && m->publish_time > m->log_time)
      c.commands_source_before_arrival = false;
  }
  c.stop = reader->stop().reason;
  return c;
}

TEST_F(HubdBlackBoxTest, AFaultLatchingWritesTheBlackBoxWithTheFaultInIt) {
  HubProcess hub = start_rsp();
  // The supply pressure goes: the RSP latches a pressure failure (fault) without any command.
  ChildProcess air = hubctl({"send", "/sim/input", "--type", "hub_msgs/msg/SimInput", "hub=rsp_ecu",
                             "signal=main_air", "active=false", "--once", "--timeout", "60"});
  ASSERT_TRUE(air.wait(kPatience));
  const auto faults = files_ending("_fault.mcap");
  ASSERT_EQ(faults.size(), 1U) << hub.output();
  auto source = mcap::open_file(faults.front());
  ASSERT_TRUE(source);
  ASSERT_TRUE(mcap::read_summary(**source)) << "complete, with its summary";
  const Contents contents = read(faults.front());
  ASSERT_FALSE(contents.rsp_states.empty());
  // The last State before the file was written says fault (decoded by Cyclone, as a reader would).
  auto participant =
      dds::Participant::create(dds::DomainConfig{dds::kMaxDomainId, dds::isolated_config_xml()}, "t");
  ASSERT_TRUE(participant);
  const msgs::TypeInfo* type = msgs::all_types().find("hub_msgs/msg/RspState");
  ASSERT_NE(type, nullptr);
  auto codec = dds::CdrCodec::create(*participant, *type->descriptor);
  ASSERT_TRUE(codec);
  dds::UntypedSample state(*type->descriptor);
  ASSERT_TRUE(codec->decode(contents.rsp_states.back(), state.data()));
  const auto json = msgs::to_json(*type, state.data());
  EXPECT_EQ(json["header"]["lifecycle"], 4) << json.dump();  // LIFECYCLE_FAULT
  EXPECT_NE(json.dump().find("pressure failure"), std::string::npos) << json.dump();
}

TEST_F(HubdBlackBoxTest, ARequestWritesItAndASecondWithinTenSecondsIsRefused) {
  HubProcess hub = start_rsp();
  ChildProcess first = hubctl({"blackbox", "rsp_ecu", "--timeout", "60"});
  auto status = first.wait(kPatience);
  ASSERT_TRUE(status);
  EXPECT_TRUE(status->exited_with(0)) << first.stderr_text() << hub.output();
  EXPECT_NE(first.stdout_text().find("written " + dir_.string()), std::string::npos) << first.stdout_text();
  EXPECT_EQ(files_ending("_request.mcap").size(), 1U);
  ChildProcess second = hubctl({"blackbox", "rsp_ecu", "--timeout", "60"});
  auto again = second.wait(kPatience);
  ASSERT_TRUE(again);
  EXPECT_TRUE(again->exited_with(1)) << again->describe();
  EXPECT_NE(second.stderr_text().find("busy"), std::string::npos) << second.stderr_text();
  EXPECT_EQ(files_ending("_request.mcap").size(), 1U);
  // A hub that does not run: said so, nothing written.
  ChildProcess nobody = hubctl({"blackbox", "nobody_here", "--timeout", "1"});
  auto none = nobody.wait(kPatience);
  ASSERT_TRUE(none);
  EXPECT_TRUE(none->exited_with(1)) << nobody.stderr_text();
}

TEST_F(HubdBlackBoxTest, SigtermWritesTheLastMinuteOfCommandsStatesAndDiagnostics) {
  HubProcess hub = start_rsp();
  ChildProcess planner =
      hubctl({"send", "/tool_changer/command", "target_type=tool_changer", "target_name=rsp", "action=lock",
              "gripper=keep", "--rate", "20", "-q", "--timeout", "60"});
  // Until the hub has the planner's commands in force for a while.
  ASSERT_TRUE(hub.process().wait_for_output("operational", kPatience)) << hub.output();
  std::this_thread::sleep_for(seconds(2));
  ASSERT_TRUE(hub.process().signal(SIGTERM));
  auto status = hub.process().wait(kPatience);
  ASSERT_TRUE(status);
  EXPECT_TRUE(status->exited_with(0)) << hub.output();
  const auto files = files_ending("_exit-SIGTERM.mcap", seconds(1));
  ASSERT_EQ(files.size(), 1U) << hub.output();
  const Contents contents = read(files.front());
  EXPECT_EQ(contents.stop, mcap::StopReason::kDataEnd);
  EXPECT_GE(contents.per_topic.at("/tool_changer/command"), 20U);  // 2 s at 20 Hz at least
  EXPECT_GT(contents.per_topic.at("/rsp_ecu/rsp/state"), 10U);
  EXPECT_GT(contents.per_topic.at("/diagnostics"), 0U);
  EXPECT_TRUE(contents.commands_source_before_arrival);
}

TEST_F(HubdBlackBoxTest, ACrashWritesItThroughTheCrashPath) {
  HubProcess hub = start_rsp();
  std::this_thread::sleep_for(seconds(1));
  ASSERT_TRUE(hub.process().signal(SIGSEGV));
  auto status = hub.process().wait(kPatience);
  ASSERT_TRUE(status);
  EXPECT_FALSE(status->exited_with(0)) << status->describe();
  const auto crashes = files_ending("_crash.mcap", seconds(1));
  ASSERT_EQ(crashes.size(), 1U) << hub.output();
  const Contents contents = read(crashes.front());
  EXPECT_EQ(contents.stop, mcap::StopReason::kDataEnd);
  EXPECT_GT(contents.per_topic.count("/rsp_ecu/rsp/state"), 0U);
}

}  // namespace
}  // namespace hubrt::integration
