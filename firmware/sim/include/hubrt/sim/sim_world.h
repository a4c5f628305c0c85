// What /sim/input and /sim/fault do to a hub's fake backend, without DDS: the sim bridge calls
// these on the cycle thread when a request arrives, and tests call them directly.
#pragma once

#include <cstdint>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/board/board_config.h"
#include "hubrt/hal/fake/fake_backend.h"

namespace hubrt::sim {

// Sets a simulated input: a dock sensor (occupied), a plain input (active) or a pressure supply
// (pressure OK). Errors: kNotFound when `signal` is none of these on the board.
// Thread-safety: the GPIO side of the backend: call on the thread that runs the cycle.
Expected<void> apply_input(hal::fake::FakeBackend& fake, std::string_view signal, bool active);

// Shows the simulated RFID reader `reader` a badge: it reads `text` next. Errors: kNotFound when
// the board has no such reader. Thread-safety: as apply_input.
Expected<void> apply_badge(hal::fake::FakeBackend& fake, std::string_view reader, std::string_view text);

// One device fault (or recovery), as sim.idl's SimFault_ documents:
//   smart tool, by CAN bus:   power_off, power_on, alarm (value: alarm bits, 0 = overcurrent),
//                             bus_off, bus_on, slip, no_slip
//   lift drive, by device:    overcurrent, overtemperature, cooled, blocked, unblocked,
//                             stop_answering, answer, go_down, come_back
//   pressure supply, by name: drop, restore
//   valve, by output signal:  stick, unstick, fail_confirm (value: confirm index; reads active),
//                             repair_confirm (value: index)
struct FaultRequest {
  std::string_view device;
  std::string_view fault;
  std::uint32_t value = 0;
};

// Applies `request` at `now` (the time base of the backend's clock); `board` is the one the backend
// was built from. Errors: kNotFound for a
// device the board does not simulate; kInvalidArgument for a fault that device does not have (the
// message lists those it has) or a confirm index out of range; come_back's own errors.
// Thread-safety: as apply_input (valves and supplies belong to the cycle thread).
Expected<void> apply_fault(hal::fake::FakeBackend& fake, const hal::BoardConfig& board,
                           const FaultRequest& request, Time now);

}  // namespace hubrt::sim
