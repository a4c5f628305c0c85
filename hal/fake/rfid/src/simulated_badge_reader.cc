#include "hubrt/hal/fake/simulated_badge_reader.h"

#include <fmt/format.h>

#include "hubrt/hal/common/badge_line.h"

namespace hubrt::hal::fake {

class SimulatedBadgeReader::Device final : public BadgeReader {
 public:
  explicit Device(SimulatedBadgeReader& reader) noexcept
      : reader_(reader), generation_(reader.generation_), line_(reader.config_.timeout) {}

 private:
  Result<bool> do_poll(BadgeRead& out, Time now) noexcept override {
    if (!reader_.plugged_ || reader_.generation_ != generation_) return Status(ErrorCode::kUnavailable);
    if (reader_.queued_.empty()) return false;
    // Popping does not allocate; the text was queued by the one who presented it.
    for (char c : reader_.queued_.front()) line_.add(c, now);
    reader_.queued_.pop_front();
    return line_.end(out, now);
  }

  SimulatedBadgeReader& reader_;
  std::uint32_t generation_;
  BadgeLineAssembler line_;
};

void SimulatedBadgeReader::present(std::string_view text) {
  if (queued_.size() >= kMaxQueued) queued_.pop_front();
  queued_.emplace_back(text);
}

void SimulatedBadgeReader::unplug() noexcept {
  plugged_ = false;
  ++generation_;
  queued_.clear();
}

Expected<std::unique_ptr<BadgeReader>> SimulatedBadgeReader::open() {
  if (!plugged_) {
    return make_error(ErrorCode::kNotFound,
                      fmt::format("{}: input device {}: no such device (simulated reader unplugged)",
                                  config_.reader, config_.device));
  }
  return std::unique_ptr<BadgeReader>(new Device(*this));
}

}  // namespace hubrt::hal::fake
