// The lift drive simulator's TCP server, reached with plain libmodbus calls on loopback.
// The drive's time is a ManualClock; socket waits are real and bounded generously (shared 2-core
// machine), each bound saying what it guards against.
#include "hubrt/hal/fake/lift_drive_server.h"

#include <cerrno>
#include <chrono>
#include <memory>

#include <gtest/gtest.h>
#include <modbus/modbus.h>

namespace hubrt::hal::fake {
namespace {

namespace ld = protocol::lift_drive;
using std::chrono::milliseconds;
using Steady = std::chrono::steady_clock;

struct ContextFree {
  void operator()(modbus_t* ctx) const noexcept {
    modbus_close(ctx);
    modbus_free(ctx);
  }
};
using Context = std::unique_ptr<modbus_t, ContextFree>;

class LiftDriveServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto started = LiftDriveServer::start(drive, clock);
    ASSERT_TRUE(started.is_ok()) << started.error().message;
    server = std::move(*started);
  }

  // A raw libmodbus master; 200 ms response timeout (the simulator answers in well under 1 ms).
  Context connect(int unit = 1) const {
    Context ctx(modbus_new_tcp("127.0.0.1", server->port()));
    EXPECT_NE(ctx, nullptr);
    modbus_set_slave(ctx.get(), unit);
    modbus_set_response_timeout(ctx.get(), 0, 200'000);
    EXPECT_EQ(modbus_connect(ctx.get()), 0) << modbus_strerror(errno);
    return ctx;
  }

  ManualClock clock;
  LiftDrive drive{LiftDriveConfig{}, clock.now().mono};
  std::unique_ptr<LiftDriveServer> server;
};

TEST_F(LiftDriveServerTest, PicksAFreePortAndServesTheRegisterMap) {
  EXPECT_NE(server->port(), 0);
  Context ctx = connect();
  std::array<std::uint16_t, ld::input::kCount> input{};
  ASSERT_EQ(modbus_read_input_registers(ctx.get(), 0, ld::input::kCount, input.data()), ld::input::kCount);
  EXPECT_EQ(input[ld::input::kStatusWord], ld::status::kInPosition | ld::status::kLimitDown);

  const std::array<std::uint16_t, 2> target_speed{1200, 100};
  ASSERT_EQ(modbus_write_registers(ctx.get(), ld::holding::kTargetPosition, 2, target_speed.data()), 2);
  ASSERT_EQ(modbus_write_bit(ctx.get(), 0, 1), 1);  // coil 0 = enable
  ASSERT_EQ(modbus_write_bit(ctx.get(), 1, 1), 1);  // coil 1 = move
  clock.advance(milliseconds(500));
  ASSERT_EQ(modbus_read_input_registers(ctx.get(), 0, ld::input::kCount, input.data()), ld::input::kCount);
  EXPECT_EQ(input[ld::input::kActualPosition], 500)
      << "the drive's time comes from the clock at each request";

  std::array<std::uint8_t, ld::status::kDiscreteInputCount> bits{};
  ASSERT_EQ(modbus_read_input_bits(ctx.get(), 0, ld::status::kDiscreteInputCount, bits.data()),
            ld::status::kDiscreteInputCount);
  EXPECT_EQ(bits[0], 1) << "enabled";
  EXPECT_EQ(bits[1], 1) << "moving";
  std::array<std::uint16_t, 1> control{};
  ASSERT_EQ(modbus_read_registers(ctx.get(), ld::holding::kControlWord, 1, control.data()), 1);
  EXPECT_EQ(control[0], ld::control::kEnable | ld::control::kMove) << "coils and control word are one";
  EXPECT_GE(server->requests_answered(), 7U);
}

TEST_F(LiftDriveServerTest, RefusedRequestsGetTheRightException) {
  Context ctx = connect();
  std::array<std::uint16_t, 2> regs{};
  EXPECT_EQ(modbus_read_registers(ctx.get(), 10, 1, regs.data()), -1);
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(modbus_write_register(ctx.get(), ld::holding::kTargetPosition, 9999), -1);
  EXPECT_EQ(errno, EMBXILVAL);
  EXPECT_EQ(modbus_write_register(ctx.get(), 7, 1), -1);
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(modbus_mask_write_register(ctx.get(), 0, 0xFFFF, 0), -1);
  EXPECT_EQ(errno, EMBXILFUN);
  // Still served after the refusals.
  EXPECT_EQ(modbus_read_registers(ctx.get(), 0, 2, regs.data()), 2);
}

TEST_F(LiftDriveServerTest, OtherUnitIdsAndASilentServerGetNoAnswer) {
  Context other = connect(7);
  std::array<std::uint16_t, 1> reg{};
  EXPECT_EQ(modbus_read_registers(other.get(), 0, 1, reg.data()), -1);
  EXPECT_EQ(errno, ETIMEDOUT);

  Context ctx = connect();
  server->set_answering(false);
  EXPECT_EQ(modbus_read_registers(ctx.get(), 0, 1, reg.data()), -1);
  EXPECT_EQ(errno, ETIMEDOUT);
  EXPECT_GE(server->requests_unanswered(), 2U);
  server->set_answering(true);
  EXPECT_EQ(modbus_read_registers(ctx.get(), 0, 1, reg.data()), 1) << "the connection survived the silence";
}

TEST_F(LiftDriveServerTest, GoesDownAndComesBackOnTheSamePort) {
  const std::uint16_t port = server->port();
  Context ctx = connect();
  std::array<std::uint16_t, 1> reg{};
  ASSERT_EQ(modbus_read_registers(ctx.get(), 0, 1, reg.data()), 1);

  server->go_down();
  EXPECT_FALSE(server->is_up());
  EXPECT_EQ(modbus_read_registers(ctx.get(), 0, 1, reg.data()), -1) << "the connection was closed";
  Context refused(modbus_new_tcp("127.0.0.1", port));
  modbus_set_response_timeout(refused.get(), 0, 200'000);
  EXPECT_EQ(modbus_connect(refused.get()), -1) << "nobody listens while down";

  ASSERT_TRUE(server->come_back().is_ok());
  EXPECT_EQ(server->port(), port);
  Context again = connect();
  EXPECT_EQ(modbus_read_registers(again.get(), 0, 1, reg.data()), 1);
}

TEST_F(LiftDriveServerTest, SlowAnswersArriveLate) {
  Context ctx = connect();
  server->set_answer_delay(milliseconds(50));
  std::array<std::uint16_t, 1> reg{};
  const auto start = Steady::now();
  ASSERT_EQ(modbus_read_registers(ctx.get(), 0, 1, reg.data()), 1);
  EXPECT_GE(Steady::now() - start, milliseconds(50));
}

TEST_F(LiftDriveServerTest, StopsCleanlyWithClientsConnected) {
  Context a = connect();
  Context b = connect();
  const auto start = Steady::now();
  server.reset();
  // The thread is woken through its eventfd, not by a timeout: 1 s only absorbs scheduling noise.
  EXPECT_LT(Steady::now() - start, std::chrono::seconds(1));
}

TEST(LiftDriveServerStart, PortInUseAndBadAddressAreReported) {
  ManualClock clock;
  LiftDrive drive(LiftDriveConfig{}, clock.now().mono);
  auto first = LiftDriveServer::start(drive, clock);
  ASSERT_TRUE(first.is_ok());
  auto second = LiftDriveServer::start(drive, clock, LiftDriveServerOptions{"127.0.0.1", (*first)->port()});
  ASSERT_FALSE(second.is_ok());
  EXPECT_EQ(second.error().code, ErrorCode::kBusy);
  EXPECT_NE(second.error().message.find(std::to_string((*first)->port())), std::string::npos)
      << second.error().message;
  auto bad = LiftDriveServer::start(drive, clock, LiftDriveServerOptions{"localhost", 0});
  ASSERT_FALSE(bad.is_ok());
  EXPECT_EQ(bad.error().code, ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace hubrt::hal::fake
