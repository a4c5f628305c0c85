// What a board's Debian package is made from: the facts of a board file (read by the real loader,
// so a package is only ever built from a valid board) and of its hub's configuration, as the
// packaging CMake module (packaging/cmake/HubrtBoardPackage.cmake) reads them.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_config.h"

namespace hubrt::packaging {

struct PackagedCanInterface {
  std::string bus;        // logical name, e.g. "tool_bus"
  std::string interface;  // e.g. "can0": systemd-networkd sets it up
  std::uint32_t bitrate = 0;
};

struct BoardFacts {
  std::string board;  // e.g. "rpi4-tool-ecu": the package is hubrt-<board>
  std::string description;
  std::string arch;  // Debian architecture: arm64 | armhf
  std::string hub;   // the board's one hub type
  double rate_hz = 0;
  std::chrono::seconds watchdog{0};         // WatchdogSec= of the unit
  bool gpio = false;                        // the hub opens GPIO chips: the service needs group gpio
  bool http = false;                        // REST devices: the package installs hubrt-http.so
  std::vector<PackagedCanInterface> can;    // one systemd-networkd .network file each
  std::vector<std::string> serial_devices;  // Modbus RTU and serial RFID readers: group dialout
  std::vector<std::string> input_devices;   // RFID keyboard-wedge readers (evdev): group input
};

// The systemd watchdog for a hub that pings it once per cycle: five periods, at least 2 s, whole
// seconds rounded up. Five periods, so that one late cycle on a loaded Pi is no restart; at least
// 2 s, so that a scheduling hiccup of the whole system is none either. Thread-safe.
std::chrono::seconds watchdog_for_rate(double rate_hz);

// The facts of a target board and its hub. Errors (kInvalidArgument, naming the board file):
// a simulation board, an architecture that is not a Debian target (x86_64), a board wired for
// more or less than one hub, a hub configuration of another hub type. Thread-safe.
Expected<BoardFacts> package_facts(const hal::BoardConfig& board, const config::HubConfig& hub);

// The facts as a JSON object (keys as the fields above; watchdog as "watchdog_sec"), for CMake's
// string(JSON). Thread-safe.
std::string to_json(const BoardFacts& facts);

}  // namespace hubrt::packaging
