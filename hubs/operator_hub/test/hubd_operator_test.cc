// The real hubd on the fake backend with the hub's test board (boards/host-sim-operator-hub.yaml) and the
// test allow-list, in the test's own DDS domain on loopback, commanded like a planner: a badge
// shown through /sim/badge verifies its operator, an unknown one is rejected, the button (through
// /sim/input) and the screen's confirm topic increment the press sequence, the watchdog logs the
// operator out, and no badge appears in hubd's output. Also: the rpi4 board passes hubd --check,
// and operator-enrol puts a badge on a list as a hash only.
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/runtime/lifecycle.h"
#include "hubrt/test_support/child_process.h"

#include "allow_list.h"
#include "hub_process.h"
#include "operator_messages.h"

namespace hubrt::operator_hub {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

// Generous: a busy 2-core machine running sanitizer builds in parallel; the test checks
// behaviour, not timing.
constexpr auto kPatience = seconds(20);
const std::string kDir = HUBRT_OPERATOR_HUB_DIR;
constexpr std::string_view kAnnaBadge = "0004123456";

hub_msgs::OperatorPanelStateView view(const OperatorPanelState& state) {
  return hub_msgs::OperatorPanelStateView(state);
}

// The shipped hub file with the test allow-list (absolute: the copy lives elsewhere).
std::string test_hub_file(std::string_view layout) {
  std::ifstream in(kDir + "/operator_hub.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto list = text.find("allow_list: operators.list");
  text.replace(list, 26, "allow_list: " + kDir + "/test/operators.list");
  const auto at = text.find("layout: node_type");
  text.replace(at, 17, "layout: " + std::string(layout));
  const auto path =
      std::filesystem::path(::testing::TempDir()) / ("operator_hub-" + std::string(layout) + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}

class HubdOperatorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "test-planner");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    // The node-type layout's topics (operator_hub.yaml).
    auto command_topic = dds::Topic<OperatorPanelCommand>::create(*participant_, "/operator_panel/command");
    ASSERT_TRUE(command_topic) << command_topic.error().message;
    command_topic_.emplace(std::move(*command_topic));
    auto writer = dds::Writer<OperatorPanelCommand>::create(*participant_, *command_topic_);
    ASSERT_TRUE(writer) << writer.error().message;
    command_writer_.emplace(std::move(*writer));
    auto state_topic = dds::Topic<OperatorPanelState>::create(*participant_, "/operator_hub/panel/state");
    ASSERT_TRUE(state_topic) << state_topic.error().message;
    state_topic_.emplace(std::move(*state_topic));
    auto reader = dds::Reader<OperatorPanelState>::create(*participant_, *state_topic_);
    ASSERT_TRUE(reader) << reader.error().message;
    state_reader_.emplace(std::move(*reader));

    integration::HubProcessOptions options;
    options.board = kDir + "/../../boards/host-sim-operator-hub.yaml";
    options.hub = test_hub_file("node_type");
    auto hub = integration::HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(state_reader_->wait_for_writers(1, kPatience)) << hub_->output();
    ASSERT_TRUE(command_writer_->wait_for_readers(1, kPatience)) << hub_->output();
  }

  void TearDown() override { stop_planner(); }

  bool wait_for_state(const std::function<bool(const OperatorPanelState&)>& predicate) {
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    while (std::chrono::steady_clock::now() < deadline) {
      const Result<bool> taken = state_reader_->take_next(state_);
      if (taken.is_ok() && taken.value()) {
        if (predicate(state_.get())) return true;
        continue;
      }
      std::this_thread::sleep_for(milliseconds(2));
    }
    return false;
  }

  // `hubctl send <topic> <fields> --once`: what a person, a script or the screen does.
  void hubctl_send(const std::vector<std::string>& args) {
    std::vector<std::string> all{"send"};
    all.insert(all.end(), args.begin(), args.end());
    for (std::string_view extra : {"--once", "--wait", "1", "--quiet"}) all.emplace_back(extra);
    auto send = test_support::ChildProcess::start(HUBRT_HUBCTL_PATH, all, domain_->env());
    ASSERT_TRUE(send) << send.error().message;
    auto status = send->wait(kPatience);
    ASSERT_TRUE(status) << status.error().message;
    ASSERT_TRUE(status->exited_with(0)) << status->describe() << "\n" << send->stderr_text();
  }
  void show_badge(std::string_view text) {
    hubctl_send({"/sim/badge", "hub=operator_hub", "reader=operator_rfid", "text=" + std::string(text)});
  }
  void set_button(bool pressed) {
    hubctl_send({"/sim/input", "hub=operator_hub", "signal=operator.confirm",
                 std::string("active=") + (pressed ? "true" : "false")});
  }

  // Like the planner: the wanted command, repeated every 50 ms (the timeout is 1 s).
  void command(std::string_view action) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      action_ = action;
      planning_ = true;
    }
    if (planner_.joinable()) return;
    planner_ = std::thread([this] {
      for (;;) {
        hub_msgs::OperatorPanelCommand c;
        {
          const std::lock_guard<std::mutex> lock(mutex_);
          if (!planning_) return;
          c.set_action(action_);
        }
        c.set_target_type("operator_panel");
        c.set_target_name("panel");
        if (!command_writer_->write(c.wire()).is_ok()) return;
        std::this_thread::sleep_for(milliseconds(50));
      }
    });
  }
  void stop_planner() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      planning_ = false;
    }
    if (planner_.joinable()) planner_.join();
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<OperatorPanelCommand>> command_topic_;
  std::optional<dds::Writer<OperatorPanelCommand>> command_writer_;
  std::optional<dds::Topic<OperatorPanelState>> state_topic_;
  std::optional<dds::Reader<OperatorPanelState>> state_reader_;
  dds::Sample<OperatorPanelState> state_;
  std::optional<integration::HubProcess> hub_;
  std::mutex mutex_;  // guards action_ and planning_, shared with the planner thread
  std::string action_;
  bool planning_ = false;
  std::thread planner_;
};

TEST_F(HubdOperatorTest, VerifiesByBadgeCountsPressesAndLogsOutWhenCommandsStop) {
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) { return view(s).reader_open(); }))
      << hub_->output();
  EXPECT_FALSE(view(state_.get()).operator_verified());
  EXPECT_EQ(view(state_.get()).name(), "panel");

  command("verify");
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) { return view(s).fresh_msg(); }));
  show_badge(kAnnaBadge);
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) {
    return view(s).operator_verified() && view(s).operator_name() == "Anna Svensson";
  })) << hub_->output();
  EXPECT_EQ(view(state_.get()).last_badge(), "accepted");
  EXPECT_EQ(view(state_.get()).last_badge_tag(), "9ad4c64a");

  show_badge("0004123457");
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) { return view(s).badge_reads() == 2; }));
  EXPECT_EQ(view(state_.get()).last_badge(), "rejected");
  EXPECT_EQ(view(state_.get()).last_badge_reason(), "unknown badge");
  EXPECT_EQ(view(state_.get()).operator_name(), "Anna Svensson");

  // The button: pressed (held past its debounce: the press is seen before the release is sent).
  set_button(true);
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) { return view(s).confirm_seq() == 1; }))
      << hub_->output();
  EXPECT_EQ(view(state_.get()).confirm_source(), "button");
  set_button(false);

  // The screen's "done" button.
  hubctl_send({"/operator_hub/operator/screen_confirm", "source=screen", "press_id=1", "--type",
               "hub_msgs/msg/OperatorConfirm"});
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) { return view(s).confirm_seq() == 2; }))
      << hub_->output();
  EXPECT_EQ(view(state_.get()).confirm_source(), "screen");

  // The planner stops: the watchdog logs the operator out.
  stop_planner();
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) {
    return !view(s).fresh_msg() && !view(s).operator_verified();
  })) << hub_->output();
  EXPECT_EQ(view(state_.get()).confirm_seq(), 2U);

  ASSERT_TRUE(hub_->process().signal(SIGTERM));
  auto status = hub_->process().wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << hub_->output();
  // No badge in clear in anything hubd wrote.
  EXPECT_EQ(hub_->output().find("000412345"), std::string::npos) << hub_->output();
}

TEST_F(HubdOperatorTest, AMalformedBadgeIsRejectedWithItsReason) {
  command("verify");
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) { return view(s).fresh_msg(); }));
  show_badge(std::string(40, '7'));
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) { return view(s).badge_reads() == 1; }));
  EXPECT_EQ(view(state_.get()).last_badge(), "rejected");
  EXPECT_EQ(view(state_.get()).last_badge_reason(), "malformed: too long");
  EXPECT_FALSE(view(state_.get()).operator_verified());
}

TEST(OperatorBoardTest, TheRpi4BoardPassesHubdCheck) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  auto finished = integration::run_hubd(
      *domain, {"--board", "rpi4-operator-hub", "--hub", "operator_hub", "--check"}, seconds(60));
  ASSERT_TRUE(finished) << finished.error().message;
  EXPECT_TRUE(finished->status.exited_with(0)) << finished->status.describe() << "\n" << finished->output;
}

TEST(OperatorBoardTest, CheckReportsAnAllowListMistakeWithItsLine) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  const auto dir = std::filesystem::path(::testing::TempDir()) / "operator-check";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "operators.list") << "salt 000102030405060708090a0b0c0d0e0f\n0004123456 Anna\n";
  std::ifstream in(kDir + "/operator_hub.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir / "operator_hub.yaml") << text;
  auto finished = integration::run_hubd(*domain,
                                        {"--board", kDir + "/../../boards/host-sim-operator-hub.yaml",
                                         "--hub", (dir / "operator_hub.yaml").string(), "--check"},
                                        seconds(60));
  ASSERT_TRUE(finished) << finished.error().message;
  EXPECT_FALSE(finished->status.exited_with(0)) << finished->output;
  EXPECT_NE(finished->output.find("operators.list:2: expected '<SHA-256 in hex (64 digits)> <name>'"),
            std::string::npos)
      << finished->output;
}

TEST(OperatorEnrolTest, AddsAnOperatorAsAHashOnly) {
  const auto file = std::filesystem::path(::testing::TempDir()) / "enrolled.list";
  std::filesystem::remove(file);
  // The tool reads the badge from stdin, so it runs through popen rather than ChildProcess (whose
  // stdin is /dev/null); in a cross build the target's emulator goes in front, as ChildProcess does.
  std::string command;
  for (const std::string& word : test_support::target_emulator()) command += word + " ";
  command += std::string(HUBRT_OPERATOR_ENROL_PATH) + " add " + file.string() + " 'Cecilia Lind' 2>&1";
  FILE* enrol = ::popen(command.c_str(), "w");
  ASSERT_NE(enrol, nullptr);
  std::fputs("77001234\n", enrol);
  ASSERT_EQ(::pclose(enrol), 0);
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("77001234"), std::string::npos) << text;
  EXPECT_EQ(std::filesystem::status(file).permissions() & std::filesystem::perms::others_read,
            std::filesystem::perms::none);
  // ... and the hub's group (hubrt on a board) reads it: 0640, not the creator's umask.
  EXPECT_EQ(std::filesystem::status(file).permissions() & std::filesystem::perms::all,
            std::filesystem::perms::owner_read | std::filesystem::perms::owner_write |
                std::filesystem::perms::group_read);
  auto list = AllowList::load(file.string());
  ASSERT_TRUE(list) << list.error().message;
  ASSERT_EQ(list->operators().size(), 1U);
  auto hasher = BadgeHasher::create();
  ASSERT_TRUE(hasher);
  BadgeDigest digest{};
  ASSERT_TRUE(hasher->hash(list->salt(), "77001234", digest));
  const AllowedOperator* found = list->find(digest);
  ASSERT_NE(found, nullptr);
  EXPECT_EQ(found->name, "Cecilia Lind");
  // The same badge again is refused.
  FILE* again = ::popen(command.c_str(), "w");
  ASSERT_NE(again, nullptr);
  std::fputs("77001234\n", again);
  EXPECT_NE(::pclose(again), 0);
}

}  // namespace
}  // namespace hubrt::operator_hub
