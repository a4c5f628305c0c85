// The CanBus contract on the fake backend's virtual CAN network (real time: SystemClock).
#include "hubrt/hal/fake/virtual_can_network.h"

#include "can_contract.h"

namespace hubrt::hal::contract {
namespace {

class VirtualCanHarness final : public CanContractHarness {
 public:
  Expected<std::unique_ptr<CanBus>> open_node(const std::vector<CanFilter>& filters) override {
    CanConfig config;
    config.bus = "contract";
    config.interface = "vcan0";
    config.filters = filters;
    auto node = network_.open(config);
    if (!node) return std::move(node).error();
    return std::unique_ptr<CanBus>(std::move(*node));
  }
  bool inject_bus_state(CanBusState state) override {
    network_.set_bus_state("vcan0", state);
    return true;
  }

 private:
  SystemClock clock_;
  fake::VirtualCanNetwork network_{clock_};
};

INSTANTIATE_TEST_SUITE_P(VirtualCan, CanContract,
                         ::testing::Values(CanContractBackend{
                             "VirtualCan", [] { return std::make_unique<VirtualCanHarness>(); }}),
                         CanContractName{});

}  // namespace
}  // namespace hubrt::hal::contract
