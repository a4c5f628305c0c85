// What read() reports for an input whose backend records edges (DigitalInputConfig::catch_pulses):
// a pulse that starts and ends between two reads is not lost.
#pragma once

#include <optional>

namespace hubrt::hal {

// The rule, shared by the Linux (edge events) and fake (level history) backends:
//   - a level that differs from the last reported one is reported at once;
//   - if the line is back at the last reported level but was at the other level at some moment
//     since the previous read, the other level is reported for this one read, and the next read
//     reports the level the line has then.
// So a pulse shorter than the polling period shows up as exactly one read of the other level, one
// poll late at most. Several pulses within one polling period merge into one. Debouncing after
// this removes such one-read pulses again, which is why a board may not ask for both.
// Not thread-safe; never allocates.
class PulseCatcher {
 public:
  // `current`: the logical level now. `saw_other_level`: the line was at the level other than the
  // last reported one at some moment since the previous call (a backend that only knows that the
  // line changed since its previous sample passes that: both levels were then seen).
  // Returns the level to report.
  bool report(bool current, bool saw_other_level) noexcept;

  // The level reported last, or nothing before the first call.
  [[nodiscard]] std::optional<bool> reported() const noexcept { return reported_; }

 private:
  std::optional<bool> reported_;
};

}  // namespace hubrt::hal
