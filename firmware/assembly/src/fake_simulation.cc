#include "hubrt/assembly/fake_simulation.h"

#include "hubrt/hal/fake/fake_backend.h"
#include "hubrt/sim/sim_bridge_stage.h"

namespace hubrt::assembly {
namespace {

class FakeSimulatedBackend final : public Simulation::SimulatedBackend {
 public:
  explicit FakeSimulatedBackend(std::unique_ptr<hal::fake::FakeBackend> fake) : fake_(std::move(fake)) {}
  hal::Backend& backend() noexcept override { return *fake_; }
  [[nodiscard]] hal::fake::FakeBackend& fake() noexcept { return *fake_; }

 private:
  std::unique_ptr<hal::fake::FakeBackend> fake_;
};

// What prepare_bridge opened, for bridge() (the only maker and taker of it).
struct FakePreparedBridge final : Simulation::PreparedBridge {
  FakePreparedBridge(std::string hub, sim::SimBridgeStage::Entities opened)
      : hub_name(std::move(hub)), entities(std::move(opened)) {}
  std::string hub_name;
  sim::SimBridgeStage::Entities entities;
};

class FakeSimulation final : public Simulation {
 public:
  Expected<std::unique_ptr<SimulatedBackend>> open_backend(const hal::BoardConfig& board,
                                                           const Clock& clock) const override {
    auto fake = hal::fake::FakeBackend::create(board, clock);
    if (!fake) return std::move(fake).error();
    return std::unique_ptr<SimulatedBackend>(std::make_unique<FakeSimulatedBackend>(std::move(*fake)));
  }

  Expected<std::unique_ptr<PreparedBridge>> prepare_bridge(const dds::Participant& participant,
                                                           const std::string& hub_name,
                                                           const std::string& ros_namespace) const override {
    auto entities = sim::SimBridgeStage::open_entities(participant, hub_name, ros_namespace);
    if (!entities) return std::move(entities).error();
    return std::unique_ptr<PreparedBridge>(
        std::make_unique<FakePreparedBridge>(hub_name, std::move(*entities)));
  }

  std::unique_ptr<runtime::CycleStage> bridge(std::unique_ptr<PreparedBridge> prepared,
                                              const hal::BoardConfig& board, SimulatedBackend& backend,
                                              std::shared_ptr<spdlog::logger> log) const override {
    auto& fake_prepared = static_cast<FakePreparedBridge&>(*prepared);
    return sim::SimBridgeStage::create(std::move(fake_prepared.entities), std::move(fake_prepared.hub_name),
                                       board, fake_backend_of(backend), std::move(log));
  }
};

}  // namespace

const Simulation& fake_simulation() noexcept {
  static const FakeSimulation simulation;
  return simulation;
}

hal::fake::FakeBackend& fake_backend_of(Simulation::SimulatedBackend& backend) noexcept {
  return static_cast<FakeSimulatedBackend&>(backend).fake();
}

}  // namespace hubrt::assembly
