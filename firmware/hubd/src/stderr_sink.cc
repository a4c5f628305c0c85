#include "stderr_sink.h"

#include <array>
#include <string_view>

namespace hubrt::hubd {
namespace {

// ANSI colors of the level names, trace..critical (as spdlog's ansicolor_sink).
constexpr std::array<std::string_view, 7> kLevelColors{
    "\033[37m", "\033[36m", "\033[32m", "\033[33m\033[1m", "\033[31m\033[1m", "\033[1m\033[41m", ""};
constexpr std::string_view kReset = "\033[m";

}  // namespace

void StderrSink::sink_it_(const spdlog::details::log_msg& msg) {
  spdlog::memory_buf_t formatted;
  formatter_->format(msg, formatted);
  const std::string_view line(formatted.data(), formatted.size());
  const auto level = static_cast<std::size_t>(msg.level);
  if (colors_ && msg.color_range_end > msg.color_range_start && level < kLevelColors.size()) {
    queue_.push({line.substr(0, msg.color_range_start), kLevelColors[level],
                 line.substr(msg.color_range_start, msg.color_range_end - msg.color_range_start), kReset,
                 line.substr(msg.color_range_end)});
  } else {
    queue_.push({line});
  }
}

}  // namespace hubrt::hubd
