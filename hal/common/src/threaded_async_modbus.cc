#include "hubrt/hal/common/threaded_async_modbus.h"

#include <condition_variable>
#include <mutex>
#include <system_error>
#include <thread>
#include <variant>

#include <fmt/format.h>

namespace hubrt::hal {
namespace {

struct Job {
  std::uint64_t id = 0;
  ModbusBatch batch;
};

// What the worker leaves for poll(): the latest request it finished.
struct Finished {
  std::uint64_t id = 0;  // 0: none yet
  Status write;
  Status read;
  std::array<std::uint16_t, kMaxBatchRegisters> registers{};
  std::uint8_t register_count = 0;
};

struct CloseWrite {
  std::uint16_t address = 0;
  std::uint8_t count = 0;
  std::array<std::uint16_t, kMaxBatchRegisters> values{};
};

class ThreadedAsyncModbus final : public AsyncModbus {
 public:
  ThreadedAsyncModbus(std::unique_ptr<ModbusClient> client, Duration request_timeout, std::string description)
      : client_(std::move(client)), request_timeout_(request_timeout), description_(std::move(description)) {}

  // Separate from the constructor so that a thread that cannot start is an error, not a throw.
  void start() {
    thread_ = std::thread([this] { run(); });
  }

  ~ThreadedAsyncModbus() override {
    {
      const std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_one();
    if (thread_.joinable()) thread_.join();
  }
  ThreadedAsyncModbus(const ThreadedAsyncModbus&) = delete;
  ThreadedAsyncModbus& operator=(const ThreadedAsyncModbus&) = delete;

  Result<std::uint64_t> submit(const ModbusBatch& batch, Time now) noexcept override {
    if (const Status valid = check_batch(batch); !valid.is_ok()) return valid;
    const std::uint64_t id = ++last_id_;
    {
      const std::lock_guard lock(mutex_);
      waiting_ = Job{id, batch};  // replaces one that has not started
      has_waiting_ = true;
    }
    wake_.notify_one();
    latest_ = id;
    latest_submitted_at_ = now;
    latest_reported_ = false;
    return id;
  }

  bool poll(Time now, ModbusCompletion& out) noexcept override {
    if (latest_reported_) return false;
    bool finished = false;
    {
      const std::lock_guard lock(mutex_);
      if (finished_.id == latest_) {
        finished = true;
        out.write = finished_.write;
        out.read = finished_.read;
        out.registers = finished_.registers;
        out.register_count = finished_.register_count;
      } else if (now - latest_submitted_at_ > request_timeout_) {
        // Withdrawn if it has not started; one in progress ends on its own (response timeout).
        if (has_waiting_ && waiting_.id == latest_) has_waiting_ = false;
      } else {
        return false;
      }
    }
    if (!finished) {
      out.read = Status(ErrorCode::kTimeout);
      out.write = Status(ErrorCode::kTimeout);
      out.register_count = 0;
    }
    out.timed_out = !finished;
    out.id = latest_;
    out.submitted_at = latest_submitted_at_;
    out.completed_at = now;
    latest_reported_ = true;
    return true;
  }

  Status set_write_on_close(std::uint16_t address, std::span<const std::uint16_t> values) noexcept override {
    if (values.size() > kMaxBatchRegisters) return Status(ErrorCode::kInvalidArgument);
    const std::lock_guard lock(mutex_);
    close_write_.address = address;
    close_write_.count = static_cast<std::uint8_t>(values.size());
    std::copy(values.begin(), values.end(), close_write_.values.begin());
    return Status::ok();
  }

  [[nodiscard]] std::string_view description() const noexcept override { return description_; }

 private:
  // The worker: one request at a time until stopping; then the write-on-close.
  void run() noexcept {
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return stopping_ || has_waiting_; });
      if (stopping_) break;
      const Job job = waiting_;
      has_waiting_ = false;
      lock.unlock();
      Finished done = execute(job);
      lock.lock();
      finished_ = done;
    }
    const CloseWrite last = close_write_;
    lock.unlock();
    if (last.count > 0) {
      // Best effort on the way out: bounded by the client's response timeout, nobody to tell.
      client_->write_registers(last.address, std::span<const std::uint16_t>(last.values.data(), last.count))
          .ignore();
    }
  }

  Finished execute(const Job& job) noexcept {
    Finished done;
    done.id = job.id;
    const ModbusBatch& batch = job.batch;
    if (batch.write_count > 0) {
      done.write = client_->write_registers(
          batch.write_address, std::span<const std::uint16_t>(batch.write_values.data(), batch.write_count));
    }
    if (batch.read_count > 0) {
      if (!done.write.is_ok() && done.write.code() != ErrorCode::kProtocol) {
        done.read = Status(ErrorCode::kFailedPrecondition);  // the unit did not answer the write
        return done;
      }
      const std::span<std::uint16_t> out(done.registers.data(), batch.read_count);
      done.read = batch.read_bank == ModbusRegisterBank::kInput
                      ? client_->read_input_registers(batch.read_address, out)
                      : client_->read_holding_registers(batch.read_address, out);
      if (done.read.is_ok()) done.register_count = batch.read_count;
    }
    return done;
  }

  std::unique_ptr<ModbusClient> client_;  // the worker thread's only
  const Duration request_timeout_;
  const std::string description_;

  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;     // guarded by mutex_
  Job waiting_;               // guarded by mutex_
  bool has_waiting_ = false;  // guarded by mutex_
  Finished finished_;         // guarded by mutex_
  CloseWrite close_write_;    // guarded by mutex_

  // The owner's (submit/poll) only.
  std::uint64_t last_id_ = 0;
  std::uint64_t latest_ = 0;
  Time latest_submitted_at_{};
  bool latest_reported_ = true;

  std::thread thread_;
};

}  // namespace

Duration batch_request_timeout(const ModbusConfig& config) noexcept {
  return 3 * config.response_timeout;
}

std::string describe_modbus(const ModbusConfig& config) {
  if (const auto* tcp = std::get_if<ModbusTcpEndpoint>(&config.endpoint)) {
    return fmt::format("{} (tcp {}:{}, unit {})", config.device, tcp->host, tcp->port, config.unit_id);
  }
  const auto& rtu = std::get<ModbusRtuEndpoint>(config.endpoint);
  return fmt::format("{} (rtu {}, unit {})", config.device, rtu.device, config.unit_id);
}

Expected<std::unique_ptr<AsyncModbus>> open_threaded_async_modbus(std::unique_ptr<ModbusClient> client,
                                                                  Duration request_timeout,
                                                                  std::string description) {
  if (client == nullptr) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: no Modbus client to run", description));
  }
  if (request_timeout <= Duration::zero()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: request timeout must be positive", description));
  }
  auto device = std::make_unique<ThreadedAsyncModbus>(std::move(client), request_timeout, description);
  try {
    device->start();
  } catch (const std::system_error& error) {
    return make_error(ErrorCode::kUnavailable, fmt::format("{}: cannot start its Modbus worker thread: {}",
                                                           description, error.what()));
  }
  return std::unique_ptr<AsyncModbus>(std::move(device));
}

}  // namespace hubrt::hal
