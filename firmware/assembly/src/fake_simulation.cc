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

class FakeSimulation final : public Simulation {
 public:
  Expected<std::unique_ptr<SimulatedBackend>> open_backend(const hal::BoardConfig& board,
                                                           const Clock& clock) const override {
    auto fake = hal::fake::FakeBackend::create(board, clock);
    if (!fake) return std::move(fake).error();
    return std::unique_ptr<SimulatedBackend>(std::make_unique<FakeSimulatedBackend>(std::move(*fake)));
  }

  Expected<std::unique_ptr<runtime::CycleStage>> bridge(const dds::Participant& participant,
                                                        const std::string& hub_name,
                                                        const hal::BoardConfig& board,
                                                        SimulatedBackend& backend,
                                                        std::shared_ptr<spdlog::logger> log) const override {
    auto stage =
        sim::SimBridgeStage::create(participant, hub_name, board, fake_backend_of(backend), std::move(log));
    if (!stage) return std::move(stage).error();
    return std::unique_ptr<runtime::CycleStage>(std::move(*stage));
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
