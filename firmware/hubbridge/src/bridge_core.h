// What a bridge does to each message, without ROS 1 or DDS in the way (so it is unit-tested):
// the check of what a ROS 1 publisher announces, the translation from ROS 1 bytes into a DDS
// sample with bounds enforced, the refusal of stale samples, and the bridge's counters.
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/msgs/type_info.h"
#include "hubrt/ros1/definition.h"

namespace hubrt::hubbridge {

// A hub type in both worlds: the reflected IDL type and its ROS 1 name, md5sum and definition.
struct BridgedType {
  const msgs::TypeInfo* type = nullptr;
  std::string ros1_name;   // "hub_msgs/DockState"
  std::string md5sum;      // genmsg's
  std::string definition;  // full ROS 1 definition, as a publisher announces it
};

// Looks `name` up among the built-in types and derives its ROS 1 form from `messages` (the ROS 2
// interface tree in ROS 1 form), checking that both lay the message out alike. Errors name the
// type, or the field that differs.
Expected<BridgedType> bridged_type(std::string_view name, const ros1::Messages& messages);

// Per-bridge counts, written by the thread that forwards and read by the diagnostics.
struct BridgeCounters {
  std::atomic<std::uint64_t> forwarded{0};
  std::atomic<std::uint64_t> dropped{0};      // over a string or sequence bound
  std::atomic<std::uint64_t> type_errors{0};  // wrong md5sum/definition, malformed bytes, bad text
  std::atomic<std::uint64_t> stale{0};        // a sample that was forwarded before (same seq and stamp)
  std::atomic<std::uint64_t> write_errors{0};
  std::atomic<std::int64_t> last_forward_ns{-1};  // monotonic time of the last forward; -1: none yet
  std::atomic<std::int64_t> last_drop_ns{-1};     // monotonic time of the last drop over a bound; -1: none
};

// The ROS 1 publishers (caller ids) a bridge received messages of its type from, each with the
// time of the last one: who is alive and publishing, for MasterSync (master_sync.h). Bounded:
// kMax caller ids, the one heard longest ago forgotten first. Thread-safe (the ROS 1 callback
// thread writes, the main thread reads).
class HeardPublishers {
 public:
  static constexpr std::size_t kMax = 32;
  // Allocates only for a caller id not held yet.
  void heard(std::string_view caller_id, std::int64_t now_ns);
  // The caller ids heard at `since_ns` or later, in the order first heard.
  [[nodiscard]] std::vector<std::string> since(std::int64_t since_ns) const;

 private:
  mutable std::mutex mutex_;
  std::vector<std::pair<std::string, std::int64_t>> last_;
};

enum class Verdict : std::uint8_t { kForward, kOverBound, kTypeError, kStale };

// The ROS 1 -> DDS half of one bridge. Not thread-safe: one thread (the ROS 1 callback thread).
class Ros1Inbound {
 public:
  Ros1Inbound(BridgedType type, const ros1::Messages& expected);
  ~Ros1Inbound();
  Ros1Inbound(const Ros1Inbound&) = delete;
  Ros1Inbound& operator=(const Ros1Inbound&) = delete;

  // What publisher `callerid` announced in its connection header. Empty when it is the bridged
  // type; else one sentence naming the field that differs (or the md5sum/type). Remembered per
  // publisher and md5sum, so the definition is parsed once.
  std::string check_publisher(const std::string& callerid, const std::string& datatype,
                              const std::string& md5sum, const std::string& definition);

  // Decodes one ROS 1 message into sample(). kForward: sample() holds it. kStale: its State
  // header (seq and stamp) equals the last forwarded one's or is older — a latched or repeated
  // delivery, which the bridge never republishes as new. `why` says what was wrong otherwise.
  Verdict take(std::span<const std::uint8_t> bytes, std::string* why);

  [[nodiscard]] const void* sample() const { return sample_.data(); }
  [[nodiscard]] const BridgedType& type() const { return type_; }

 private:
  struct HeaderStamp {
    std::int32_t sec = 0;
    std::uint32_t nanosec = 0;
    std::uint64_t seq = 0;
  };
  std::optional<HeaderStamp> header_of_sample() const;

  BridgedType type_;
  const ros1::Messages& expected_;
  std::vector<std::uint8_t> sample_;
  std::map<std::string, std::string> verdict_by_publisher_;  // callerid + md5 -> "" or the error
  std::optional<HeaderStamp> last_;
};

// The ROS 1 bytes of a DDS sample of `type` (the DDS -> ROS 1 half).
void to_ros1(const BridgedType& type, const void* sample, std::vector<std::uint8_t>& out);

}  // namespace hubrt::hubbridge
