#include "hubrt/assembly/black_box_service.h"

#include <algorithm>
#include <optional>

#include <fmt/format.h>

#include "hubrt/base/utf8.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"

#include "diagnostic_msgs_typed.h"

namespace hubrt::assembly {
namespace {

using KeyValue = diagnostic_msgs_msg_dds__KeyValue_;
using SteadyClock = std::chrono::steady_clock;

// A request's id as the answer carries it back: at most 64 bytes of valid UTF-8 (a peer's text).
std::string request_id(const KeyValue& request) {
  const std::string_view key = request.key != nullptr ? request.key : "";
  const std::string_view cut = key.substr(0, 64);
  return std::string(cut.substr(0, valid_utf8_prefix(cut)));
}

class LifecycleStage final : public runtime::CycleStage {
 public:
  LifecycleStage(BlackBoxService& service, const runtime::Hub& hub) : service_(&service), hub_(&hub) {}
  void before_nodes(const Instant& /*now*/) noexcept override {}
  void after_nodes(const Instant& /*now*/, bool /*publish_all*/, bool /*took_effect*/) noexcept override {
    service_->observe(hub_->lifecycle().state());
  }

 private:
  BlackBoxService* service_;
  const runtime::Hub* hub_;
};

}  // namespace

std::string black_box_request_topic(const std::string& ros_namespace, const std::string& hub_name) {
  return fmt::format("{}/{}/blackbox/request", ros_namespace, hub_name);
}
std::string black_box_reply_topic(const std::string& ros_namespace, const std::string& hub_name) {
  return fmt::format("{}/{}/blackbox/written", ros_namespace, hub_name);
}

struct BlackBoxService::Endpoints {
  dds::Topic<KeyValue> request_topic;
  dds::Topic<KeyValue> reply_topic;
  dds::Reader<KeyValue> reader;
  dds::Writer<KeyValue> writer;
  dds::Sample<KeyValue> request;
};

BlackBoxService::BlackBoxService(blackbox::BlackBox& box, std::shared_ptr<spdlog::logger> log)
    : box_(&box), log_(std::move(log)) {}

Expected<std::unique_ptr<BlackBoxService>> BlackBoxService::start(const dds::Participant& participant,
                                                                  blackbox::BlackBox& box,
                                                                  const std::string& ros_namespace,
                                                                  const std::string& hub_name,
                                                                  std::shared_ptr<spdlog::logger> log) {
  std::unique_ptr<BlackBoxService> service(new BlackBoxService(box, std::move(log)));
  BlackBoxService* self = service.get();
  auto endpoints = [&]() -> Expected<std::unique_ptr<Endpoints>> {
    auto request_topic =
        dds::Topic<KeyValue>::create(participant, black_box_request_topic(ros_namespace, hub_name));
    if (!request_topic) return std::move(request_topic).error();
    auto reply_topic =
        dds::Topic<KeyValue>::create(participant, black_box_reply_topic(ros_namespace, hub_name));
    if (!reply_topic) return std::move(reply_topic).error();
    // A flood keeps only the last few requests: the history is all a peer can make the hub hold.
    auto reader = dds::Reader<KeyValue>::create(participant, *request_topic,
                                                dds::Qos::ros2_default(kRequestsPerRound), [self] {
                                                  self->requests_ = true;
                                                  self->wake();
                                                });
    if (!reader) return std::move(reader).error();
    auto writer = dds::Writer<KeyValue>::create(participant, *reply_topic);
    if (!writer) return std::move(writer).error();
    return std::make_unique<Endpoints>(Endpoints{
        std::move(*request_topic), std::move(*reply_topic), std::move(*reader), std::move(*writer), {}});
  }();
  if (endpoints) {
    service->endpoints_ = std::move(*endpoints);
  } else {
    // E.g. DDS Security permissions made before the black box had topics: the hub runs, and its
    // black box is still written on faults, on exit and on a crash.
    service->log_->warn(
        "black box: requests over DDS unavailable ({}); it is still written on faults, exits and "
        "crashes",
        endpoints.error().message);
  }
  service->thread_ = std::thread([self] { self->run(); });
  return service;
}

BlackBoxService::~BlackBoxService() {
  stop_ = true;
  wake();
  if (thread_.joinable()) thread_.join();
  endpoints_.reset();  // the reader's listener runs no more after this (dds_delete waits for it)
}

void BlackBoxService::wake() noexcept {
  { const std::lock_guard lock(mutex_); }
  cv_.notify_one();
}

void BlackBoxService::observe(runtime::Lifecycle state) noexcept {
  if (state == runtime::Lifecycle::kFault && last_state_ != runtime::Lifecycle::kFault) {
    fault_ = true;
    cv_.notify_one();  // the thread also looks every kRequestRound: a missed notify costs that much
  }
  last_state_ = state;
}

std::unique_ptr<runtime::CycleStage> BlackBoxService::make_stage(const runtime::Hub& hub) {
  return std::make_unique<LifecycleStage>(*this, hub);
}

bool BlackBoxService::serve_requests() {
  if (!endpoints_) return false;
  std::optional<SteadyClock::time_point>& last_dump = last_request_dump_;
  std::string& last_path = last_request_path_;
  for (int n = 0; n < kRequestsPerRound; ++n) {
    const Result<bool> taken = endpoints_->reader.take_next(endpoints_->request);
    if (!taken.is_ok() || !taken.value()) return false;
    const std::string id = request_id(*endpoints_->request);
    std::string answer;
    const auto now = SteadyClock::now();
    // An empty id is nobody's: never matched, never kept.
    const auto given = id.empty() ? given_.end()
                                  : std::find_if(given_.begin(), given_.end(),
                                                 [&](const GivenAnswer& g) { return g.id == id; });
    if (given != given_.end()) {
      answer = given->answer;  // asked again: its answer may have been lost on the way
    } else if (last_dump && now - *last_dump < kMinDumpInterval) {
      answer = fmt::format("busy: the last was written {:.1f} s ago to {}", to_seconds(now - *last_dump),
                           last_path);
    } else {
      auto written = box_->dump("request");
      last_dump = now;
      if (written) {
        last_path = written->path;
        answer = fmt::format("written {} ({} bytes, {} messages, {:.1f} s)", written->path, written->bytes,
                             written->messages, written->seconds);
        log_->info("black box written on request: {}", answer.substr(8));
      } else {
        answer = fmt::format("failed: {}", written.error().message);
        log_->error("black box: {}", written.error().message);
      }
    }
    if (given == given_.end() && !id.empty()) {
      given_[next_given_] = GivenAnswer{id, answer};
      next_given_ = (next_given_ + 1) % given_.size();
    }
    dds::Sample<KeyValue> reply;
    reply->key = dds_string_dup(id.c_str());
    reply->value = dds_string_dup(answer.c_str());
    (void)endpoints_->writer.write(*reply);
    ++answered_;
  }
  return true;  // a full round: more may wait
}

void BlackBoxService::run() noexcept {
  std::optional<SteadyClock::time_point> last_fault_dump;
  try {
    while (!stop_) {
      {
        std::unique_lock lock(mutex_);
        cv_.wait_for(lock, kRequestRound, [this] { return stop_ || fault_ || requests_; });
      }
      if (stop_) break;
      if (fault_.exchange(false)) {
        const auto now = SteadyClock::now();
        if (last_fault_dump && now - *last_fault_dump < kMinDumpInterval) {
          log_->warn("black box: another fault latched within {} s; not written again",
                     std::chrono::duration_cast<std::chrono::seconds>(kMinDumpInterval).count());
        } else if (auto written = box_->dump("fault")) {
          last_fault_dump = now;
          log_->warn("black box written on a fault: {} ({} messages, {:.1f} s)", written->path,
                     written->messages, written->seconds);
        } else {
          log_->error("black box: {}", written.error().message);
        }
      }
      if (requests_.exchange(false) && serve_requests()) {
        // At most kRequestsPerRound answers per round, whatever a peer sends; then look again.
        std::this_thread::sleep_for(kRequestRound);
        requests_ = true;
      }
    }
  } catch (const std::exception&) {
    // Out of memory on this thread: no more black boxes from it; hubd's exit still writes one.
  }
}

}  // namespace hubrt::assembly
