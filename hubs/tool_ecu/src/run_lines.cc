#include "run_lines.h"

namespace hubrt::tool_ecu {

std::string_view to_string(RunOutput output) noexcept {
  switch (output) {
    case RunOutput::kForward:
      return "forward";
    case RunOutput::kReverse:
      return "reverse";
    case RunOutput::kIdle:
      break;
  }
  return "idle";
}

void RunLines::write(Line& line, bool level, Time now) noexcept {
  const Status written = line.output.write(level, now);
  // A line that is not open is reported as such (report()), not as a failed write.
  line.write_error =
      written.code() == ErrorCode::kUnavailable && !line.output.is_open() ? ErrorCode::kOk : written.code();
}

void RunLines::drive(RunOutput output, Time now) noexcept {
  const bool run = output != RunOutput::kIdle;
  const bool reverse = output == RunOutput::kReverse;
  Line& forward_line = lines_[0];
  Line& reverse_line = lines_[1];
  // driven() is the level a line is at: false while it is not open (nothing drives it) and its
  // `initial` level right after it was opened again.
  if (reverse_line.output.driven() != reverse && forward_line.output.driven())
    write(forward_line, false, now);
  // The direction only changes once the run enable is off.
  if (!forward_line.output.driven() || reverse_line.output.driven() == reverse) {
    write(reverse_line, reverse, now);
  }
  if (reverse_line.output.driven() == reverse) {
    write(forward_line, run, now);
  } else if (forward_line.output.driven()) {
    // The direction line could not be set (its chip went away: it drives nothing now, which the
    // tool reads as "forward"): the run enable must not stay on with the wrong direction.
    write(forward_line, false, now);
  }
  update_shown();
}

void RunLines::update_shown() noexcept {
  if (!lines_[0].output.driven()) {
    shown_ = RunOutput::kIdle;
  } else {
    shown_ = lines_[1].output.driven() ? RunOutput::kReverse : RunOutput::kForward;
  }
}

void RunLines::drive_safe() noexcept {
  for (Line& line : lines_) {
    if (!line.output.is_open()) continue;
    line.write_error = line.output.write_safe_if_open().code();
  }
  update_shown();
}

void RunLines::report(runtime::ErrorList& errors) const noexcept {
  for (const Line& line : lines_) {
    if (!line.output.is_open()) {
      errors.add("run line {} not available: {}", line.output.config().signal, line.output.error());
    } else if (line.write_error != ErrorCode::kOk) {
      errors.add("run line {}: write failed ({})", line.output.config().signal, to_string(line.write_error));
    }
  }
}

}  // namespace hubrt::tool_ecu
