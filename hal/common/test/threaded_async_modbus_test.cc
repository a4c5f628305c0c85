// The HAL's threaded AsyncModbus against the lift drive simulator's real libmodbus server on
// loopback, through the real libmodbus client. The times the caller passes in come from a
// ManualClock; the worker thread's socket waits are real. Where a test needs a request to be in
// progress, the client is wrapped so that its calls wait at a gate the test opens — no sleeps.
// Waits for the worker are bounded generously (a shared 2-core machine running sanitizer builds).
#include "hubrt/hal/common/threaded_async_modbus.h"

#include <array>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/hal/fake/lift_drive_server.h"
#include "hubrt/hal/libmodbus/open_libmodbus.h"

namespace hubrt::hal {
namespace {

namespace ld = protocol::lift_drive;
using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr auto kPatience = seconds(20);  // real time; only a stuck worker takes this long

// A ModbusClient that counts the calls that started and lets them through only while its gate is
// open. Thread-safe (the worker calls, the test opens the gate and waits).
class GatedClient final : public ModbusClient {
 public:
  explicit GatedClient(std::unique_ptr<ModbusClient> real) : real_(std::move(real)) {}

  void close_gate() {
    const std::lock_guard lock(mutex_);
    open_ = false;
  }
  void open_gate() {
    {
      const std::lock_guard lock(mutex_);
      open_ = true;
    }
    changed_.notify_all();
  }
  // True once `n` calls have started (real time, up to kPatience).
  bool wait_started(int n) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, kPatience, [&] { return started_ >= n; });
  }
  int started() {
    const std::lock_guard lock(mutex_);
    return started_;
  }

 private:
  void enter() {
    std::unique_lock lock(mutex_);
    ++started_;
    changed_.notify_all();
    changed_.wait(lock, [&] { return open_; });
  }
  Status do_read_registers(RegisterKind kind, std::uint16_t address,
                           std::span<std::uint16_t> out) noexcept override {
    enter();
    return kind == RegisterKind::kInput ? real_->read_input_registers(address, out)
                                        : real_->read_holding_registers(address, out);
  }
  Status do_write_registers(std::uint16_t address, std::span<const std::uint16_t> values) noexcept override {
    enter();
    return real_->write_registers(address, values);
  }
  Status do_read_bits(BitKind kind, std::uint16_t address, std::span<bool> out) noexcept override {
    enter();
    return kind == BitKind::kCoil ? real_->read_coils(address, out)
                                  : real_->read_discrete_inputs(address, out);
  }
  Status do_write_coil(std::uint16_t address, bool value) noexcept override {
    enter();
    return real_->write_coil(address, value);
  }

  std::unique_ptr<ModbusClient> real_;
  std::mutex mutex_;
  std::condition_variable changed_;
  bool open_ = true;
  int started_ = 0;
};

ModbusBatch read_inputs() {
  ModbusBatch batch;
  batch.read_bank = ModbusRegisterBank::kInput;
  batch.read_address = 0;
  batch.read_count = ld::input::kCount;
  return batch;
}

ModbusBatch write_speed(std::uint16_t speed) {
  ModbusBatch batch;
  batch.write_address = ld::holding::kSpeed;
  batch.write_count = 1;
  batch.write_values[0] = speed;
  return batch;
}

class ThreadedAsyncModbusTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto started = fake::LiftDriveServer::start(drive_, clock_);
    ASSERT_TRUE(started) << started.error().message;
    server_ = std::move(*started);
    config_.device = "lift_drive";
    config_.endpoint = ModbusTcpEndpoint{"127.0.0.1", server_->port()};
    config_.response_timeout = milliseconds(100);
  }
  // Opens the device on a gated libmodbus client; `request_timeout` as the caller's deadline.
  void open(Duration request_timeout = seconds(60)) {
    auto client = libmodbus::open_libmodbus(config_, clock_);
    ASSERT_TRUE(client) << client.error().message;
    auto gated = std::make_unique<GatedClient>(std::move(*client));
    gate_ = gated.get();
    auto device = open_threaded_async_modbus(std::move(gated), request_timeout, describe_modbus(config_));
    ASSERT_TRUE(device) << device.error().message;
    device_ = std::move(*device);
  }
  // Polls at the caller's time `now` until a completion comes (real time, up to kPatience).
  bool wait_completion(Time now, ModbusCompletion& out) {
    const auto give_up = std::chrono::steady_clock::now() + kPatience;
    while (std::chrono::steady_clock::now() < give_up) {
      if (device_->poll(now, out)) return true;
      std::this_thread::yield();
    }
    return false;
  }
  std::uint16_t holding(std::uint16_t address) { return drive_.read(clock_.now().mono).holding[address]; }

  ManualClock clock_;
  fake::LiftDrive drive_{fake::LiftDriveConfig{}, clock_.now().mono};
  std::unique_ptr<fake::LiftDriveServer> server_;
  ModbusConfig config_;
  GatedClient* gate_ = nullptr;
  std::unique_ptr<AsyncModbus> device_;
};

TEST_F(ThreadedAsyncModbusTest, RunsAWriteThenAReadAndStampsTheCallersTimes) {
  open();
  ModbusBatch batch;
  batch.write_address = ld::holding::kSpeed;
  batch.write_count = 2;
  batch.write_values[0] = 123;  // speed
  batch.write_values[1] = 0;    // watchdog off
  batch.read_bank = ModbusRegisterBank::kHolding;
  batch.read_address = ld::holding::kControlWord;
  batch.read_count = ld::holding::kCount;
  const Time submitted = clock_.now().mono;
  const Result<std::uint64_t> id = device_->submit(batch, submitted);
  ASSERT_TRUE(id.is_ok());
  EXPECT_EQ(id.value(), 1u);
  ModbusCompletion done;
  const Time polled = submitted + milliseconds(7);
  ASSERT_TRUE(wait_completion(polled, done));
  EXPECT_EQ(done.id, 1u);
  EXPECT_TRUE(done.status().is_ok()) << to_string(done.status().code());
  EXPECT_FALSE(done.timed_out);
  EXPECT_EQ(done.submitted_at, submitted);
  EXPECT_EQ(done.completed_at, polled) << "the time of the poll that reported it, not a clock's";
  ASSERT_EQ(done.register_count, ld::holding::kCount);
  EXPECT_EQ(done.registers[ld::holding::kSpeed], 123) << "the read shows what the write did";
  EXPECT_EQ(holding(ld::holding::kSpeed), 123);
  EXPECT_FALSE(device_->poll(polled, done)) << "reported once";
  EXPECT_EQ(device_->description(),
            "lift_drive (tcp 127.0.0.1:" + std::to_string(server_->port()) + ", unit 1)");

  ASSERT_TRUE(device_->submit(read_inputs(), polled).is_ok());
  ASSERT_TRUE(wait_completion(polled, done));
  EXPECT_EQ(done.id, 2u);
  ASSERT_EQ(done.register_count, ld::input::kCount);
  EXPECT_NE(done.registers[ld::input::kStatusWord] & ld::status::kInPosition, 0) << "the drive at power-up";
}

TEST_F(ThreadedAsyncModbusTest, AReadIsNotSentAfterAnUnansweredWrite) {
  open();
  server_->set_answering(false);
  ModbusBatch batch = read_inputs();
  batch.write_address = ld::holding::kSpeed;
  batch.write_count = 1;
  batch.write_values[0] = 77;
  ASSERT_TRUE(device_->submit(batch, clock_.now().mono).is_ok());
  ModbusCompletion done;
  ASSERT_TRUE(wait_completion(clock_.now().mono, done));
  EXPECT_EQ(done.write.code(), ErrorCode::kTimeout) << "the client's response timeout";
  EXPECT_EQ(done.read.code(), ErrorCode::kFailedPrecondition);
  EXPECT_EQ(done.status().code(), ErrorCode::kTimeout);
  EXPECT_FALSE(done.timed_out) << "the client's own timeout, not the deadline";
  EXPECT_EQ(done.register_count, 0);
  EXPECT_EQ(gate_->started(), 1) << "only the write";

  // A refused write (an exception answer: the unit is there) is followed by the read.
  server_->set_answering(true);
  batch.write_values[0] = 0;  // speed 0: refused
  ASSERT_TRUE(device_->submit(batch, clock_.now().mono).is_ok());
  ASSERT_TRUE(wait_completion(clock_.now().mono, done));
  EXPECT_EQ(done.write.code(), ErrorCode::kProtocol);
  EXPECT_TRUE(done.read.is_ok());
  EXPECT_EQ(done.register_count, ld::input::kCount);
  EXPECT_EQ(holding(ld::holding::kSpeed), 50) << "the power-up speed: neither 77 nor 0 was taken";
}

TEST_F(ThreadedAsyncModbusTest, ALaterSubmitReplacesAWaitingRequest) {
  open();
  gate_->close_gate();
  const Time now = clock_.now().mono;
  const auto first = device_->submit(read_inputs(), now);
  ASSERT_TRUE(gate_->wait_started(1)) << "the worker took the first request";
  const auto second = device_->submit(write_speed(60), now);
  const auto third = device_->submit(write_speed(70), now);
  ASSERT_TRUE(first.is_ok() && second.is_ok() && third.is_ok());
  ModbusCompletion done;
  EXPECT_FALSE(device_->poll(now, done)) << "the first is held at the gate, the third waits";
  gate_->open_gate();
  ASSERT_TRUE(wait_completion(now, done));
  EXPECT_EQ(done.id, third.value()) << "only the latest submission is reported";
  EXPECT_TRUE(done.status().is_ok());
  EXPECT_EQ(holding(ld::holding::kSpeed), 70);
  EXPECT_EQ(gate_->started(), 2) << "the second never ran";
}

TEST_F(ThreadedAsyncModbusTest, ARequestPastItsDeadlineIsATimeoutJudgedAtTheCallersTime) {
  open(milliseconds(300));
  gate_->close_gate();
  const Time t0 = clock_.now().mono;
  ASSERT_TRUE(device_->submit(read_inputs(), t0).is_ok());
  ASSERT_TRUE(gate_->wait_started(1));
  const auto waiting = device_->submit(write_speed(60), t0);
  ASSERT_TRUE(waiting.is_ok());
  ModbusCompletion done;
  EXPECT_FALSE(device_->poll(t0 + milliseconds(300), done)) << "at the deadline, not past it";
  ASSERT_TRUE(device_->poll(t0 + milliseconds(301), done));
  EXPECT_EQ(done.id, waiting.value());
  EXPECT_TRUE(done.timed_out);
  EXPECT_EQ(done.read.code(), ErrorCode::kTimeout);
  EXPECT_EQ(done.completed_at, t0 + milliseconds(301));

  // The timed-out request had not started: it was withdrawn. The next one runs after the one held.
  const Time t1 = t0 + seconds(1);
  const auto next = device_->submit(write_speed(80), t1);
  gate_->open_gate();
  ASSERT_TRUE(wait_completion(t1, done));
  EXPECT_EQ(done.id, next.value());
  EXPECT_TRUE(done.status().is_ok());
  EXPECT_EQ(holding(ld::holding::kSpeed), 80);
  EXPECT_EQ(gate_->started(), 2) << "the withdrawn write never reached the drive";
}

TEST_F(ThreadedAsyncModbusTest, TheWriteOnCloseIsTheLastWord) {
  open();
  const std::uint16_t stop = ld::control::kStop;
  ASSERT_TRUE(device_->set_write_on_close(ld::holding::kControlWord, {&stop, 1}).is_ok());
  ModbusBatch move;
  move.write_address = ld::holding::kControlWord;
  move.write_count = 1;
  move.write_values[0] = ld::control::kEnable | ld::control::kMove;
  ASSERT_TRUE(device_->submit(read_inputs(), clock_.now().mono).is_ok());
  ASSERT_TRUE(device_->submit(move, clock_.now().mono).is_ok());
  device_.reset();  // ends the request in progress, drops a waiting one, then writes "stop"
  EXPECT_EQ(drive_.read(clock_.now().mono).control_word(), ld::control::kStop);
}

TEST_F(ThreadedAsyncModbusTest, BadBatchesAndBadOpensAreRefusedWithTheirReason) {
  open();
  ModbusBatch nothing;
  EXPECT_EQ(device_->submit(nothing, clock_.now().mono).status().code(), ErrorCode::kInvalidArgument);
  ModbusBatch too_many = read_inputs();
  too_many.read_count = kMaxBatchRegisters + 1;
  EXPECT_EQ(device_->submit(too_many, clock_.now().mono).status().code(), ErrorCode::kInvalidArgument);
  const std::array<std::uint16_t, kMaxBatchRegisters + 1> long_write{};
  EXPECT_EQ(device_->set_write_on_close(0, long_write).code(), ErrorCode::kInvalidArgument);

  auto no_client = open_threaded_async_modbus(nullptr, seconds(1), "lift_drive (tcp 127.0.0.1:1, unit 1)");
  ASSERT_FALSE(no_client);
  EXPECT_EQ(no_client.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(no_client.error().message, "lift_drive (tcp 127.0.0.1:1, unit 1): no Modbus client to run");
  auto client = libmodbus::open_libmodbus(config_, clock_);
  ASSERT_TRUE(client);
  auto no_timeout = open_threaded_async_modbus(std::move(*client), Duration::zero(), "lift_drive");
  ASSERT_FALSE(no_timeout);
  EXPECT_EQ(no_timeout.error().message, "lift_drive: request timeout must be positive");
  EXPECT_EQ(batch_request_timeout(config_), milliseconds(300));
}

}  // namespace
}  // namespace hubrt::hal
