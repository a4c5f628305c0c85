// The lift drive simulator as a real Modbus TCP server (libmodbus: modbus_tcp_listen,
// modbus_receive, modbus_reply with a modbus_mapping_t), serving a LiftDrive from its own
// thread, so that the real libmodbus client backend is tested for real on loopback.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/fake/lift_drive.h"

namespace hubrt::hal::fake {

struct LiftDriveServerOptions {
  std::string address = "127.0.0.1";  // IPv4 address to listen on; tests stay on loopback
  std::uint16_t port = 0;             // 0 = let the kernel pick a free port (see port())
};

// Answers requests for the drive's unit id only (others get no answer, like an absent unit).
// Thread-safe: every member may be called from any thread; the drive and clock must outlive it.
class LiftDriveServer {
 public:
  // Listens and starts serving. Errors: kInvalidArgument (address not an IPv4 address),
  // kBusy (port in use), kIo (any other socket error); the message names address and port.
  static Expected<std::unique_ptr<LiftDriveServer>> start(LiftDrive& drive, const Clock& clock,
                                                          LiftDriveServerOptions options = {});
  // Stops the thread and closes every socket.
  ~LiftDriveServer();
  LiftDriveServer(const LiftDriveServer&) = delete;
  LiftDriveServer& operator=(const LiftDriveServer&) = delete;

  // The bound port (the picked one when started with port 0); stays the same across come_back().
  [[nodiscard]] std::uint16_t port() const noexcept { return port_; }

  // Fault: while false the server keeps every connection and reads every request but never
  // answers, so clients run into their response timeout.
  void set_answering(bool answering) noexcept { answering_.store(answering); }
  // Fault: a slow drive — every answer goes out this much later (0 = at once), so a client
  // with a shorter timeout sees the answer arrive after it gave up.
  void set_answer_delay(Duration delay) noexcept { answer_delay_ns_.store(delay.count()); }
  // Fault: the server goes away — listening socket and all connections closed, thread stopped.
  void go_down() noexcept;
  // The server comes back on the same port. Errors as start(). No-op when already up.
  Expected<void> come_back();
  [[nodiscard]] bool is_up() const noexcept;

  [[nodiscard]] std::uint64_t requests_answered() const noexcept { return answered_.load(); }
  [[nodiscard]] std::uint64_t requests_unanswered() const noexcept { return unanswered_.load(); }
  [[nodiscard]] std::uint64_t connections_accepted() const noexcept { return accepted_.load(); }

 private:
  class Session;
  LiftDriveServer(LiftDrive& drive, const Clock& clock, LiftDriveServerOptions options);
  Expected<void> listen_and_serve();  // with lifecycle_mutex_ held

  LiftDrive& drive_;
  const Clock& clock_;
  const LiftDriveServerOptions options_;
  std::uint16_t port_ = 0;
  mutable std::mutex lifecycle_mutex_;
  std::unique_ptr<Session> session_;  // present while up; guarded by lifecycle_mutex_
  std::atomic<bool> answering_{true};
  std::atomic<std::int64_t> answer_delay_ns_{0};
  std::atomic<std::uint64_t> answered_{0};
  std::atomic<std::uint64_t> unanswered_{0};
  std::atomic<std::uint64_t> accepted_{0};
};

}  // namespace hubrt::hal::fake
