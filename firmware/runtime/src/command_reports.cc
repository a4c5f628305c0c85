#include "hubrt/runtime/command_reports.h"

namespace hubrt::runtime {

bool CommandReports::RateLimit::due(std::string_view text, Time now) noexcept {
  if (ever && text == last.view() && now - at < std::chrono::seconds(1)) return false;
  last.assign(text);
  at = now;
  ever = true;
  return true;
}

void CommandReports::rejected(Time now) noexcept {
  ++rejected_;
  rejected_at_ = now;
  has_rejection_ = true;
  if (rejection_log_.due(rejection_.view(), now)) {
    log_->warn("{}: rejected command ({} so far): {}", node_, rejected_, rejection_.view());
  }
}

void CommandReports::stale(Time now, const JudgedAge& judged) noexcept {
  ++stale_;
  stale_at_ = now;
  has_stale_ = true;
  // Logged once a second per kind, not per reason: the age in the text changes with every command.
  std::string_view kind;
  if (judged.verdict == AgeVerdict::kQueued) {
    kind = "queued";
    stale_text_.assign("command queued while the hub could not run (cycle stalled): discarded");
  } else {
    kind = "stale";
    stale_text_.format("stale command: written {:.3f} s ago, older than the command timeout: not applied",
                       to_seconds(judged.offset));
  }
  if (stale_log_.due(kind, now)) {
    log_->warn("{}: {} ({} stale so far; clocks and links: docs/safety.md)", node_, stale_text_.view(),
               stale_);
  }
}

void CommandReports::add_to(ErrorList& errors, Time now) const noexcept {
  if (has_rejection_ && now - rejected_at_ <= visible_for_)
    errors.add("rejected command: {}", rejection_.view());
  if (has_stale_ && now - stale_at_ <= visible_for_) errors.add("{}", stale_text_.view());
}

}  // namespace hubrt::runtime
