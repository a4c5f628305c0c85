#include "hubrt/runtime/node.h"

#include <string>

#include <gtest/gtest.h>

#include "hubrt/runtime/reflected_message_ops.h"

#include "node_test_support.h"
#include "valve_test_reflect.h"

namespace hubrt::runtime::testing {
namespace {

using std::chrono::milliseconds;

std::string str(const char* s) {
  return s == nullptr ? std::string("<null>") : std::string(s);
}

std::vector<std::string> error_list(const ValveState& state) {
  std::vector<std::string> out;
  for (std::uint32_t i = 0; i < state.error_list._length; ++i) out.emplace_back(state.error_list._buffer[i]);
  return out;
}

bool has_error(const ValveState& state, const std::string& fragment) {
  for (const auto& e : error_list(state)) {
    if (e.find(fragment) != std::string::npos) return true;
  }
  return false;
}

class NodeTest : public ::testing::Test {
 protected:
  NodeTest() { make_node(Addressing::kIgnoreOthers); }

  void make_node(Addressing addressing) {
    NodeOptions options;
    options.name = "v1";
    options.command_timeout = milliseconds(500);
    options.addressing = addressing;
    node_ = std::make_unique<Node<ValveLogic>>(options, ValveLogic(world_), source_, sink_, ops_);
  }
  bool step() { return node_->step(clock_.now()); }
  void step_and_publish() {
    step();
    ASSERT_TRUE(node_->publish(clock_.now()).is_ok());
  }
  const ValveState& state() const { return node_->state().wire(); }

  ManualClock clock_;
  ValveWorld world_;
  QueueSource source_;
  CountingSink sink_;
  ReflectedMessageOps ops_{msgs::type_info_of<ValveCommand>()};
  std::unique_ptr<Node<ValveLogic>> node_;
};

TEST_F(NodeTest, BeforeAnyCommandTheNodeIsSafeAndNotFresh) {
  EXPECT_FALSE(step());
  EXPECT_FALSE(state().fresh_msg);
  EXPECT_FLOAT_EQ(state().t_plus, 0.0f);
  EXPECT_FALSE(state().got_reset);
  EXPECT_EQ(state().error_list._length, 0u) << "waiting for the first command is not an error";
  EXPECT_EQ(str(state().name), "v1");
  EXPECT_EQ(world_.updates_without_command, 1);
  EXPECT_FALSE(world_.open);
}

TEST_F(NodeTest, HubAlertsComeFirstInTheErrorListWhileTheyLast) {
  HubAlerts alerts;
  node_->watch_alerts(&alerts);
  step();
  EXPECT_EQ(state().error_list._length, 0u);

  alerts.add("twin: another hub publishes {} from host {} pid {}", "/hub/v1/state", "pi", 42);
  step();
  ASSERT_EQ(error_list(state()),
            std::vector<std::string>{"twin: another hub publishes /hub/v1/state from host pi pid 42"});
  EXPECT_EQ(node_->first_error(), "twin: another hub publishes /hub/v1/state from host pi pid 42");
  EXPECT_EQ(node_->health(), Health::kError);

  alerts.clear();
  step();
  EXPECT_EQ(state().error_list._length, 0u);
}

TEST_F(NodeTest, AValidCommandTakesEffectAndIsEchoedVerbatim) {
  OwnedValveCommand command;
  command.tags = {"bolt-7", "ånd ütf8"};
  source_.push(command);
  EXPECT_TRUE(step()) << "a command taking effect asks for an immediate publish";
  EXPECT_TRUE(world_.open);
  EXPECT_TRUE(state().fresh_msg);
  EXPECT_EQ(str(state().echo.target_type), "valve");
  EXPECT_EQ(str(state().echo.target_name), "v1");
  EXPECT_EQ(str(state().echo.action), "open");
  EXPECT_FLOAT_EQ(state().echo.pressure_bar, 2.5f);
  ASSERT_EQ(state().echo.tags._length, 2u);
  EXPECT_EQ(str(state().echo.tags._buffer[1]), "ånd ütf8");
  EXPECT_EQ(state().error_list._length, 0u);
}

TEST_F(NodeTest, TheEchoIsACopyNotAPointerIntoTheReceivedSample) {
  source_.push(OwnedValveCommand{});
  step();
  // The source reuses its sample for the next take; the echo must not change with it.
  OwnedValveCommand other;
  other.target_name = "v2";
  other.action = "close";
  source_.push(other);
  step();
  EXPECT_EQ(str(state().echo.action), "open");
}

TEST_F(NodeTest, RepeatsKeepTPlusRunningAndDoNotRepublish) {
  source_.push(OwnedValveCommand{});
  EXPECT_TRUE(step());
  for (int i = 0; i < 5; ++i) {
    clock_.advance(milliseconds(100));
    source_.push(OwnedValveCommand{});
    EXPECT_FALSE(step()) << "an identical repeat only feeds the watchdog";
  }
  EXPECT_NEAR(state().t_plus, 0.5f, 1e-6);
  EXPECT_TRUE(state().fresh_msg);
  OwnedValveCommand changed;
  changed.pressure_bar = 3.0f;
  source_.push(changed);
  EXPECT_TRUE(step());
  EXPECT_FLOAT_EQ(state().t_plus, 0.0f);
  EXPECT_FLOAT_EQ(state().echo.pressure_bar, 3.0f);
}

TEST_F(NodeTest, TheLatestValidCommandInOneDrainWins) {
  OwnedValveCommand a;
  a.action = "close";
  OwnedValveCommand b;
  b.pressure_bar = 7.0f;
  OwnedValveCommand bad;
  bad.action = "explode";
  source_.push(a);
  source_.push(b);
  source_.push(bad);
  EXPECT_TRUE(step());
  EXPECT_EQ(source_.pending(), 0u);
  EXPECT_EQ(str(state().echo.action), "open");
  EXPECT_FLOAT_EQ(state().echo.pressure_bar, 7.0f);
  EXPECT_EQ(world_.updates_with_command, 1) << "logic runs once per step, on the latest";
  EXPECT_TRUE(has_error(state(), "unknown action 'explode'"));
}

TEST_F(NodeTest, WatchdogDrivesTheSafeStateAndReportsIt) {
  source_.push(OwnedValveCommand{});
  step();
  ASSERT_TRUE(world_.open);
  clock_.advance(milliseconds(500));
  step();
  EXPECT_TRUE(world_.open) << "still within the timeout";
  EXPECT_TRUE(state().fresh_msg);
  clock_.advance(milliseconds(1));
  step();
  EXPECT_FALSE(world_.open) << "outputs go to the safe state";
  EXPECT_FALSE(state().fresh_msg);
  EXPECT_TRUE(has_error(state(), "command timeout"));
  EXPECT_EQ(str(state().echo.action), "open") << "the echo keeps showing the last command received";
  EXPECT_EQ(node_->health(), Health::kStale);
}

TEST_F(NodeTest, AStaleCommandIsNeverReapplied) {
  source_.push(OwnedValveCommand{});
  step();
  clock_.advance(milliseconds(600));
  step();
  ASSERT_FALSE(world_.open);
  const int with_command_before = world_.updates_with_command;
  // Time passing, rejected commands and commands for other nodes do not revive it.
  for (int i = 0; i < 10; ++i) {
    clock_.advance(milliseconds(100));
    OwnedValveCommand bad;
    bad.action = "opne";
    source_.push(bad);
    OwnedValveCommand other;
    other.target_name = "v2";
    source_.push(other);
    step();
    EXPECT_FALSE(world_.open);
  }
  EXPECT_EQ(world_.updates_with_command, with_command_before);
  EXPECT_FALSE(state().fresh_msg);
  // Only a command that arrives now acts, even with the same content.
  source_.push(OwnedValveCommand{});
  EXPECT_TRUE(step());
  EXPECT_TRUE(world_.open);
  EXPECT_TRUE(state().fresh_msg);
  EXPECT_FLOAT_EQ(state().t_plus, 0.0f);
  EXPECT_FALSE(has_error(state(), "command timeout"));
}

struct BadCommandCase {
  const char* what;
  OwnedValveCommand command;
  const char* expected_error;
};

std::vector<BadCommandCase> bad_commands() {
  std::vector<BadCommandCase> cases;
  auto add = [&](const char* what, auto mutate, const char* expected) {
    OwnedValveCommand c;
    mutate(c);
    cases.push_back({what, c, expected});
  };
  add(
      "unknown action", [](auto& c) { c.action = "vent"; },
      "rejected command: unknown action 'vent' (expected one of: open, close, reset)");
  add(
      "wrong target type", [](auto& c) { c.target_type = "lift"; },
      "rejected command: wrong target type 'lift' for node 'v1' of type 'valve'");
  add(
      "over-long action", [](auto& c) { c.action = std::string(65, 'o'); },
      "rejected command: field 'action' is too long (limit 64 bytes of UTF-8 text)");
  add(
      "over-long tag",
      [](auto& c) {
        c.tags = {"ok", std::string(200, 't')};
      },
      "rejected command: field 'tags[1]' is too long (limit 64 bytes of UTF-8 text)");
  add(
      "control character", [](auto& c) { c.action = "op\x1b[2Jen"; },
      "rejected command: field 'action' contains a control character: 'op\\x1B[2Jen' (limit 64 bytes of "
      "UTF-8 "
      "text)");
  add(
      "invalid UTF-8", [](auto& c) { c.target_type = "val\xc3(ve"; },
      "rejected command: field 'target_type' is not valid UTF-8: 'val\\xC3(ve' (limit 64 bytes of UTF-8 "
      "text)");
  add(
      "encoded surrogate (issue 11: it used to pass and be quoted raw as an unknown action)",
      [](auto& c) {
        c.action =
            "op\xed\xa0\x80"
            "en";
      },
      "rejected command: field 'action' is not valid UTF-8: 'op\\xED\\xA0\\x80en' (limit 64 bytes of UTF-8 "
      "text)");
  add(
      "encoded surrogate in a sequence",
      [](auto& c) {
        c.tags = {"ok", "\xed\xbf\xbf"};
      },
      "rejected command: field 'tags[1]' is not valid UTF-8: '\\xED\\xBF\\xBF' (limit 64 bytes of UTF-8 "
      "text)");
  add(
      "out of range value", [](auto& c) { c.pressure_bar = 12.5f; },
      "rejected command: pressure_bar 12.5 is out of range [0, 10]");
  add(
      "NaN value", [](auto& c) { c.pressure_bar = std::numeric_limits<float>::quiet_NaN(); },
      "rejected command: field 'pressure_bar' is not a finite number (nan)");
  add(
      "infinite value", [](auto& c) { c.pressure_bar = -std::numeric_limits<float>::infinity(); },
      "rejected command: field 'pressure_bar' is not a finite number (-inf)");
  return cases;
}

TEST_F(NodeTest, BadCommandsAreRejectedWithAReasonAndNothingActuated) {
  for (const BadCommandCase& bad : bad_commands()) {
    SCOPED_TRACE(bad.what);
    world_ = ValveWorld{};
    make_node(Addressing::kIgnoreOthers);
    // In force: "close". The bad command must not open the valve, nor change the echo.
    OwnedValveCommand close;
    close.action = "close";
    source_.push(close);
    step();
    source_.push(bad.command);
    EXPECT_FALSE(step());
    EXPECT_FALSE(world_.open);
    EXPECT_EQ(world_.last_action, "close");
    EXPECT_EQ(str(state().echo.action), "close");
    EXPECT_EQ(node_->rejected(), 1u);
    const auto errors = error_list(state());
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0], bad.expected_error);
  }
}

TEST_F(NodeTest, ABadCommandFirstLeavesTheNodeSafe) {
  OwnedValveCommand bad;
  bad.pressure_bar = -1.0f;
  source_.push(bad);
  EXPECT_FALSE(step());
  EXPECT_FALSE(world_.open);
  EXPECT_EQ(world_.updates_with_command, 0);
  EXPECT_FALSE(state().fresh_msg);
}

TEST_F(NodeTest, ARejectionStaysVisibleForOneTimeoutThenClears) {
  source_.push(OwnedValveCommand{});
  step();
  OwnedValveCommand bad;
  bad.action = "vent";
  source_.push(bad);
  step();
  for (int i = 0; i < 4; ++i) {  // the planner keeps its valid command coming
    clock_.advance(milliseconds(100));
    source_.push(OwnedValveCommand{});
    step();
    EXPECT_TRUE(has_error(state(), "unknown action 'vent'"));
  }
  clock_.advance(milliseconds(101));
  source_.push(OwnedValveCommand{});
  step();
  EXPECT_FALSE(has_error(state(), "vent")) << "gone after the command timeout";
  EXPECT_TRUE(world_.open);
}

TEST_F(NodeTest, CommandsForOtherNodesAreIgnoredOnASharedTopic) {
  OwnedValveCommand other;
  other.target_name = "v2";
  source_.push(other);
  EXPECT_FALSE(step());
  EXPECT_EQ(node_->rejected(), 0u);
  EXPECT_EQ(state().error_list._length, 0u);
  EXPECT_FALSE(world_.open);
}

TEST_F(NodeTest, CommandsForOtherNodesAreRejectedWhenRoutedHere) {
  make_node(Addressing::kRejectOthers);
  OwnedValveCommand other;
  other.target_name = "v2";
  source_.push(other);
  EXPECT_FALSE(step());
  EXPECT_EQ(node_->rejected(), 1u);
  EXPECT_TRUE(has_error(state(), "wrong target: addressed to 'v2', this node is 'v1'"));
  EXPECT_FALSE(world_.open);
}

TEST_F(NodeTest, ResetClearsLatchedFaultsOnceAndIsReported) {
  world_.overpressure_input = true;
  source_.push(OwnedValveCommand{});
  step();
  world_.overpressure_input = false;
  step();
  EXPECT_FALSE(world_.open) << "latched fault holds the valve closed";
  EXPECT_TRUE(has_error(state(), "overpressure"));
  OwnedValveCommand reset;
  reset.action = "reset";
  source_.push(reset);
  EXPECT_TRUE(step());
  EXPECT_EQ(world_.resets, 1);
  EXPECT_TRUE(state().got_reset);
  EXPECT_FALSE(has_error(state(), "overpressure"));
  // The fault comes back while the planner still sends reset: it stays visible.
  world_.overpressure_input = true;
  source_.push(reset);
  step();
  EXPECT_EQ(world_.resets, 1) << "a repeated reset does not act again";
  EXPECT_TRUE(has_error(state(), "overpressure"));
  world_.overpressure_input = false;
  source_.push(OwnedValveCommand{});
  step();
  EXPECT_FALSE(state().got_reset);
  EXPECT_FALSE(world_.open) << "still latched: it returned after the reset";
}

TEST_F(NodeTest, PublishStampsASequenceAndTheWallTime) {
  step_and_publish();
  step_and_publish();
  EXPECT_EQ(sink_.count, 2u);
  EXPECT_EQ(sink_.last_seq, 2u);
  EXPECT_EQ(sink_.last_sec, clock_.now().wall.ns_since_epoch / 1'000'000'000);
  EXPECT_EQ(node_->published(), 2u);
}

TEST_F(NodeTest, ACommandTooLargeToHoldIsRejectedAndTheEchoKept) {
  source_.push(OwnedValveCommand{});
  step();
  OwnedValveCommand huge;
  huge.action = "close";
  huge.tags.assign(100, std::string(60, 'x'));  // 6 kB of valid strings, more than the echo holds
  source_.push(huge);
  EXPECT_FALSE(step());
  EXPECT_TRUE(has_error(state(), "too large"));
  EXPECT_EQ(str(state().echo.action), "open");
  EXPECT_TRUE(world_.open);
}

TEST_F(NodeTest, ATransportErrorIsLoggedAndTheCycleGoesOn) {
  source_.push(OwnedValveCommand{});
  source_.fail_next();
  EXPECT_FALSE(step());
  EXPECT_TRUE(step()) << "the queued command is taken on the next step";
  EXPECT_TRUE(world_.open);
}

TEST_F(NodeTest, SafeStateOnRequest) {
  source_.push(OwnedValveCommand{});
  step();
  node_->enter_safe_state();
  EXPECT_FALSE(world_.open);
  EXPECT_EQ(world_.safe_state_entries, 1);
}

}  // namespace
}  // namespace hubrt::runtime::testing
