// The ModbusClient contract: what every Modbus backend must do against a device, as a
// parameterised gtest suite. A backend pairs a client with a device it can observe and fault
// (a harness) and instantiates:
//
//   INSTANTIATE_TEST_SUITE_P(MyBackend, ModbusContract, ::testing::Values(ModbusContractBackend{
//       "MyBackend", [] { return std::make_unique<MyHarness>(); }}), ModbusContractName{});
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/base/status.h"
#include "hubrt/hal/modbus_client.h"

namespace hubrt::hal::contract {

// The parts of the device's register map the suite uses.
struct ModbusContractMap {
  std::uint16_t holding_first = 0;                // writable holding registers ...
  std::vector<std::uint16_t> holding_values;      // ... and values the device accepts for them
  std::vector<std::uint16_t> holding_values_alt;  // a second accepted set, different from the first
  std::uint16_t input_first = 0;
  std::uint16_t input_count = 1;
  std::uint16_t coil = 0;  // a coil that may be written both ways
  std::uint16_t discrete_first = 0;
  std::uint16_t discrete_count = 1;
  std::uint16_t unmapped_holding = 0;   // an address the device refuses (exception 02)
  std::uint16_t rejected_register = 0;  // a register and a value the device refuses (exception 03)
  std::uint16_t rejected_value = 0;
};

class ModbusContractHarness {
 public:
  virtual ~ModbusContractHarness() = default;
  // A client for the device with these timings; reconnect attempts are paced by the harness's
  // clock (advance_reconnect_clock), so that the suite decides when a retry is due.
  virtual Expected<std::unique_ptr<ModbusClient>> open_client(Duration response_timeout,
                                                              Duration reconnect_interval) = 0;
  virtual void advance_reconnect_clock(Duration by) = 0;
  [[nodiscard]] virtual ModbusContractMap map() const = 0;

  // What the device holds now, seen from the device side.
  virtual std::vector<std::uint16_t> device_holding(std::uint16_t first, std::size_t count) = 0;
  virtual std::vector<std::uint16_t> device_input(std::uint16_t first, std::size_t count) = 0;
  virtual std::vector<bool> device_coils(std::uint16_t first, std::size_t count) = 0;
  virtual std::vector<bool> device_discrete_inputs(std::uint16_t first, std::size_t count) = 0;

  // Faults. Each returns false when this pairing cannot produce it (the test is skipped).
  virtual bool set_answering(bool answering) = 0;  // false: the device hears but never answers
  virtual bool take_down() = 0;                    // the device (server) disappears
  virtual bool bring_back() = 0;
};

struct ModbusContractBackend {
  std::string name;
  std::function<std::unique_ptr<ModbusContractHarness>()> make;
};

// gtest prints a parameter with this (the name, instead of the struct's bytes).
inline void PrintTo(const ModbusContractBackend& backend, std::ostream* os) {
  *os << backend.name;
}

struct ModbusContractName {
  std::string operator()(const ::testing::TestParamInfo<ModbusContractBackend>& info) const {
    return info.param.name;
  }
};

class ModbusContract : public ::testing::TestWithParam<ModbusContractBackend> {
 protected:
  // Response timeout the suite uses: long enough for loopback under load, short for the suite.
  static constexpr Duration kResponseTimeout = std::chrono::milliseconds(100);
  static constexpr Duration kReconnectInterval = std::chrono::milliseconds(500);

  void SetUp() override;
  std::unique_ptr<ModbusContractHarness> harness_;
  std::unique_ptr<ModbusClient> client_;
  ModbusContractMap map_;
};

}  // namespace hubrt::hal::contract
