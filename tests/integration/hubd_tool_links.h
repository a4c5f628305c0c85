// The planner's side of the hubd Tool ECU tests (hubd_tool_fixture.h): the commands it sends each
// node and the States it takes back as plain values, over either layout's DDS topics (node-type:
// one Command and one State topic per node; hub: one of each for the whole hub). The fixture picks
// the link for the layout under test, so the tests read the same View in both.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/dds/read_condition.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/waitset.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/typed.h"

#include "tool_messages.h"

namespace hubrt::integration::tool_test {

using tool_ecu::LiftCommand;
using tool_ecu::LiftState;
using tool_ecu::SmartToolCommand;
using tool_ecu::SmartToolState;
using ToolEcuCommand = hub_msgs_msg_dds__ToolEcuCommand_;
using ToolEcuState = hub_msgs_msg_dds__ToolEcuState_;

inline char* wire(const std::string& text) {
  return const_cast<char*>(text.c_str());  // NOLINT: the wire type wants char*
}
inline std::string text(const char* s) {
  return s == nullptr ? std::string() : std::string(s);
}
// A State's header stamp (the hub's clock when it built the State), in nanoseconds.
template <class State>
std::int64_t stamp_ns(const State& s) {
  return std::int64_t{s.header.stamp.sec} * 1'000'000'000 + s.header.stamp.nanosec;
}
template <class Sequence>
std::string joined(const Sequence& list) {
  std::string out;
  for (std::uint32_t i = 0; i < list._length; ++i) out += text(list._buffer[i]) + "; ";
  return out;
}

// What the planner wants of each node; repeated at a fixed rate by the planner thread.
struct ToolOrder {
  std::string action = "idle";
  std::uint32_t run_id = 0;
  std::string program;
};
struct LiftOrder {
  std::string action = "stop";
  std::string position;
};

// The Tool ECU's States as plain values, the same for both layouts.
struct ToolView {
  bool seen = false;
  bool fresh_msg = false;
  std::string echo_action;
  std::string errors;
  std::string output;
  std::string activity;
  std::string blocked_by;
  bool robot_holds_tool = false;
  std::string arm_position;
  bool controller_online = false;
  std::uint32_t result_run_id = 0;
  bool result_ok = false;
  std::string result_reasons;
  std::uint32_t result_counter = 0;
  bool status_fresh = false;
  std::uint32_t status_age_ms = 0;
  std::string controller_alarms;
  std::string selected_program;
  float torque_nm = 0;
  std::int64_t stamp_ns = 0;  // the hub's clock when it built this State
};
struct LiftView {
  bool seen = false;
  bool fresh_msg = false;
  std::string errors;
  std::string at;
  std::string target;
  bool drive_online = false;
  bool fault = false;
  float position_mm = 0;
  std::uint32_t reading_age_ms = 0;
  bool moving = false;
  bool enabled = false;
  float speed_mm_s = 0;
  std::string fault_text;
  std::int64_t stamp_ns = 0;  // the hub's clock when it built this State
};
struct View {
  ToolView tool;
  LiftView lift;
};

inline ToolView view_of(const SmartToolState& s) {
  return ToolView{true,
                  s.fresh_msg,
                  text(s.echo.action),
                  joined(s.error_list),
                  text(s.output),
                  text(s.activity),
                  text(s.blocked_by),
                  s.robot_holds_tool,
                  text(s.arm_position),
                  s.controller_online,
                  s.last_result.run_id,
                  s.last_result.ok,
                  text(s.last_result.nok_reasons),
                  s.last_result.run_counter,
                  s.status_fresh,
                  s.status_age_ms,
                  text(s.controller_alarms),
                  text(s.selected_program),
                  s.torque_nm,
                  stamp_ns(s)};
}
inline LiftView view_of(const LiftState& s) {
  return LiftView{true,           s.fresh_msg,  joined(s.error_list), text(s.at),       text(s.target),
                  s.drive_online, s.fault,      s.position_mm,        s.reading_age_ms, s.moving,
                  s.enabled,      s.speed_mm_s, text(s.fault_text),   stamp_ns(s)};
}

// The planner's side of one layout: send both nodes their commands, take States.
class Link {
 public:
  virtual ~Link() = default;
  virtual void send(const ToolOrder& tool, const LiftOrder& lift) = 0;
  // Takes what arrived into `view`; true when something did.
  virtual bool take(View& view) = 0;
  // Blocks until a State is there to be taken, or `timeout` passes.
  virtual void wait_for_data(Duration timeout) = 0;
  virtual bool wait_for_hub(Duration patience) = 0;
};

// A WaitSet on the read conditions of a link's readers: waiting for States is waiting on the data.
class DataWait {
 public:
  template <class... Readers>
  DataWait(const dds::Participant& participant, const Readers&... readers)
      : waitset_(*dds::WaitSet::create(participant)) {
    (conditions_.push_back(*dds::ReadCondition::create(readers)), ...);
    dds::WaitSet::Token token = 0;
    for (const auto& condition : conditions_) EXPECT_TRUE(waitset_.attach(condition, token++));
  }
  void wait(Duration timeout) {
    std::array<dds::WaitSet::Token, 4> fired{};
    [[maybe_unused]] const auto n = waitset_.wait(fired, timeout);
  }

 private:
  std::vector<dds::ReadCondition> conditions_;
  dds::WaitSet waitset_;
};

template <class T>
struct Endpoint {
  static Endpoint create(const dds::Participant& participant, const std::string& topic_name) {
    auto topic = dds::Topic<T>::create(participant, topic_name);
    EXPECT_TRUE(topic) << topic.error().message;
    return Endpoint{std::move(*topic)};
  }
  dds::Topic<T> topic;
};

// Node-type layout: /smart_tool/command, /lift/command; /tool_ecu/tool/state, /tool_ecu/lift/state.
class NodeTypeLink final : public Link {
 public:
  explicit NodeTypeLink(const dds::Participant& p)
      : tool_command_(Endpoint<SmartToolCommand>::create(p, "/smart_tool/command")),
        lift_command_(Endpoint<LiftCommand>::create(p, "/lift/command")),
        tool_state_(Endpoint<SmartToolState>::create(p, "/tool_ecu/tool/state")),
        lift_state_(Endpoint<LiftState>::create(p, "/tool_ecu/lift/state")),
        tool_writer_(*dds::Writer<SmartToolCommand>::create(p, tool_command_.topic)),
        lift_writer_(*dds::Writer<LiftCommand>::create(p, lift_command_.topic)),
        tool_reader_(*dds::Reader<SmartToolState>::create(p, tool_state_.topic)),
        lift_reader_(*dds::Reader<LiftState>::create(p, lift_state_.topic)),
        data_(p, tool_reader_, lift_reader_) {}

  void send(const ToolOrder& tool, const LiftOrder& lift) override {
    SmartToolCommand t{};
    hubrt::msgs::typed::assign(t.target_type, "smart_tool");
    hubrt::msgs::typed::assign(t.target_name, "tool");
    hubrt::msgs::typed::assign(t.action, tool.action);
    t.run_id = tool.run_id;
    hubrt::msgs::typed::assign(t.program, tool.program);
    LiftCommand l{};
    hubrt::msgs::typed::assign(l.target_type, "lift");
    hubrt::msgs::typed::assign(l.target_name, "lift");
    hubrt::msgs::typed::assign(l.action, lift.action);
    hubrt::msgs::typed::assign(l.position, lift.position);
    EXPECT_TRUE(tool_writer_.write(t).is_ok());
    EXPECT_TRUE(lift_writer_.write(l).is_ok());
  }
  bool take(View& view) override {
    bool any = false;
    while (true) {
      const Result<bool> taken = tool_reader_.take_next(tool_sample_);
      if (!taken.is_ok() || !taken.value()) break;
      view.tool = view_of(tool_sample_.get());
      any = true;
    }
    while (true) {
      const Result<bool> taken = lift_reader_.take_next(lift_sample_);
      if (!taken.is_ok() || !taken.value()) break;
      view.lift = view_of(lift_sample_.get());
      any = true;
    }
    return any;
  }
  void wait_for_data(Duration timeout) override { data_.wait(timeout); }
  bool wait_for_hub(Duration patience) override {
    return tool_reader_.wait_for_writers(1, patience) && lift_reader_.wait_for_writers(1, patience) &&
           tool_writer_.wait_for_readers(1, patience) && lift_writer_.wait_for_readers(1, patience);
  }

 private:
  Endpoint<SmartToolCommand> tool_command_;
  Endpoint<LiftCommand> lift_command_;
  Endpoint<SmartToolState> tool_state_;
  Endpoint<LiftState> lift_state_;
  dds::Writer<SmartToolCommand> tool_writer_;
  dds::Writer<LiftCommand> lift_writer_;
  dds::Reader<SmartToolState> tool_reader_;
  dds::Reader<LiftState> lift_reader_;
  dds::Sample<SmartToolState> tool_sample_;
  dds::Sample<LiftState> lift_sample_;
  DataWait data_;  // after the readers: destroyed before them
};

// Hub layout: /tool_ecu/command and /tool_ecu/state, one field per node.
class HubLink final : public Link {
 public:
  explicit HubLink(const dds::Participant& p)
      : command_(Endpoint<ToolEcuCommand>::create(p, "/tool_ecu/command")),
        state_(Endpoint<ToolEcuState>::create(p, "/tool_ecu/state")),
        writer_(*dds::Writer<ToolEcuCommand>::create(p, command_.topic)),
        reader_(*dds::Reader<ToolEcuState>::create(p, state_.topic)),
        data_(p, reader_) {}

  void send(const ToolOrder& tool, const LiftOrder& lift) override {
    const std::string hub_type = "tool_ecu", hub_name = "tool_ecu", apply = "apply";
    ToolEcuCommand command{};
    hubrt::msgs::typed::assign(command.target_type, hub_type);
    hubrt::msgs::typed::assign(command.target_name, hub_name);
    hubrt::msgs::typed::assign(command.action, apply);
    // Empty target fields address each fragment to the node of its field.
    hubrt::msgs::typed::assign(command.tool.action, tool.action);
    command.tool.run_id = tool.run_id;
    hubrt::msgs::typed::assign(command.tool.program, tool.program);
    hubrt::msgs::typed::assign(command.lift.action, lift.action);
    hubrt::msgs::typed::assign(command.lift.position, lift.position);
    EXPECT_TRUE(writer_.write(command).is_ok());
  }
  bool take(View& view) override {
    bool any = false;
    while (true) {
      const Result<bool> taken = reader_.take_next(sample_);
      if (!taken.is_ok() || !taken.value()) break;
      const ToolEcuState& s = sample_.get();
      EXPECT_STREQ(s.tool.name, "tool");
      EXPECT_STREQ(s.lift.name, "lift");
      view.tool = view_of(s.tool);
      view.lift = view_of(s.lift);
      hub_errors_ = joined(s.error_list);
      any = true;
    }
    return any;
  }
  void wait_for_data(Duration timeout) override { data_.wait(timeout); }
  bool wait_for_hub(Duration patience) override {
    return reader_.wait_for_writers(1, patience) && writer_.wait_for_readers(1, patience);
  }

 private:
  Endpoint<ToolEcuCommand> command_;
  Endpoint<ToolEcuState> state_;
  dds::Writer<ToolEcuCommand> writer_;
  dds::Reader<ToolEcuState> reader_;
  dds::Sample<ToolEcuState> sample_;
  std::string hub_errors_;
  DataWait data_;  // after the reader: destroyed before it
};
}  // namespace hubrt::integration::tool_test
