// Backend-specific behaviour of the libmodbus client against the lift drive simulator's real
// server on loopback (the generic behaviour is the Modbus contract suite). Reconnect pacing runs
// on a ManualClock; socket waits are real, bounded generously (shared 2-core machine).
#include <array>
#include <chrono>

#include <gtest/gtest.h>

#include "hubrt/hal/fake/lift_drive_server.h"
#include "hubrt/hal/libmodbus/open_libmodbus.h"

namespace hubrt::hal::libmodbus {
namespace {

namespace ld = protocol::lift_drive;
using std::chrono::milliseconds;

class LibmodbusAgainstServer : public ::testing::Test {
 protected:
  void SetUp() override {
    auto started = fake::LiftDriveServer::start(drive, clock);
    ASSERT_TRUE(started.is_ok()) << started.error().message;
    server = std::move(*started);
  }
  Expected<std::unique_ptr<ModbusClient>> open(Duration timeout) {
    ModbusConfig config;
    config.device = "lift_drive";
    config.endpoint = ModbusTcpEndpoint{"127.0.0.1", server->port()};
    config.response_timeout = timeout;
    config.reconnect_interval = milliseconds(500);
    return open_libmodbus(config, clock);
  }

  ManualClock clock;
  fake::LiftDrive drive{fake::LiftDriveConfig{}, clock.now().mono};
  std::unique_ptr<fake::LiftDriveServer> server;
};

TEST_F(LibmodbusAgainstServer, DriveThatBootsAfterTheHubIsPickedUpAtTheReconnectPace) {
  server->go_down();
  auto client = open(milliseconds(100));
  ASSERT_TRUE(client.is_ok()) << client.error().message;
  std::array<std::uint16_t, 1> reg{};
  EXPECT_EQ((*client)->read_input_registers(0, reg).code(), ErrorCode::kUnavailable);

  ASSERT_TRUE(server->come_back().is_ok());
  EXPECT_EQ((*client)->read_input_registers(0, reg).code(), ErrorCode::kUnavailable)
      << "no attempt before the reconnect interval has passed";
  clock.advance(milliseconds(500));
  EXPECT_TRUE((*client)->read_input_registers(0, reg).is_ok());
}

TEST_F(LibmodbusAgainstServer, LateAnswerIsNeverTakenForTheNextRequest) {
  auto client = open(milliseconds(40));
  ASSERT_TRUE(client.is_ok());
  ASSERT_TRUE((*client)->write_register(ld::holding::kTargetPosition, 1111).is_ok());
  ASSERT_TRUE((*client)->write_register(ld::holding::kSpeed, 22).is_ok());

  // Answers take 80 ms, the client waits 40 ms: the answer to the first read arrives while the
  // client waits for the second.
  server->set_answer_delay(milliseconds(80));
  std::array<std::uint16_t, 1> reg{};
  EXPECT_EQ((*client)->read_holding_registers(ld::holding::kTargetPosition, reg).code(), ErrorCode::kTimeout);
  const Status second = (*client)->read_holding_registers(ld::holding::kSpeed, reg);
  if (second.is_ok()) {
    EXPECT_EQ(reg[0], 22) << "the target's late answer was taken for the speed";
  }

  server->set_answer_delay(Duration::zero());
  Status settled(ErrorCode::kInternal);
  for (int i = 0; i < 10 && !settled.is_ok(); ++i)
    settled = (*client)->read_holding_registers(ld::holding::kSpeed, reg);
  ASSERT_TRUE(settled.is_ok()) << "the client recovers once the answers are in time again";
  EXPECT_EQ(reg[0], 22);
}

TEST_F(LibmodbusAgainstServer, StateBasedMasterMovesTheLift) {
  auto client = open(milliseconds(100));
  ASSERT_TRUE(client.is_ok());
  const std::array<std::uint16_t, 3> command{ld::control::kEnable | ld::control::kMove, 2000, 100};
  ASSERT_TRUE((*client)->write_registers(ld::holding::kControlWord, command).is_ok());
  clock.advance(std::chrono::seconds(2));
  std::array<std::uint16_t, ld::input::kCount> input{};
  ASSERT_TRUE((*client)->read_input_registers(0, input).is_ok());
  EXPECT_EQ(input[ld::input::kActualPosition], 2000);
  EXPECT_EQ(input[ld::input::kStatusWord], ld::status::kEnabled | ld::status::kInPosition);
  std::array<bool, 6> status_bits{};
  ASSERT_TRUE((*client)->read_discrete_inputs(0, status_bits).is_ok());
  EXPECT_TRUE(status_bits[0]);
  EXPECT_TRUE(status_bits[2]);
  EXPECT_FALSE(status_bits[5]);
}

}  // namespace
}  // namespace hubrt::hal::libmodbus
