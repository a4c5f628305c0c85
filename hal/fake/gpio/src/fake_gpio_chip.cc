#include "hubrt/hal/fake/fake_gpio_chip.h"

#include <algorithm>
#include <cassert>

#include "hubrt/hal/fake/fake_gpio.h"

namespace hubrt::hal::fake {

FakeGpioChip::FakeGpioChip(FakeGpio& owner, std::string name, unsigned num_lines,
                           std::size_t history_capacity)
    : owner_(owner), name_(std::move(name)), lines_(num_lines) {
  assert(history_capacity > 0);
  for (Line& line : lines_) line.ring.resize(history_capacity);
}

Time FakeGpioChip::now() const noexcept {
  return owner_.now();
}

void FakeGpioChip::record(Line& line, Time at, bool high) noexcept {
  if (line.changes > 0) {
    const LevelChange& last = line.ring[static_cast<std::size_t>((line.changes - 1) % line.ring.size())];
    at = std::max(at, last.at);
  }
  line.ring[static_cast<std::size_t>(line.changes % line.ring.size())] = LevelChange{at, high};
  ++line.changes;
}

void FakeGpioChip::settle(unsigned index, Time at, bool force) noexcept {
  Line& line = lines_[index];
  bool level = line.level;
  if (line.use == Use::kOutput) {
    level = line.output_level;
  } else if (line.external.has_value()) {
    level = *line.external;
  } else if (line.bias == Bias::kPullUp) {
    level = true;
  } else if (line.bias == Bias::kPullDown) {
    level = false;
  }
  const bool changed = level != line.level;
  line.level = level;
  if (changed || force) record(line, at, level);
  if (changed) {
    for (LineListener* listener : line.listeners) listener->on_line_changed(at, level);
  }
}

bool FakeGpioChip::was_at_since(unsigned index, bool high, std::uint64_t since) const noexcept {
  const Line& line = lines_[index];
  const std::uint64_t capacity = line.ring.size();
  const std::uint64_t oldest_kept = line.changes > capacity ? line.changes - capacity : 0;
  // Changes were dropped from the history: two or more changes mean both levels were seen.
  if (since < oldest_kept) return line.changes - since >= 2;
  for (std::uint64_t k = since; k < line.changes; ++k) {
    if (line.ring[static_cast<std::size_t>(k % capacity)].high == high) return true;
  }
  return false;
}

Status FakeGpioChip::set_input_level(unsigned line, bool high) {
  owner_.advance();
  return drive(line, high, now());
}

Status FakeGpioChip::drive(unsigned line, bool high, Time at) {
  if (!valid(line)) return Status(ErrorCode::kOutOfRange);
  if (lines_[line].use == Use::kOutput) return Status(ErrorCode::kFailedPrecondition);
  lines_[line].external = high;
  settle(line, at);
  return Status::ok();
}

Status FakeGpioChip::release_input(unsigned line) {
  if (!valid(line)) return Status(ErrorCode::kOutOfRange);
  owner_.advance();
  lines_[line].external.reset();
  settle(line, now());
  return Status::ok();
}

Result<bool> FakeGpioChip::level(unsigned line) const {
  if (!valid(line)) return Status(ErrorCode::kOutOfRange);
  owner_.advance();
  return lines_[line].level;
}

std::vector<LevelChange> FakeGpioChip::history(unsigned index) const {
  std::vector<LevelChange> out;
  if (!valid(index)) return out;
  owner_.advance();
  const Line& line = lines_[index];
  const std::uint64_t capacity = line.ring.size();
  const std::uint64_t first = line.changes > capacity ? line.changes - capacity : 0;
  for (std::uint64_t k = first; k < line.changes; ++k)
    out.push_back(line.ring[static_cast<std::size_t>(k % capacity)]);
  return out;
}

std::optional<std::string> FakeGpioChip::holder(unsigned line) const {
  if (!valid(line) || lines_[line].use == Use::kFree) return std::nullopt;
  return std::string(kFakeGpioConsumer);
}

Status FakeGpioChip::fail_reads(unsigned line, bool fail) {
  if (!valid(line)) return Status(ErrorCode::kOutOfRange);
  lines_[line].fail_reads = fail;
  return Status::ok();
}

Status FakeGpioChip::fail_writes(unsigned line, bool fail) {
  if (!valid(line)) return Status(ErrorCode::kOutOfRange);
  lines_[line].fail_writes = fail;
  return Status::ok();
}

void FakeGpioChip::vanish() noexcept {
  present_ = false;
  ++generation_;
  // The kernel frees the requests of a removed chip; what is wired to the lines stays.
  for (Line& line : lines_) {
    line.use = Use::kFree;
    line.bias = Bias::kAsIs;
  }
}

void FakeGpioChip::reappear() noexcept {
  present_ = true;
}

Status FakeGpioChip::watch(unsigned line, LineListener& listener) {
  if (!valid(line)) return Status(ErrorCode::kOutOfRange);
  lines_[line].listeners.push_back(&listener);
  return Status::ok();
}

}  // namespace hubrt::hal::fake
