#include "tap.h"

namespace hubrt::hubctl {

void TapQueue::push(TapEvent event) {
  {
    const std::lock_guard lock(mutex_);
    if (closed_) return;
    if (event.kind == TapEvent::Kind::kSample) {
      if (samples_ >= capacity_) {
        ++dropped_;  // the consumer is behind: its loss, never the tap's wait
        return;
      }
      ++samples_;
    }
    events_.push_back(std::move(event));
  }
  ready_.notify_one();
}

void TapQueue::add_producer() {
  const std::lock_guard lock(mutex_);
  ++producers_;
}

void TapQueue::close() {
  {
    const std::lock_guard lock(mutex_);
    if (producers_ > 0) --producers_;
    if (producers_ > 0) return;
    closed_ = true;
  }
  ready_.notify_all();
}

std::optional<TapEvent> TapQueue::pop(Duration timeout) {
  std::unique_lock lock(mutex_);
  if (!ready_.wait_for(lock, timeout, [this] { return !events_.empty() || closed_; })) return std::nullopt;
  if (events_.empty()) return std::nullopt;
  TapEvent event = std::move(events_.front());
  events_.pop_front();
  if (event.kind == TapEvent::Kind::kSample) --samples_;
  return event;
}

bool TapQueue::closed_and_empty() const {
  const std::lock_guard lock(mutex_);
  return closed_ && events_.empty();
}

std::uint64_t TapQueue::dropped() const {
  const std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace hubrt::hubctl
