// hubd's log sink: formatted lines to stderr with write(2), colored on a terminal. A line that
// cannot be written (stderr a closed pipe — `hubd | head`, an SSH session gone — or a full disk)
// is dropped quietly and counted, never fatal: hubd ignores SIGPIPE, so the write fails with EPIPE
// instead of killing the process, and this sink neither throws (spdlog would print a "LOG ERROR"
// to the same dead stderr) nor retries.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>

#include <spdlog/sinks/base_sink.h>

namespace hubrt::hubd {

// Thread-safety: spdlog's base_sink serialises sink_it_; the counter is atomic.
class StderrSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  // `colors`: wrap each line's level name (the pattern's %^...%$) in ANSI colors.
  // `dropped`: counts the lines not written; must outlive the sink.
  StderrSink(bool colors, std::atomic<std::uint64_t>& dropped) : colors_(colors), dropped_(dropped) {}

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override;
  void flush_() override {}  // write(2) is unbuffered

 private:
  bool colors_;
  std::atomic<std::uint64_t>& dropped_;
};

}  // namespace hubrt::hubd
