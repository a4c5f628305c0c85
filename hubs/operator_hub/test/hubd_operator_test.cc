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
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/hub_under_test.h"

#include "allow_list.h"
#include "operator_messages.h"

namespace hubrt::operator_hub {
namespace {

using std::chrono::seconds;
using test_support::HubUnderTest;
using test_support::StateStream;

// Generous: a busy 2-core machine running sanitizer builds in parallel; the test checks
// behaviour, not timing.
constexpr auto kPatience = seconds(20);
const std::string kDir = HUBRT_OPERATOR_HUB_DIR;
constexpr std::string_view kAnnaBadge = "0004123456";

hub_msgs::OperatorPanelStateView view(const OperatorPanelState& state) {
  return hub_msgs::OperatorPanelStateView(state);
}

class HubdOperatorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NO_FATAL_FAILURE(hub_.open());
    // The node-type layout's topics (operator_hub.yaml).
    ASSERT_NO_FATAL_FAILURE(hub_.make_writer(commands_, "/operator_panel/command"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_stream(states_, "/operator_hub/panel/state"));
    // The shipped hub file with the test allow-list (absolute: the copy lives elsewhere).
    const std::string hub_file =
        hub_.hub_file("operator_hub", "node_type",
                      {{"allow_list: operators.list", "allow_list: " + kDir + "/test/operators.list"}});
    ASSERT_NO_FATAL_FAILURE(
        hub_.start({.board = kDir + "/../../boards/host-sim-operator-hub.yaml", .hub = hub_file}));
  }

  ::testing::AssertionResult wait_for_state(const std::function<bool(const OperatorPanelState&)>& predicate,
                                            std::string_view what) {
    return hub_.wait_for(*states_, predicate, what);
  }
  const OperatorPanelState& state() const { return states_->latest(); }

  // `hubctl send <topic> <fields> --once`: what a person, a script or the screen does.
  void hubctl_send(const std::vector<std::string>& args) {
    std::vector<std::string> all{"send"};
    all.insert(all.end(), args.begin(), args.end());
    for (std::string_view extra : {"--once", "--wait", "1", "--quiet"}) all.emplace_back(extra);
    auto send = test_support::ChildProcess::start(HUBRT_HUBCTL_PATH, all, hub_.domain().env());
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
    hub_msgs::OperatorPanelCommand c;
    c.set_action(action);
    c.set_target_type("operator_panel");
    c.set_target_name("panel");
    hub_.plan(*commands_, c.wire());
  }

  dds::Writer<OperatorPanelCommand>* commands_ = nullptr;
  StateStream<OperatorPanelState>* states_ = nullptr;
  HubUnderTest hub_{kPatience};
};

TEST_F(HubdOperatorTest, VerifiesByBadgeCountsPressesAndLogsOutWhenCommandsStop) {
  ASSERT_TRUE(
      wait_for_state([](const OperatorPanelState& s) { return view(s).reader_open(); }, "reader open"));
  EXPECT_FALSE(view(state()).operator_verified());
  EXPECT_EQ(view(state()).name(), "panel");

  command("verify");
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) { return view(s).fresh_msg(); }, "fresh"));
  show_badge(kAnnaBadge);
  ASSERT_TRUE(wait_for_state(
      [](const OperatorPanelState& s) {
        return view(s).operator_verified() && view(s).operator_name() == "Anna Svensson";
      },
      "Anna Svensson verified"));
  EXPECT_EQ(view(state()).last_badge(), "accepted");
  EXPECT_EQ(view(state()).last_badge_tag(), "9ad4c64a");

  show_badge("0004123457");
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) { return view(s).badge_reads() == 2; },
                             "2 badge reads"));
  EXPECT_EQ(view(state()).last_badge(), "rejected");
  EXPECT_EQ(view(state()).last_badge_reason(), "unknown badge");
  EXPECT_EQ(view(state()).operator_name(), "Anna Svensson");

  // The button: pressed (held past its debounce: the press is seen before the release is sent).
  set_button(true);
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) { return view(s).confirm_seq() == 1; },
                             "confirm_seq 1"));
  EXPECT_EQ(view(state()).confirm_source(), "button");
  set_button(false);

  // The screen's "done" button.
  hubctl_send({"/operator_hub/operator/screen_confirm", "source=screen", "press_id=1", "--type",
               "hub_msgs/msg/OperatorConfirm"});
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) { return view(s).confirm_seq() == 2; },
                             "confirm_seq 2"));
  EXPECT_EQ(view(state()).confirm_source(), "screen");

  // The planner stops: the watchdog logs the operator out.
  hub_.stop_planner();
  ASSERT_TRUE(wait_for_state(
      [](const OperatorPanelState& s) { return !view(s).fresh_msg() && !view(s).operator_verified(); },
      "not fresh, logged out"));
  EXPECT_EQ(view(state()).confirm_seq(), 2U);

  ASSERT_TRUE(hub_.hub().process().signal(SIGTERM));
  auto status = hub_.hub().process().wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << hub_.output();
  // No badge in clear in anything hubd wrote.
  EXPECT_EQ(hub_.output().find("000412345"), std::string::npos) << hub_.output();
}

TEST_F(HubdOperatorTest, AMalformedBadgeIsRejectedWithItsReason) {
  command("verify");
  ASSERT_TRUE(wait_for_state([](const OperatorPanelState& s) { return view(s).fresh_msg(); }, "fresh"));
  show_badge(std::string(40, '7'));
  ASSERT_TRUE(
      wait_for_state([](const OperatorPanelState& s) { return view(s).badge_reads() == 1; }, "1 badge read"));
  EXPECT_EQ(view(state()).last_badge(), "rejected");
  EXPECT_EQ(view(state()).last_badge_reason(), "malformed: too long");
  EXPECT_FALSE(view(state()).operator_verified());
}

TEST(OperatorBoardTest, TheRpi4BoardPassesHubdCheck) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  auto finished = test_support::run_hubd(
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
  auto finished = test_support::run_hubd(*domain,
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
