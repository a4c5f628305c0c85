// An in-memory GPIO chip with the hooks a test (or a simulated device) needs: drive an input's
// electrical level, watch an output's level and its history, inject faults, make the chip vanish.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/digital_io.h"

namespace hubrt::hal::fake {

class FakeGpio;

// The consumer name the fake's line requests carry, as the Linux backend's do.
inline constexpr std::string_view kFakeGpioConsumer = "hubrt";

// An electrical level change of one line: `high` from `at` on.
struct LevelChange {
  Time at;
  bool high = false;
  friend bool operator==(const LevelChange&, const LevelChange&) = default;
};

// Told about every change of the electrical level of a line it watches (see FakeGpioChip::watch).
class LineListener {
 public:
  virtual void on_line_changed(Time at, bool high) = 0;

 protected:
  LineListener() = default;
  ~LineListener() = default;
  LineListener(const LineListener&) = default;
  LineListener& operator=(const LineListener&) = default;
};

// Levels in this interface are electrical (true = high); polarity is applied by the devices the
// backend hands out, exactly as the kernel applies the active-low flag. A line's level is what
// drives it: the output driver when requested as an output, else what was driven from outside
// (set_input_level, a simulator), else its bias (pull-up high, pull-down low, otherwise as it was).
// Every change is recorded with its time; the history keeps the last `history_capacity` changes.
//
// Hooks fail with kOutOfRange for a line beyond the chip. Not thread-safe: the chip, its FakeGpio
// and every device opened from it belong to one thread (see FakeGpio). Created by FakeGpio.
class FakeGpioChip {
 public:
  FakeGpioChip(FakeGpio& owner, std::string name, unsigned num_lines, std::size_t history_capacity);
  FakeGpioChip(const FakeGpioChip&) = delete;
  FakeGpioChip& operator=(const FakeGpioChip&) = delete;
  ~FakeGpioChip() = default;

  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  [[nodiscard]] unsigned num_lines() const noexcept { return static_cast<unsigned>(lines_.size()); }

  // --- Test hooks -------------------------------------------------------------------------------
  // Drives the line from outside at the clock's current time, as a sensor wired to it would.
  // kFailedPrecondition when the line is requested as an output (an output's driver wins).
  Status set_input_level(unsigned line, bool high);
  // Stops driving the line from outside: its bias decides again.
  Status release_input(unsigned line);
  // The line's electrical level now.
  [[nodiscard]] Result<bool> level(unsigned line) const;
  // Its changes, oldest first (requesting an output records its initial level even when unchanged).
  [[nodiscard]] std::vector<LevelChange> history(unsigned line) const;
  // The consumer holding the line ("hubrt"), or nothing when free.
  [[nodiscard]] std::optional<std::string> holder(unsigned line) const;
  // While set, reads (or writes) of the line fail with kIo.
  Status fail_reads(unsigned line, bool fail);
  Status fail_writes(unsigned line, bool fail);
  // The chip disappears (unplugged, driver unbound): every device opened from it fails with
  // kUnavailable from then on, even after reappear(); opening fails with kNotFound meanwhile.
  void vanish() noexcept;
  void reappear() noexcept;
  [[nodiscard]] bool present() const noexcept { return present_; }
  // While set, opening a line fails with kPermissionDenied (as without access to /dev/gpiochipN).
  void deny_access(bool deny) noexcept { access_denied_ = deny; }

  // --- For simulated devices ----------------------------------------------------------------------
  // Drives the line from outside from time `at` (not before the line's last change: clamped).
  // Used by simulators catching up lazily, so it does not advance the simulation itself.
  Status drive(unsigned line, bool high, Time at);
  // `listener` is told about every later level change of the line. It must outlive the chip.
  Status watch(unsigned line, LineListener& listener);

 private:
  friend class FakeGpio;
  friend class FakeLineDevice;
  friend class FakeDigitalInput;
  friend class FakeDigitalOutput;

  enum class Use : std::uint8_t { kFree, kInput, kOutput };

  struct Line {
    Use use = Use::kFree;
    Bias bias = Bias::kAsIs;
    bool level = false;
    std::optional<bool> external;  // level driven from outside
    bool output_level = false;
    bool fail_reads = false;
    bool fail_writes = false;
    std::vector<LevelChange> ring;  // fixed capacity, allocated once
    std::uint64_t changes = 0;      // changes recorded so far; ring holds the last ring.size()
    std::vector<LineListener*> listeners;
  };

  [[nodiscard]] bool valid(unsigned line) const noexcept { return line < lines_.size(); }
  [[nodiscard]] Time now() const noexcept;
  // Recomputes the line's level from what drives it and records it if it changed (or `force`).
  void settle(unsigned line, Time at, bool force = false) noexcept;
  void record(Line& line, Time at, bool high) noexcept;
  // Whether the line was at `high` at some change numbered after `since`.
  [[nodiscard]] bool was_at_since(unsigned line, bool high, std::uint64_t since) const noexcept;

  FakeGpio& owner_;
  std::string name_;
  std::vector<Line> lines_;
  bool present_ = true;
  bool access_denied_ = false;
  std::uint32_t generation_ = 0;  // bumped by vanish(): devices of an older generation are dead
};

}  // namespace hubrt::hal::fake
