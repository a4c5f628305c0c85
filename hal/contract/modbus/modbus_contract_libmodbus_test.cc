// The ModbusClient contract on the real libmodbus backend, against the lift drive simulator's
// libmodbus TCP server on loopback. One ManualClock drives the drive and paces reconnects.
#include "hubrt/hal/fake/lift_drive_server.h"
#include "hubrt/hal/libmodbus/open_libmodbus.h"

#include "modbus_contract.h"

namespace hubrt::hal::contract {
namespace {

namespace ld = protocol::lift_drive;

class LiftDriveHarness final : public ModbusContractHarness {
 public:
  LiftDriveHarness() {
    auto started = fake::LiftDriveServer::start(drive_, clock_);
    if (started) server_ = std::move(*started);
    EXPECT_TRUE(server_ != nullptr) << (started ? "" : started.error().message);
  }

  Expected<std::unique_ptr<ModbusClient>> open_client(Duration response_timeout,
                                                      Duration reconnect_interval) override {
    if (!server_) return make_error(ErrorCode::kInternal, "lift drive simulator did not start");
    ModbusConfig config;
    config.device = "lift_drive";
    config.endpoint = ModbusTcpEndpoint{"127.0.0.1", server_->port()};
    config.unit_id = ld::kDefaultUnitId;
    config.response_timeout = response_timeout;
    config.reconnect_interval = reconnect_interval;
    return libmodbus::open_libmodbus(config, clock_);
  }
  void advance_reconnect_clock(Duration by) override { clock_.advance(by); }

  [[nodiscard]] ModbusContractMap map() const override {
    ModbusContractMap m;
    m.holding_first = ld::holding::kTargetPosition;  // target, speed, watchdog
    m.holding_values = {1234, 80, 0};
    m.holding_values_alt = {2500, 120, 1000};
    m.input_first = 0;
    m.input_count = ld::input::kCount;
    m.coil = 2;  // stop: harmless both ways
    m.discrete_first = 0;
    m.discrete_count = ld::status::kDiscreteInputCount;
    m.unmapped_holding = 100;
    m.rejected_register = ld::holding::kTargetPosition;
    m.rejected_value = 60000;  // beyond the 400 mm of travel
    return m;
  }

  std::vector<std::uint16_t> device_holding(std::uint16_t first, std::size_t count) override {
    const auto r = drive_.read(clock_.now().mono);
    return {r.holding.begin() + first, r.holding.begin() + first + static_cast<std::ptrdiff_t>(count)};
  }
  std::vector<std::uint16_t> device_input(std::uint16_t first, std::size_t count) override {
    const auto r = drive_.read(clock_.now().mono);
    return {r.input.begin() + first, r.input.begin() + first + static_cast<std::ptrdiff_t>(count)};
  }
  std::vector<bool> device_coils(std::uint16_t first, std::size_t count) override {
    return bits(drive_.read(clock_.now().mono).control_word(), first, count);
  }
  std::vector<bool> device_discrete_inputs(std::uint16_t first, std::size_t count) override {
    return bits(drive_.read(clock_.now().mono).status_word(), first, count);
  }

  bool set_answering(bool answering) override {
    server_->set_answering(answering);
    return true;
  }
  bool take_down() override {
    server_->go_down();
    return true;
  }
  bool bring_back() override { return server_->come_back().is_ok(); }

 private:
  static std::vector<bool> bits(std::uint16_t word, std::uint16_t first, std::size_t count) {
    std::vector<bool> out;
    for (std::size_t i = 0; i < count; ++i) out.push_back(((word >> (first + i)) & 1U) != 0);
    return out;
  }

  ManualClock clock_;
  fake::LiftDrive drive_{fake::LiftDriveConfig{}, clock_.now().mono};
  std::unique_ptr<fake::LiftDriveServer> server_;
};

INSTANTIATE_TEST_SUITE_P(LibmodbusTcp, ModbusContract,
                         ::testing::Values(ModbusContractBackend{
                             "LibmodbusTcpLiftDrive", [] { return std::make_unique<LiftDriveHarness>(); }}),
                         ModbusContractName{});

}  // namespace
}  // namespace hubrt::hal::contract
