#include "stderr_sink.h"

#include <unistd.h>

#include <array>
#include <cerrno>
#include <string_view>

namespace hubrt::hubd {
namespace {

// Writes all of `text` to stderr; false when the kernel refuses (EPIPE, EBADF, EIO, ENOSPC...).
bool write_all(std::string_view text) noexcept {
  while (!text.empty()) {
    const ssize_t n = ::write(STDERR_FILENO, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    text.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

// ANSI colors of the level names, trace..critical (as spdlog's ansicolor_sink).
constexpr std::array<std::string_view, 7> kLevelColors{
    "\033[37m", "\033[36m", "\033[32m", "\033[33m\033[1m", "\033[31m\033[1m", "\033[1m\033[41m", ""};
constexpr std::string_view kReset = "\033[m";

}  // namespace

void StderrSink::sink_it_(const spdlog::details::log_msg& msg) {
  spdlog::memory_buf_t formatted;
  formatter_->format(msg, formatted);
  const std::string_view line(formatted.data(), formatted.size());
  bool ok = true;
  const auto level = static_cast<std::size_t>(msg.level);
  if (colors_ && msg.color_range_end > msg.color_range_start && level < kLevelColors.size()) {
    ok = write_all(line.substr(0, msg.color_range_start)) && write_all(kLevelColors[level]) &&
         write_all(line.substr(msg.color_range_start, msg.color_range_end - msg.color_range_start)) &&
         write_all(kReset) && write_all(line.substr(msg.color_range_end));
  } else {
    ok = write_all(line);
  }
  if (!ok) dropped_.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace hubrt::hubd
