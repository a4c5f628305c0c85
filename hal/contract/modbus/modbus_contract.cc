#include "modbus_contract.h"

#include <array>
#include <chrono>
#include <memory>
#include <span>

namespace hubrt::hal::contract {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using Steady = std::chrono::steady_clock;

std::vector<bool> to_vector(std::span<const bool> bits) {
  return {bits.begin(), bits.end()};
}

}  // namespace

void ModbusContract::SetUp() {
  harness_ = GetParam().make();
  ASSERT_NE(harness_, nullptr);
  map_ = harness_->map();
  auto client = harness_->open_client(kResponseTimeout, kReconnectInterval);
  ASSERT_TRUE(client.is_ok()) << client.error().message;
  client_ = std::move(*client);
}

TEST_P(ModbusContract, WrittenHoldingRegistersReadBack) {
  const auto n = map_.holding_values.size();
  ASSERT_TRUE(client_->write_registers(map_.holding_first, map_.holding_values).is_ok());
  std::vector<std::uint16_t> read(n);
  ASSERT_TRUE(client_->read_holding_registers(map_.holding_first, read).is_ok());
  EXPECT_EQ(read, map_.holding_values);
  EXPECT_EQ(harness_->device_holding(map_.holding_first, n), map_.holding_values) << "the device holds them";

  ASSERT_TRUE(client_->write_register(map_.holding_first, map_.holding_values_alt[0]).is_ok());
  std::vector<std::uint16_t> one(1);
  ASSERT_TRUE(client_->read_holding_registers(map_.holding_first, one).is_ok());
  EXPECT_EQ(one[0], map_.holding_values_alt[0]);
}

TEST_P(ModbusContract, InputRegistersShowWhatTheDeviceHolds) {
  std::vector<std::uint16_t> read(map_.input_count);
  ASSERT_TRUE(client_->read_input_registers(map_.input_first, read).is_ok());
  EXPECT_EQ(read, harness_->device_input(map_.input_first, map_.input_count));
}

TEST_P(ModbusContract, CoilsWriteBothWaysAndDiscreteInputsRead) {
  std::array<bool, 1> coil{};
  ASSERT_TRUE(client_->write_coil(map_.coil, true).is_ok());
  ASSERT_TRUE(client_->read_coils(map_.coil, coil).is_ok());
  EXPECT_TRUE(coil[0]);
  EXPECT_EQ(harness_->device_coils(map_.coil, 1), std::vector<bool>{true});
  ASSERT_TRUE(client_->write_coil(map_.coil, false).is_ok());
  ASSERT_TRUE(client_->read_coils(map_.coil, coil).is_ok());
  EXPECT_FALSE(coil[0]);

  // std::vector<bool> has no span: a plain array of bool.
  const auto inputs = std::make_unique<bool[]>(map_.discrete_count);
  ASSERT_TRUE(
      client_->read_discrete_inputs(map_.discrete_first, std::span<bool>(inputs.get(), map_.discrete_count))
          .is_ok());
  EXPECT_EQ(to_vector(std::span<const bool>(inputs.get(), map_.discrete_count)),
            harness_->device_discrete_inputs(map_.discrete_first, map_.discrete_count));
}

TEST_P(ModbusContract, RefusedRequestsAreProtocolErrorsAndChangeNothing) {
  std::vector<std::uint16_t> one(1);
  EXPECT_EQ(client_->read_holding_registers(map_.unmapped_holding, one).code(), ErrorCode::kProtocol);
  const auto before = harness_->device_holding(map_.rejected_register, 1);
  EXPECT_EQ(client_->write_register(map_.rejected_register, map_.rejected_value).code(),
            ErrorCode::kProtocol);
  EXPECT_EQ(harness_->device_holding(map_.rejected_register, 1), before);
  EXPECT_TRUE(client_->read_holding_registers(map_.holding_first, one).is_ok()) << "the link stays usable";
}

TEST_P(ModbusContract, RequestsBeyondTheProtocolAreRefusedLocally) {
  std::vector<std::uint16_t> none;
  EXPECT_EQ(client_->read_holding_registers(0, none).code(), ErrorCode::kInvalidArgument);
  std::vector<std::uint16_t> too_many(126);
  EXPECT_EQ(client_->read_input_registers(0, too_many).code(), ErrorCode::kInvalidArgument);
  std::vector<std::uint16_t> two(2);
  EXPECT_EQ(client_->read_holding_registers(0xFFFF, two).code(), ErrorCode::kInvalidArgument);
  const auto bits = std::make_unique<bool[]>(2001);
  EXPECT_EQ(client_->read_coils(0, std::span<bool>(bits.get(), 2001)).code(), ErrorCode::kInvalidArgument);
}

TEST_P(ModbusContract, SilentDeviceTimesOutWithinBoundsAndIsUsableAfterwards) {
  if (!harness_->set_answering(false)) GTEST_SKIP() << "cannot silence this device";
  std::vector<std::uint16_t> one(1);
  const auto start = Steady::now();
  EXPECT_EQ(client_->read_holding_registers(map_.holding_first, one).code(), ErrorCode::kTimeout);
  const auto took = Steady::now() - start;
  EXPECT_GE(took, kResponseTimeout - milliseconds(1)) << "gave up before the response timeout";
  // The response timeout plus scheduling noise; 1 s is generous on a loaded 2-core machine.
  EXPECT_LT(took, kResponseTimeout + seconds(1));

  ASSERT_TRUE(harness_->set_answering(true));
  EXPECT_TRUE(client_->read_holding_registers(map_.holding_first, one).is_ok())
      << "the next call works without waiting for a reconnect interval";
}

TEST_P(ModbusContract, DeviceGoneAndBackIsUnavailableThenReconnectsAtItsPace) {
  std::vector<std::uint16_t> one(1);
  ASSERT_TRUE(client_->read_holding_registers(map_.holding_first, one).is_ok());
  if (!harness_->take_down()) GTEST_SKIP() << "cannot take this device away";
  EXPECT_EQ(client_->read_holding_registers(map_.holding_first, one).code(), ErrorCode::kUnavailable);
  EXPECT_EQ(client_->read_holding_registers(map_.holding_first, one).code(), ErrorCode::kUnavailable);

  ASSERT_TRUE(harness_->bring_back());
  EXPECT_EQ(client_->read_holding_registers(map_.holding_first, one).code(), ErrorCode::kUnavailable)
      << "no reconnect before the reconnect interval has passed";
  harness_->advance_reconnect_clock(kReconnectInterval);
  EXPECT_TRUE(client_->read_holding_registers(map_.holding_first, one).is_ok());
  EXPECT_TRUE(client_->write_registers(map_.holding_first, map_.holding_values).is_ok());
}

TEST_P(ModbusContract, ReconnectFailsWhileTheDeviceStaysAway) {
  std::vector<std::uint16_t> one(1);
  if (!harness_->take_down()) GTEST_SKIP() << "cannot take this device away";
  EXPECT_EQ(client_->read_holding_registers(map_.holding_first, one).code(), ErrorCode::kUnavailable);
  harness_->advance_reconnect_clock(kReconnectInterval);
  EXPECT_EQ(client_->read_holding_registers(map_.holding_first, one).code(), ErrorCode::kUnavailable)
      << "the retry found nobody";
  ASSERT_TRUE(harness_->bring_back());
  harness_->advance_reconnect_clock(kReconnectInterval);
  EXPECT_TRUE(client_->read_holding_registers(map_.holding_first, one).is_ok());
}

}  // namespace hubrt::hal::contract
