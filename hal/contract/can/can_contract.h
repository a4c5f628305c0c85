// The CanBus contract: what every backend must do, as a parameterised gtest suite. A backend
// provides a harness (how to open nodes on one bus, how to fault the bus) and instantiates:
//
//   INSTANTIATE_TEST_SUITE_P(MyBackend, CanContract, ::testing::Values(CanContractBackend{
//       "MyBackend", [] { return std::make_unique<MyHarness>(); }}), CanContractName{});
//
// Real time is unavoidable here (backends block in the kernel): bounds are generous and say why.
#pragma once

#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/base/status.h"
#include "hubrt/hal/can_bus.h"

namespace hubrt::hal::contract {

class CanContractHarness {
 public:
  virtual ~CanContractHarness() = default;
  // Opens one more node (socket) on the bus under test, with these filters.
  virtual Expected<std::unique_ptr<CanBus>> open_node(const std::vector<CanFilter>& filters) = 0;
  // Puts the whole bus into `state` (kBusOff, kDown) or back to health (kErrorActive).
  // Returns false when this backend cannot produce that state (the test is skipped).
  virtual bool inject_bus_state(CanBusState state) = 0;
};

struct CanContractBackend {
  std::string name;
  std::function<std::unique_ptr<CanContractHarness>()> make;
};

// gtest prints a parameter with this (the name, instead of the struct's bytes).
inline void PrintTo(const CanContractBackend& backend, std::ostream* os) {
  *os << backend.name;
}

struct CanContractName {
  std::string operator()(const ::testing::TestParamInfo<CanContractBackend>& info) const {
    return info.param.name;
  }
};

class CanContract : public ::testing::TestWithParam<CanContractBackend> {
 protected:
  void SetUp() override;
  void TearDown() override;
  // Opens a node or fails the test.
  std::unique_ptr<CanBus> open(const std::vector<CanFilter>& filters = {});

  std::unique_ptr<CanContractHarness> harness_;
};

}  // namespace hubrt::hal::contract
