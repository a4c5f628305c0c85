// What the lift drive answers over Modbus, through the hub's side: LiftDriveLink's decoding of
// the input registers (position, status word, fault code, signed speed) and its control-word
// rules, and LiftLogic acting on them — one request answered per cycle of the node, no thread.
//
// Input: 11-byte records, one answer and one cycle each:
//   byte 0     the read's outcome: 0 ok, 1 timeout, 2 exception (kProtocol), 3 unavailable, 4+ ok
//   byte 1     the write's outcome (when the request writes), same coding
//   byte 2     the command this cycle: bits 0-1 action (0 none, 1 move, 2 stop, 3 reset),
//              bits 2-4 the position index (past the last one: an unknown name), bit 7: 600 ms pass
//   bytes 3-10 the four input registers, little-endian
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

#include "node_fixtures.h"
#include "node_harness.h"
#include "scripted_devices.h"
#include "station_files.h"

namespace {

using hubrt::tool_ecu::LiftLogic;
constexpr std::size_t kRecord = 11;
constexpr int kMaxCycles = 64;

hubrt::ErrorCode outcome(std::uint8_t code) {
  switch (code) {
    case 1:
      return hubrt::ErrorCode::kTimeout;
    case 2:
      return hubrt::ErrorCode::kProtocol;
    case 3:
      return hubrt::ErrorCode::kUnavailable;
    default:
      return hubrt::ErrorCode::kOk;
  }
}

// Commands whose strings live as long as the harness call.
struct Order {
  std::string type{LiftLogic::kType};
  std::string target;
  std::string action;
  std::string position;
  hubrt::tool_ecu::LiftCommand wire{};
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  hubrt::ManualClock& clock = hubrt::fuzz::fuzz_clock();
  static const std::string& name = hubrt::fuzz::node_name("tool_ecu", LiftLogic::kType);
  static const std::string positions[] = {"home", "float", "work", "nowhere"};
  hubrt::fuzz::ModbusScript& drive = hubrt::fuzz::scripted_backend(clock).modbus();

  drive.set_lockstep(true);
  hubrt::fuzz::OneShotSource<hubrt::tool_ecu::LiftCommand> source;
  hubrt::fuzz::DiscardingSink<hubrt::tool_ecu::LiftState> sink;
  hubrt::runtime::NodeOptions options;
  options.name = name;
  options.command_timeout = std::chrono::seconds(10);
  options.log = hubrt::fuzz::quiet_logger();
  {
    hubrt::runtime::Node<LiftLogic> node(std::move(options), hubrt::fuzz::make_lift_logic_lockstep(), source,
                                         sink, hubrt::fuzz::ops_of<hubrt::tool_ecu::LiftCommand>());
    Order order;
    order.target = name;
    node.step(clock.now());  // the node's first cycle sends the first request
    int cycles = 0;
    for (std::size_t at = 0; at + kRecord <= size && cycles < kMaxCycles; at += kRecord, ++cycles) {
      const std::uint8_t* record = data + at;
      hubrt::fuzz::ModbusRound round;
      round.read = outcome(record[0]);
      round.write = outcome(record[1]);
      for (std::size_t i = 0; i < round.input_registers.size(); ++i) {
        round.input_registers[i] = static_cast<std::uint16_t>(record[3 + 2 * i] | (record[4 + 2 * i] << 8));
      }
      clock.advance((record[2] & 0x80) != 0 ? std::chrono::milliseconds(600) : hubrt::fuzz::kCycle);
      drive.offer(round);  // the answer to the request in flight, taken by this cycle
      static constexpr const char* kActions[] = {nullptr, "move", "stop", "reset"};
      if (const char* action = kActions[record[2] & 0x03]; action != nullptr) {
        order.action = action;
        order.position = positions[std::min<std::size_t>((record[2] >> 2) & 0x07, 3)];
        hubrt::msgs::typed::assign(order.wire.target_type, order.type);
        hubrt::msgs::typed::assign(order.wire.target_name, order.target);
        hubrt::msgs::typed::assign(order.wire.action, order.action);
        hubrt::msgs::typed::assign(order.wire.position, order.position);
        source.post(&order.wire);
      }
      node.step(clock.now());
    }
  }
  drive.set_lockstep(false);
  return 0;
}
