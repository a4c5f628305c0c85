// When a running hub writes its black box (hubrt/blackbox/black_box.h), off the cycle thread: a
// thread of its own writes it when a fault latches (the hub's lifecycle becoming fault, seen by a
// cycle stage) and when someone asks over DDS — `hubctl blackbox HUB` writes a
// diagnostic_msgs/KeyValue {key: a request id, value: who asks} on <ns>/<hub>/blackbox/request and
// reads the answer on <ns>/<hub>/blackbox/written {key: the id, value: "written <path> ..." or why
// not}. (hubd writes it on exit itself, and crash_dump() on a crash.)
//
// Bounded, whoever asks: at most one file per kMinDumpInterval for requests and one for faults
// (asking again meanwhile gets "busy" and the last file's name, but a request repeated with its id,
// as hubctl repeats one whose answer it has not seen, gets the answer it had), at most
// kRequestsPerRound requests answered per kRequestRound, the rest of a flood dropped by the
// reader's history; the directory's cap bounds the disk. Nothing here runs on the cycle thread but
// fault_latched(), which only sets a flag.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <spdlog/logger.h>

#include "hubrt/base/status.h"
#include "hubrt/blackbox/black_box.h"
#include "hubrt/dds/participant.h"
#include "hubrt/runtime/hub.h"

namespace hubrt::assembly {

inline constexpr auto kMinDumpInterval = std::chrono::seconds(10);
inline constexpr auto kRequestRound = std::chrono::milliseconds(200);
inline constexpr int kRequestsPerRound = 4;

// "<ns>/<hub>/blackbox/request" and "/written".
std::string black_box_request_topic(const std::string& ros_namespace, const std::string& hub_name);
std::string black_box_reply_topic(const std::string& ros_namespace, const std::string& hub_name);

class BlackBoxService {
 public:
  // Makes the request reader and reply writer on `participant` and starts the thread. `box` and
  // `participant` must outlive the service. When the DDS entities cannot be made (Cyclone refuses,
  // e.g. DDS Security permissions that do not name them) it says so in the log and serves no
  // requests: faults are still written. Errors: none today (kept for a thread that cannot start).
  static Expected<std::unique_ptr<BlackBoxService>> start(const dds::Participant& participant,
                                                          blackbox::BlackBox& box,
                                                          const std::string& ros_namespace,
                                                          const std::string& hub_name,
                                                          std::shared_ptr<spdlog::logger> log);
  // Stops the thread (a dump in progress finishes first) and deletes the entities.
  ~BlackBoxService();
  BlackBoxService(const BlackBoxService&) = delete;
  BlackBoxService& operator=(const BlackBoxService&) = delete;

  // From the cycle: the hub's lifecycle after a step; the step into fault asks for a file.
  // Allocation-free, never blocks.
  void observe(runtime::Lifecycle state) noexcept;

  // A cycle stage that calls observe() with the hub's lifecycle after every step.
  std::unique_ptr<runtime::CycleStage> make_stage(const runtime::Hub& hub);

  [[nodiscard]] std::uint64_t requests_answered() const noexcept { return answered_.load(); }

 private:
  struct Endpoints;
  BlackBoxService(blackbox::BlackBox& box, std::shared_ptr<spdlog::logger> log);
  void run() noexcept;
  // Answers up to kRequestsPerRound requests; true when it answered that many (more may wait).
  bool serve_requests();
  void wake() noexcept;

  blackbox::BlackBox* box_;
  std::shared_ptr<spdlog::logger> log_;
  std::unique_ptr<Endpoints> endpoints_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> fault_{false};
  std::atomic<bool> requests_{false};
  std::atomic<std::uint64_t> answered_{0};
  runtime::Lifecycle last_state_ = runtime::Lifecycle::kConfiguring;        // cycle thread only
  std::optional<std::chrono::steady_clock::time_point> last_request_dump_;  // the service's thread only
  std::string last_request_path_;
  // The last answers given, by request id (the service's thread only): a bounded memory.
  struct GivenAnswer {
    std::string id;
    std::string answer;
  };
  std::array<GivenAnswer, kRequestsPerRound> given_{};
  std::size_t next_given_ = 0;
  std::thread thread_;
};

}  // namespace hubrt::assembly
