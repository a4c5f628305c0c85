// The digital I/O contract on the fake backend: once on a board made for the suite, once on the
// host simulation board the whole station runs on (free lines of its dock chip).
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/fake_backend.h"

#include "digital_io_contract.h"

namespace hubrt::hal::contract {
namespace {

class FakeBackendHarness final : public DigitalIoHarness {
 public:
  // Precondition: `board` loads and has a simulation section with a chip `chip`.
  FakeBackendHarness(const Expected<BoardConfig>& board, std::string chip, std::vector<unsigned> inputs,
                     std::vector<unsigned> outputs)
      : chip_(std::move(chip)), inputs_(std::move(inputs)), outputs_(std::move(outputs)) {
    if (!board) {
      ADD_FAILURE() << board.error().message;
      return;
    }
    auto backend = fake::FakeBackend::create(*board, clock_);
    if (!backend) {
      ADD_FAILURE() << backend.error().message;
      return;
    }
    backend_ = std::move(*backend);
  }

  Backend& backend() override { return *backend_; }
  [[nodiscard]] std::string chip() const override { return chip_; }
  [[nodiscard]] unsigned num_lines() const override { return fake_chip().num_lines(); }
  [[nodiscard]] std::vector<unsigned> input_lines() const override { return inputs_; }
  [[nodiscard]] std::vector<unsigned> output_lines() const override { return outputs_; }
  Expected<void> drive(unsigned line, bool high) override {
    const Status driven = fake_chip().set_input_level(line, high);
    if (!driven.is_ok())
      return make_error(driven.code(), "set_input_level(" + std::to_string(line) + ") failed");
    return {};
  }
  Expected<bool> observe(unsigned line) override {
    const Result<bool> level = fake_chip().level(line);
    if (!level.is_ok())
      return make_error(level.status().code(), "level(" + std::to_string(line) + ") failed");
    return level.value();
  }
  [[nodiscard]] Time now() const override { return clock_.now().mono; }
  void advance(Duration d) override { clock_.advance(d); }
  bool remove_chip() override {
    fake_chip().vanish();
    return true;
  }

  [[nodiscard]] bool ready() const { return backend_ != nullptr; }

 private:
  [[nodiscard]] fake::FakeGpioChip& fake_chip() const { return *backend_->gpio().chip(chip_); }

  ManualClock clock_;
  std::string chip_;
  std::vector<unsigned> inputs_;
  std::vector<unsigned> outputs_;
  std::unique_ptr<fake::FakeBackend> backend_;
};

constexpr const char* kContractBoard = R"(board: contract
arch: x86_64
hub: contract
gpio:
  chips:
    c: {label: contract-chip}
  inputs:
    contract.placeholder: {chip: c, line: 15}
simulation:
  chip_lines: 16
)";

std::unique_ptr<DigitalIoHarness> contract_board() {
  auto harness = std::make_unique<FakeBackendHarness>(load_board_string(kContractBoard, "contract.yaml"),
                                                      "contract-chip", std::vector<unsigned>{0, 1},
                                                      std::vector<unsigned>{2, 3});
  return harness->ready() ? std::move(harness) : nullptr;
}

// Lines 20..25 of sim-dock carry no signal in host-sim.yaml.
std::unique_ptr<DigitalIoHarness> host_sim_board() {
  auto harness = std::make_unique<FakeBackendHarness>(
      load_board(std::string(HUBRT_BOARDS_DIR) + "/host-sim.yaml"), "sim-dock", std::vector<unsigned>{20, 21},
      std::vector<unsigned>{24, 25});
  return harness->ready() ? std::move(harness) : nullptr;
}

INSTANTIATE_TEST_SUITE_P(Fake, DigitalIoContract,
                         ::testing::Values(DigitalIoContractBackend{"ContractBoard", contract_board,
                                                                    "the fake backend could not be built"},
                                           DigitalIoContractBackend{"HostSimBoard", host_sim_board,
                                                                    "the fake backend could not be built"}),
                         DigitalIoContractName{});

}  // namespace
}  // namespace hubrt::hal::contract
