// What the smart tool controller says on CAN, through the hub's side of the link: the protocol's
// decoders (hubrt/protocol/smart_tool_can.h) as ToolController uses them, and SmartToolLogic's
// run state machine, which acts on what they decoded — the node running a command picked by the
// input while the frames arrive.
//
// Input: byte 0 picks the action, byte 1 the program; then 14-byte records, one received frame
// (or receive error) each: flags, id (4 bytes, little-endian), length, 8 data bytes. Flags:
//   bit 0  the cycle runs after this record      bit 1 extended id     bit 2 remote frame
//   bit 3  receive fails (kUnavailable) instead  bits 4-6 bus state (CanBusState; 5..7: unchanged)
//   bit 7  that cycle comes 100 ms later instead of 10 ms (heartbeat loss takes 350 ms)
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "node_fixtures.h"
#include "node_harness.h"
#include "scripted_devices.h"

namespace {

using hubrt::tool_ecu::SmartToolLogic;
constexpr std::size_t kRecord = 14;
constexpr int kMaxCycles = 200;

hubrt::hal::CanFrame frame_of(const std::uint8_t* record) {
  hubrt::hal::CanFrame frame;
  std::uint32_t id = 0;
  std::memcpy(&id, record + 1, 4);  // little-endian hosts only (the fuzz preset is x86-64)
  frame.extended = (record[0] & 0x02) != 0;
  frame.remote = (record[0] & 0x04) != 0;
  frame.id = id & (frame.extended ? 0x1FFFFFFFu : 0x7FFu);  // what SocketCAN can deliver
  frame.len = static_cast<std::uint8_t>(record[5] % 9);     // likewise: 0..8
  std::memcpy(frame.data.data(), record + 6, 8);
  return frame;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  hubrt::ManualClock& clock = hubrt::fuzz::fuzz_clock();
  static const std::string& name = hubrt::fuzz::node_name("tool_ecu", SmartToolLogic::kType);
  hubrt::fuzz::CanScript& can = hubrt::fuzz::scripted_backend(clock).can();

  std::string action(SmartToolLogic::kActions[data[0] % SmartToolLogic::kActions.size()]);
  std::string program = data[1] % 2 == 0 ? "ladder_frame_bolt" : "unknown";
  std::string type(SmartToolLogic::kType);
  std::string target = name;
  hubrt::tool_ecu::SmartToolCommand command{};
  hubrt::msgs::typed::assign(command.target_type, type);
  hubrt::msgs::typed::assign(command.target_name, target);
  hubrt::msgs::typed::assign(command.action, action);
  command.run_id = 1;
  hubrt::msgs::typed::assign(command.program, program);

  hubrt::fuzz::OneShotSource<hubrt::tool_ecu::SmartToolCommand> source;
  hubrt::fuzz::DiscardingSink<hubrt::tool_ecu::SmartToolState> sink;
  hubrt::runtime::NodeOptions options;
  options.name = name;
  options.command_timeout = std::chrono::seconds(10);  // the command stays in force throughout
  options.log = hubrt::fuzz::quiet_logger();
  hubrt::runtime::Node<SmartToolLogic> node(std::move(options), hubrt::fuzz::make_smart_tool_logic(), source,
                                            sink, hubrt::fuzz::ops_of<hubrt::tool_ecu::SmartToolCommand>());
  source.post(&command);
  int cycles = 0;
  for (std::size_t at = 2; at + kRecord <= size && cycles < kMaxCycles; at += kRecord) {
    const std::uint8_t* record = data + at;
    if ((record[0] & 0x08) != 0) {
      can.incoming.emplace_back(hubrt::Status(hubrt::ErrorCode::kUnavailable));
    } else {
      can.incoming.emplace_back(frame_of(record));
    }
    const unsigned state = (record[0] >> 4) & 0x07;
    if (state <= static_cast<unsigned>(hubrt::hal::CanBusState::kDown)) {
      can.status.state = static_cast<hubrt::hal::CanBusState>(state);
    }
    if ((record[0] & 0x01) == 0) continue;
    clock.advance((record[0] & 0x80) != 0 ? std::chrono::milliseconds(100) : hubrt::fuzz::kCycle);
    node.step(clock.now());
    ++cycles;
  }
  clock.advance(hubrt::fuzz::kCycle);
  node.step(clock.now());
  node.enter_safe_state();
  can = hubrt::fuzz::CanScript{};
  return 0;
}
