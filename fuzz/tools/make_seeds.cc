// Writes the binary seeds of fuzz/corpus/: commands serialised by Cyclone (what a planner sends),
// CAN conversations encoded with the smart tool protocol's own encoders, and lift drive answers.
// The text seeds (YAML, .msg) are copies of the project's files. Run by hand when a message type
// or a protocol changes:  build/fuzz/fuzz/fuzz_make_seeds fuzz/corpus
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hubrt/dds/sample.h"
#include "hubrt/msgs/json.h"
#include "hubrt/protocol/smart_tool_can.h"

#include "cdr_sample.h"
#include "dock_messages.h"
#include "rsp_messages.h"
#include "tool_messages.h"

namespace {

namespace fs = std::filesystem;
namespace st = hubrt::protocol::smart_tool;
using Bytes = std::vector<std::uint8_t>;

fs::path g_root;

void write(const std::string& harness, const std::string& name, const Bytes& bytes) {
  fs::create_directories(g_root / harness);
  std::ofstream out(g_root / harness / name, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  std::printf("%s/%s (%zu bytes)\n", harness.c_str(), name.c_str(), bytes.size());
}

template <class T>
void command(const std::string& harness, const std::string& name, const char* json) {
  const hubrt::msgs::TypeInfo& type = hubrt::msgs::type_info_of<T>();
  hubrt::dds::UntypedSample sample(*type.descriptor);
  // Every string set (null ones refuse to serialise), then the seed's fields.
  auto filled = hubrt::msgs::from_json(type, hubrt::msgs::to_json(type, sample.data()), sample.data());
  if (filled) filled = hubrt::msgs::from_json(type, nlohmann::ordered_json::parse(json), sample.data());
  if (!filled) {
    std::fprintf(stderr, "%s/%s: %s\n", harness.c_str(), name.c_str(), filled.error().message.c_str());
    std::exit(1);
  }
  write(harness, name, hubrt::fuzz::CdrDecoder::of(type).encode(sample.data()));
}

// A smart_tool_can record: flags, id (little-endian), length, data.
void frame(Bytes& out, const hubrt::hal::CanFrame& f, std::uint8_t flags) {
  out.push_back(flags);
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(f.id >> (8 * i)));
  out.push_back(f.len);
  out.insert(out.end(), f.data.begin(), f.data.end());
}

// A lift_drive_modbus record.
void round(Bytes& out, std::uint8_t read, std::uint8_t write_code, std::uint8_t order,
           std::array<std::uint16_t, 4> registers) {
  out.push_back(read);
  out.push_back(write_code);
  out.push_back(order);
  for (std::uint16_t r : registers) {
    out.push_back(static_cast<std::uint8_t>(r & 0xFF));
    out.push_back(static_cast<std::uint8_t>(r >> 8));
  }
}

void can_seeds() {
  constexpr std::uint8_t kNode = 1;
  constexpr std::uint8_t kCycle = 0x01;
  Bytes tighten{1, 0};  // action "tighten", program ladder_frame_bolt
  for (std::uint8_t beat = 0; beat < 3; ++beat) {
    frame(tighten, st::encode(kNode, st::Heartbeat{beat, st::ControllerState::kIdle}), kCycle);
  }
  const st::Program program{12, 1000, 1500, 2000};
  frame(tighten, st::encode(kNode, st::ProgramAck{program, st::AckCode::kAccepted}), kCycle);
  frame(tighten,
        st::encode(kNode, st::Status{st::status_flag::kRunning | st::status_flag::kProgramSelected, 0, 300,
                                     400, 12, 1}),
        0);
  frame(tighten, st::encode(kNode, st::Heartbeat{3, st::ControllerState::kRunning}), kCycle);
  frame(tighten,
        st::encode(kNode, st::Status{st::status_flag::kTorqueReached | st::status_flag::kProgramSelected, 0,
                                     1000, 1700, 12, 1}),
        0);
  frame(tighten, st::encode(kNode, st::RunResult{12, 1000, 1700, true, 0, 1}), kCycle);
  frame(tighten, st::encode(kNode, st::Heartbeat{4, st::ControllerState::kIdle}), kCycle);
  write("smart_tool_can", "tighten-ok", tighten);

  Bytes alarm{1, 0};
  frame(alarm, st::encode(kNode, st::Heartbeat{0, st::ControllerState::kIdle}), kCycle);
  frame(alarm,
        st::encode(kNode, st::Status{st::status_flag::kAlarm, st::alarm_bit::kOvercurrent, 0, 0, 0, 0}), 0);
  frame(alarm, st::encode(kNode, st::Heartbeat{1, st::ControllerState::kAlarm}), kCycle);
  frame(alarm, st::encode(kNode, st::Heartbeat{2, st::ControllerState::kAlarm}), 0x80 | kCycle);  // 100 ms
  frame(alarm, st::encode(kNode, st::RunResult{12, 50, 10, false, st::nok_reason::kAlarm, 0}), 0x08 | kCycle);
  write("smart_tool_can", "alarm-then-bus-error", alarm);

  Bytes loosen{2, 0};  // "loosen"
  frame(loosen, st::encode(kNode, st::Heartbeat{7, st::ControllerState::kIdle}), kCycle);
  frame(loosen,
        st::encode(kNode, st::Status{st::status_flag::kRunning | st::status_flag::kReverse, 0, 0, 0, 0, 9}),
        0x40 | kCycle);  // bus state 4: down
  write("smart_tool_can", "loosen-bus-down", loosen);
}

void modbus_seeds() {
  // Registers: position (0.1 mm), status word, fault code, speed. Order byte: action | index << 2.
  constexpr std::uint8_t kMove = 1, kStop = 2, kReset = 3;
  Bytes move;
  round(move, 0, 0, kMove | (2 << 2), {3800, 0x0005, 0, 0});  // at home, enabled, in position: move work
  round(move, 0, 0, 0, {3000, 0x0003, 0, static_cast<std::uint16_t>(-100)});
  round(move, 0, 0, 0, {1200, 0x0005, 0, 0});
  round(move, 0, 0, kStop, {1200, 0x0005, 0, 0});
  write("lift_drive_modbus", "move-to-work", move);

  Bytes fault;
  round(fault, 0, 0, kMove | (1 << 2), {2500, 0x0001, 0, 0});
  round(fault, 0, 0, 0, {2500, 0x0021, 1, 0});  // fault: overcurrent
  round(fault, 0, 2, kReset, {2500, 0x0020, 1, 0});
  round(fault, 0, 0, 0, {2500, 0x0000, 0, 0});
  write("lift_drive_modbus", "fault-and-reset", fault);

  Bytes silent;
  round(silent, 0, 0, kMove, {3800, 0x0005, 0, 0});
  round(silent, 1, 1, 0x80, {0, 0, 0, 0});  // no answer for 600 ms
  round(silent, 3, 3, 0, {0, 0, 0, 0});
  round(silent, 0, 0, kReset, {3800, 0x0005, 0, 0});
  write("lift_drive_modbus", "drive-silent", silent);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <corpus folder>\n", argv[0]);
    return 2;
  }
  g_root = argv[1];
  using hubrt::dock_ecu::DockCommand;
  using hubrt::rsp_ecu::RspCommand;
  using hubrt::tool_ecu::LiftCommand;
  using hubrt::tool_ecu::SmartToolCommand;
  command<DockCommand>("dock_command", "monitor",
                       R"({"target_type":"dock","target_name":"dock","action":"monitor"})");
  command<DockCommand>("dock_command", "reset",
                       R"({"target_type":"dock","target_name":"dock","action":"reset"})");
  command<DockCommand>("dock_command", "wrong-type",
                       R"({"target_type":"lift","target_name":"dock","action":"monitor"})");
  command<RspCommand>(
      "rsp_command", "lock-keep",
      R"({"target_type":"tool_changer","target_name":"rsp","action":"lock","gripper":"keep"})");
  command<RspCommand>(
      "rsp_command", "unlock",
      R"({"target_type":"tool_changer","target_name":"rsp","action":"unlock","gripper":"release"})");
  command<RspCommand>(
      "rsp_command", "lock-grab",
      R"({"target_type":"tool_changer","target_name":"rsp","action":"lock","gripper":"grab"})");
  command<SmartToolCommand>(
      "smart_tool_command", "tighten",
      R"({"target_type":"smart_tool","target_name":"tool","action":"tighten","run_id":1,"program":"ladder_frame_bolt"})");
  command<SmartToolCommand>("smart_tool_command", "loosen",
                            R"({"target_type":"smart_tool","target_name":"tool","action":"loosen"})");
  command<SmartToolCommand>("smart_tool_command", "inhibit",
                            R"({"target_type":"smart_tool","target_name":"tool","action":"inhibit"})");
  command<SmartToolCommand>(
      "smart_tool_command", "tighten-unknown-program",
      R"({"target_type":"smart_tool","target_name":"tool","action":"tighten","run_id":7,"program":"pipe"})");
  command<LiftCommand>("lift_command", "move-work",
                       R"({"target_type":"lift","target_name":"lift","action":"move","position":"work"})");
  command<LiftCommand>("lift_command", "stop",
                       R"({"target_type":"lift","target_name":"lift","action":"stop"})");
  command<LiftCommand>("lift_command", "reset",
                       R"({"target_type":"lift","target_name":"lift","action":"reset"})");
  command<hubrt::dock_ecu::DockEcuTypes::Command::Wire>(
      "dock_ecu_command", "apply-monitor",
      R"({"target_type":"dock_ecu","target_name":"dock_ecu","action":"apply","dock":{"action":"monitor"}})");
  command<hubrt::dock_ecu::DockEcuTypes::Command::Wire>(
      "dock_ecu_command", "apply-named",
      R"({"target_type":"dock_ecu","target_name":"dock_ecu","action":"apply","dock":{"target_type":"dock","target_name":"dock","action":"reset"}})");
  command<hubrt::rsp_ecu::RspEcuTypes::Command::Wire>(
      "rsp_ecu_command", "apply-lock",
      R"({"target_type":"rsp_ecu","target_name":"rsp_ecu","action":"apply","rsp":{"action":"lock","gripper":"grab"}})");
  command<hubrt::rsp_ecu::RspEcuTypes::Command::Wire>(
      "rsp_ecu_command", "reset",
      R"({"target_type":"rsp_ecu","target_name":"rsp_ecu","action":"reset","rsp":{"action":"reset"}})");
  command<hubrt::tool_ecu::ToolEcuTypes::Command::Wire>(
      "tool_ecu_command", "apply-tighten-move",
      R"({"target_type":"tool_ecu","target_name":"tool_ecu","action":"apply","tool":{"action":"tighten","run_id":3,"program":"pipe_plate"},"lift":{"action":"move","position":"float"}})");
  command<hubrt::tool_ecu::ToolEcuTypes::Command::Wire>(
      "tool_ecu_command", "apply-idle-stop",
      R"({"target_type":"tool_ecu","target_name":"tool_ecu","action":"apply","tool":{"action":"idle"},"lift":{"action":"stop"}})");
  can_seeds();
  modbus_seeds();
  return 0;
}
