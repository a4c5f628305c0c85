#include "run_lines.h"

#include <fmt/format.h>

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

Expected<RunLines> RunLines::create(std::string_view run_forward, std::string_view run_reverse,
                                    const hal::BoardConfig& board, hal::Backend& backend, Time now) {
  RunLines lines(backend);
  const std::array<std::string_view, 2> names{run_forward, run_reverse};
  for (std::size_t i = 0; i < names.size(); ++i) {
    const hal::BoardOutput* output = board.find_output(names[i]);
    if (output == nullptr) {
      return make_error(ErrorCode::kNotFound,
                        fmt::format("smart tool: board {} has no output '{}'", board.file, names[i]));
    }
    lines.lines_[i].config = output->config;
    lines.lines_[i].level = output->config.initial;
    lines.open(lines.lines_[i], now);
  }
  lines.next_open_ = now + kReopenInterval;
  return lines;
}

void RunLines::open(Line& line, Time /*now*/) {
  auto opened = backend_->open_output(line.config);
  if (!opened) {
    line.open_error.assign(opened.error().message);
    return;
  }
  line.output = std::move(*opened);
  line.open_error.clear();
  line.level = line.config.initial;
}

bool RunLines::write(Line& line, bool level, Time now) noexcept {
  if (line.output == nullptr) {
    if (now < next_open_) return false;
    open(line, now);
    if (line.output == nullptr) return false;
  }
  const Status written = line.output->write(level);
  line.write_error = written.code();
  if (written.is_ok()) line.level = level;
  return written.is_ok();
}

void RunLines::drive(RunOutput output, Time now) noexcept {
  const bool run = output != RunOutput::kIdle;
  const bool reverse = output == RunOutput::kReverse;
  Line& forward_line = lines_[0];
  Line& reverse_line = lines_[1];
  if (reverse_line.level != reverse && forward_line.level) write(forward_line, false, now);
  // The direction only changes once the run enable is off.
  if (!forward_line.level || reverse_line.level == reverse) write(reverse_line, reverse, now);
  if (reverse_line.level == reverse) write(forward_line, run, now);
  if (now >= next_open_) next_open_ = now + kReopenInterval;
  update_shown();
}

void RunLines::update_shown() noexcept {
  if (!lines_[0].level) {
    shown_ = RunOutput::kIdle;
  } else {
    shown_ = lines_[1].level ? RunOutput::kReverse : RunOutput::kForward;
  }
}

void RunLines::drive_safe() noexcept {
  for (Line& line : lines_) {
    if (line.output == nullptr) continue;
    const Status written = line.output->write_safe();
    line.write_error = written.code();
    if (written.is_ok()) line.level = line.output->safe_value();
  }
  update_shown();
}

void RunLines::report(runtime::ErrorList& errors) const noexcept {
  for (const Line& line : lines_) {
    if (line.output == nullptr) {
      errors.add("run line {} not available: {}", line.config.signal, line.open_error.view());
    } else if (line.write_error != ErrorCode::kOk) {
      errors.add("run line {}: write failed ({})", line.config.signal, to_string(line.write_error));
    }
  }
}

}  // namespace hubrt::tool_ecu
