// hubd's black box (issue 30 point 3) as the process runs it: a fault latching writes a file whose
// last RSP State shows the fault; `hubctl blackbox` writes one on request and a second request
// within 10 s is refused, while a request asked again gets its answer again and hubctl asks again
// when no answer comes; SIGTERM writes the last minute — the planner's commands with their source
// time before their arrival, the States, /diagnostics; a crash (SIGSEGV) writes through the crash
// path a file the linear reader reads.
#include <csignal>
#include <filesystem>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/dds/cdr_codec.h"
#include "hubrt/dds/domain.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/mcap/linear_reader.h"
#include "hubrt/mcap/summary.h"
#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/json.h"
#include "hubrt/test_support/hub_process.h"
#include "hubrt/test_support/hub_under_test.h"

#include "diagnostic_msgs_typed.h"

namespace hubrt::integration {
namespace {

namespace fs = std::filesystem;
using std::chrono::seconds;
using test_support::ChildProcess;
using test_support::HubProcess;
using test_support::HubProcessOptions;
using KeyValue = diagnostic_msgs_msg_dds__KeyValue_;

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

// One end of the black box's request and answer, made by the test: it reads `read_topic` and
// writes `write_topic` (the hub's ends swapped for a client, as they are for a fake hub).
class KeyValueEnd {
 public:
  static std::unique_ptr<KeyValueEnd> open(const test_support::TestDomain& domain,
                                           const std::string& read_topic, const std::string& write_topic) {
    auto participant = dds::Participant::create(domain.config(), "blackbox_test");
    if (!participant) return nullptr;
    auto in = dds::Topic<KeyValue>::create(*participant, read_topic);
    auto out = dds::Topic<KeyValue>::create(*participant, write_topic);
    if (!in || !out) return nullptr;
    auto reader = dds::Reader<KeyValue>::create(*participant, *in, dds::Qos::ros2_default(100));
    auto writer = dds::Writer<KeyValue>::create(*participant, *out);
    if (!reader || !writer) return nullptr;
    return std::unique_ptr<KeyValueEnd>(new KeyValueEnd(
        std::move(*participant), std::move(*in), std::move(*reader), std::move(*out), std::move(*writer)));
  }

  // Until the other end's reader and writer are matched with ours.
  bool matched() {
    return in_.reader().wait_for_writers(1, kPatience) && writer_.wait_for_readers(1, kPatience);
  }
  bool write(const std::string& key, const std::string& value) {
    dds::Sample<KeyValue> sample;
    sample->key = dds_string_dup(key.c_str());
    sample->value = dds_string_dup(value.c_str());
    return writer_.write(*sample).is_ok();
  }
  // The next {key, value} that comes within `wait`.
  std::optional<std::pair<std::string, std::string>> next(Duration wait) {
    if (!in_.take_any(wait)) return std::nullopt;
    const KeyValue& got = in_.latest();
    return std::pair<std::string, std::string>(got.key != nullptr ? got.key : "",
                                               got.value != nullptr ? got.value : "");
  }

 private:
  KeyValueEnd(dds::Participant participant, dds::Topic<KeyValue> in_topic, dds::Reader<KeyValue> reader,
              dds::Topic<KeyValue> out_topic, dds::Writer<KeyValue> writer)
      : participant_(std::move(participant)),
        in_(std::move(in_topic), std::move(reader)),
        out_topic_(std::move(out_topic)),
        writer_(std::move(writer)) {}
  dds::Participant participant_;  // first made, last gone
  test_support::StateStream<KeyValue> in_;
  dds::Topic<KeyValue> out_topic_;
  dds::Writer<KeyValue> writer_;
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

TEST_F(HubdBlackBoxTest, ARequestAskedAgainGetsItsAnswerAgainNotASecondFile) {
  HubProcess hub = start_rsp();
  auto client = KeyValueEnd::open(*domain_, "/rsp_ecu/blackbox/written", "/rsp_ecu/blackbox/request");
  ASSERT_TRUE(client);
  ASSERT_TRUE(client->matched()) << hub.output();
  // As hubctl asks: again every second until an answer comes (the first may be lost on the way).
  std::vector<std::string> answers;
  for (int attempt = 0; attempt < 60 && answers.empty(); ++attempt) {
    ASSERT_TRUE(client->write("same-id", "the test"));
    while (auto reply = client->next(seconds(1))) answers.push_back(reply->second);
  }
  ASSERT_FALSE(answers.empty()) << hub.output();
  const std::string first = answers.front();
  EXPECT_TRUE(first.starts_with("written " + dir_.string())) << first;
  // Asked again well within the 10 s between files: the same answer, not "busy".
  ASSERT_TRUE(client->write("same-id", "the test"));
  const std::size_t before = answers.size();
  while (auto reply = client->next(seconds(3))) answers.push_back(reply->second);
  ASSERT_GT(answers.size(), before) << "no answer to the request asked again";
  for (const std::string& answer : answers) EXPECT_EQ(answer, first);
  // Another request within the 10 s is still refused.
  ASSERT_TRUE(client->write("another-id", "the test"));
  auto other = client->next(kPatience);
  ASSERT_TRUE(other);
  EXPECT_EQ(other->first, "another-id");
  EXPECT_TRUE(other->second.starts_with("busy")) << other->second;
  EXPECT_EQ(files_ending("_request.mcap").size(), 1U);
}

// A fake hub that never answers the first request: hubctl asks again, with the same id, and
// prints the answer to the second.
TEST_F(HubdBlackBoxTest, HubctlAsksAgainWhenNoAnswerComes) {
  auto fake_hub = KeyValueEnd::open(*domain_, "/fake_ecu/blackbox/request", "/fake_ecu/blackbox/written");
  ASSERT_TRUE(fake_hub);
  ChildProcess asking = hubctl({"blackbox", "fake_ecu", "--timeout", "60"});
  auto first = fake_hub->next(kPatience);
  ASSERT_TRUE(first) << asking.stderr_text();
  auto second = fake_hub->next(seconds(30));
  ASSERT_TRUE(second) << "hubctl did not ask again; " << asking.stderr_text();
  EXPECT_EQ(second->first, first->first) << "asked again with another id";
  ASSERT_TRUE(fake_hub->write(second->first, "written /fake/black_box.mcap (1 bytes, 0 messages, 0.0 s)"));
  auto status = asking.wait(kPatience);
  ASSERT_TRUE(status);
  EXPECT_TRUE(status->exited_with(0)) << asking.stderr_text();
  EXPECT_NE(asking.stdout_text().find("written /fake/black_box.mcap"), std::string::npos)
      << asking.stdout_text();
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
