// The real hubd on the fake backend with the hub's own test board (test/lamp-sim.yaml), commanded
// over Cyclone DDS on loopback in the test's own domain (TestDomain): what the runtime gives a new
// hub type for free (echo, fresh_msg, the watchdog, the lifecycle, a clean stop) around the lamp.
#include <csignal>
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

#include "hub_process.h"
#include "lamp_messages.h"

namespace hubrt::signal_lamp {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

// Generous: a busy 2-core machine running sanitizer builds in parallel; the test checks
// behaviour, not timing.
constexpr auto kPatience = seconds(15);

hub_msgs::LampStateView view(const LampState& state) {
  return hub_msgs::LampStateView(state);
}

std::string errors_of(const LampState& state) {
  std::string out;
  for (std::string_view error : view(state).error_list()) out += std::string(error) + "; ";
  return out;
}

bool operational(const LampState& state) {
  return view(state).header().lifecycle() == static_cast<std::uint8_t>(runtime::Lifecycle::kOperational);
}

class HubdLampTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "test-planner");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    // The node-type layout's topics (signal_lamp.yaml): /lamp/command, /signal_lamp/lamp/state.
    auto command_topic = dds::Topic<LampCommand>::create(*participant_, "/lamp/command");
    ASSERT_TRUE(command_topic) << command_topic.error().message;
    command_topic_.emplace(std::move(*command_topic));
    auto writer = dds::Writer<LampCommand>::create(*participant_, *command_topic_);
    ASSERT_TRUE(writer) << writer.error().message;
    command_writer_.emplace(std::move(*writer));
    auto state_topic = dds::Topic<LampState>::create(*participant_, "/signal_lamp/lamp/state");
    ASSERT_TRUE(state_topic) << state_topic.error().message;
    state_topic_.emplace(std::move(*state_topic));
    auto reader = dds::Reader<LampState>::create(*participant_, *state_topic_);
    ASSERT_TRUE(reader) << reader.error().message;
    state_reader_.emplace(std::move(*reader));

    integration::HubProcessOptions options;
    options.board = std::string(HUBRT_SIGNAL_LAMP_DIR) + "/test/lamp-sim.yaml";
    options.hub = "signal_lamp";
    auto hub = integration::HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(state_reader_->wait_for_writers(1, kPatience)) << hub_->output();
    ASSERT_TRUE(command_writer_->wait_for_readers(1, kPatience)) << hub_->output();
  }

  void TearDown() override { stop_planner(); }

  // Takes States until one satisfies `predicate`; false after kPatience.
  bool wait_for_state(const std::function<bool(const LampState&)>& predicate) {
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
        hub_msgs::LampCommand c;
        {
          const std::lock_guard<std::mutex> lock(mutex_);
          if (!planning_) return;
          c.set_action(action_);
        }
        c.set_target_type("lamp");
        c.set_target_name("lamp");
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
  std::optional<dds::Topic<LampCommand>> command_topic_;
  std::optional<dds::Writer<LampCommand>> command_writer_;
  std::optional<dds::Topic<LampState>> state_topic_;
  std::optional<dds::Reader<LampState>> state_reader_;
  dds::Sample<LampState> state_;
  std::optional<integration::HubProcess> hub_;
  std::mutex mutex_;  // guards action_ and planning_, shared with the planner thread
  std::string action_;
  bool planning_ = false;
  std::thread planner_;
};

TEST_F(HubdLampTest, FollowsItsCommandOverDdsAndGoesOutWhenCommandsStop) {
  // No command yet: out, not operational, not fresh.
  ASSERT_TRUE(wait_for_state([](const LampState&) { return true; })) << hub_->output();
  EXPECT_FALSE(view(state_.get()).lit());
  EXPECT_FALSE(view(state_.get()).fresh_msg());
  EXPECT_FALSE(operational(state_.get()));
  EXPECT_EQ(view(state_.get()).name(), "lamp");

  command("on");
  ASSERT_TRUE(wait_for_state([](const LampState& s) {
    return view(s).lit() && view(s).fresh_msg() && view(s).echo().action() == "on" && operational(s);
  })) << hub_->output();
  EXPECT_EQ(view(state_.get()).error_list().size(), 0u) << errors_of(state_.get());

  command("off");
  ASSERT_TRUE(wait_for_state([](const LampState& s) {
    return !view(s).lit() && view(s).echo().action() == "off";
  })) << hub_->output();

  command("on");
  ASSERT_TRUE(wait_for_state([](const LampState& s) { return view(s).lit(); })) << hub_->output();
  // The planner goes quiet: after the 1 s command timeout the watchdog puts the lamp out.
  stop_planner();
  ASSERT_TRUE(wait_for_state([](const LampState& s) { return !view(s).fresh_msg(); })) << hub_->output();
  EXPECT_FALSE(view(state_.get()).lit());
  EXPECT_FALSE(operational(state_.get()));
  EXPECT_NE(errors_of(state_.get()).find("command timeout"), std::string::npos) << errors_of(state_.get());
  EXPECT_EQ(view(state_.get()).echo().action(), "on") << "the echo still shows the last command";

  // A bad action is rejected with its reason, naming the lamp's actions.
  hub_msgs::LampCommand dance;
  dance.set_target_type("lamp");
  dance.set_target_name("lamp");
  dance.set_action("blink");
  ASSERT_TRUE(command_writer_->write(dance.wire()).is_ok());
  ASSERT_TRUE(wait_for_state([](const LampState& s) {
    return errors_of(s).find("unknown action 'blink' (expected one of: on, off, reset)") != std::string::npos;
  })) << hub_->output();

  ASSERT_TRUE(hub_->process().signal(SIGTERM));
  auto status = hub_->process().wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << hub_->output();
  EXPECT_NE(hub_->output().find("outputs driven to their safe state"), std::string::npos) << hub_->output();
}

}  // namespace
}  // namespace hubrt::signal_lamp
