// What the logic tests share: a simulated platform (the simulator's model, answering through a
// scripted device on the manual clock), the node's settings from the shipped mir_com.yaml, and a
// cycle() that steps the logic as runtime::Node does.
#pragma once

#include <memory>
#include <optional>

#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/fake/mir_platform.h"

#include "mir_settings.h"
#include "scripted_mir_device.h"

namespace hubrt::mir_com::test {

using std::chrono::milliseconds;
using std::chrono::seconds;

// 10 ms: a request's round trip through the worker thread on a LAN (the logic must not care).
constexpr Duration kLatency = milliseconds(10);
constexpr Duration kRequestTimeout = milliseconds(1000);
constexpr Duration kPeriod = milliseconds(100);  // the shipped rate_hz: 10

class MirLogicFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    auto config = config::load_hub_config(std::string(HUBRT_MIR_COM_DIR) + "/mir_com.yaml");
    ASSERT_TRUE(config) << config.error().message;
    config_ = std::move(*config);
    hal::fake::MirPlatformConfig platform;
    platform.robot_name = "mir100";
    platform.speed_m_s = 1.0;
    platform_.emplace(platform, clock_.now().mono);
    home_ = platform_->add_position("home", 0, 0, 0);
    platform_->add_position("kit_pickup", 2.0, 0.0, 0.0);
    platform_->add_position("station", 2.0, 1.5, 90.0);
  }

  std::unique_ptr<ScriptedMirDevice> make_device() {
    auto device = std::make_unique<ScriptedMirDevice>(*platform_, kLatency, kRequestTimeout);
    device_ = device.get();
    return device;
  }

  const config::NodeConfig& node(std::string_view name) {
    for (const config::NodeConfig& n : config_.nodes) {
      if (n.name == name) return n;
    }
    ADD_FAILURE() << "no node " << name;
    return config_.nodes.front();
  }

  // One cycle as runtime::Node runs it, then `kPeriod` of time: the State the logic reports.
  template <class Logic, class Command>
  typename Logic::State cycle(Logic& logic, const Command* in_force) {
    const Time now = clock_.now().mono;
    logic.read_inputs(now);
    std::optional<typename Logic::Command> view;
    if (in_force != nullptr && logic.condition() == runtime::NodeCondition::kOk) view = in_force->view();
    logic.update(view ? &*view : nullptr, now);
    errors_.clear();
    typename Logic::State state;
    logic.report(state, errors_, now);
    clock_.advance(kPeriod);
    return state;
  }

  template <class Logic, class Command>
  typename Logic::State run(Logic& logic, const Command* in_force, Duration how_long) {
    typename Logic::State state = cycle(logic, in_force);
    for (Duration t = kPeriod; t < how_long; t += kPeriod) state = cycle(logic, in_force);
    return state;
  }

  std::string errors_text() const {
    std::string out;
    for (std::size_t i = 0; i < errors_.size(); ++i) out += std::string(errors_.at(i)) + "; ";
    return out;
  }

  ManualClock clock_;
  config::HubConfig config_;
  std::optional<hal::fake::MirPlatform> platform_;
  std::string home_;
  ScriptedMirDevice* device_ = nullptr;
  runtime::ErrorList errors_;
};

}  // namespace hubrt::mir_com::test
