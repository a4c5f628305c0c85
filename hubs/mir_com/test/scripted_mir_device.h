// The platform's asynchronous HTTP device for the logic's unit tests, without a thread or a
// network: requests are answered by a MirPlatform (the simulator's model) and decoded by the real
// MiR decoder, `latency` after they were submitted (manual clock), or fail as told — HTTP
// errors, no answer (reported timed out after the request timeout), a refused connection,
// malformed JSON.
#pragma once

#include <string>
#include <vector>

#include "hubrt/hal/fake/mir_platform.h"

#include "mir_link.h"

namespace hubrt::mir_com::test {

enum class DeviceFault { kNone, kServerError, kUnauthorized, kNoAnswer, kRefused, kMalformedJson };

class ScriptedMirDevice final : public MirDevice {
 public:
  ScriptedMirDevice(hal::fake::MirPlatform& platform, Duration latency, Duration request_timeout)
      : platform_(platform), latency_(latency), request_timeout_(request_timeout) {}

  Result<std::uint64_t> submit(const hal::HttpRequest& request, Time now) noexcept override;
  bool poll(Time now, MirCompletion& out) noexcept override;
  void set_request_on_close(const hal::HttpRequest& request) noexcept override { on_close_ = request; }
  [[nodiscard]] std::string_view description() const noexcept override { return "mir (scripted)"; }

  void set_fault(DeviceFault fault) { fault_ = fault; }
  // "PUT /status {"state_id": 4}": every request sent to the platform, in order.
  [[nodiscard]] const std::vector<std::string>& sent() const { return sent_; }
  [[nodiscard]] const hal::HttpRequest& on_close() const { return on_close_; }

 private:
  hal::fake::MirPlatform& platform_;
  Duration latency_;
  Duration request_timeout_;
  DeviceFault fault_ = DeviceFault::kNone;
  bool pending_ = false;
  hal::HttpRequest request_;
  Time submitted_at_{};
  std::uint64_t id_ = 0;
  hal::HttpRequest on_close_;
  std::vector<std::string> sent_;
};

}  // namespace hubrt::mir_com::test
