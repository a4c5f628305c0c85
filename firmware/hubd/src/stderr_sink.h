// hubd's log sink: formatted lines to stderr, colored on a terminal, through a bounded queue and
// a writer thread of its own (log_queue.h), so that logging never waits for stderr. A line that
// cannot be written (stderr a closed pipe — `hubd | head`, an SSH session gone — or a full disk)
// or finds the queue full (a reader that stopped reading) is dropped quietly and counted, never
// fatal: hubd ignores SIGPIPE, so a write fails with EPIPE instead of killing the process, and
// this sink neither throws (spdlog would print a "LOG ERROR" to the same dead stderr) nor retries.
#pragma once

#include <mutex>

#include <spdlog/sinks/base_sink.h>

#include "log_queue.h"

namespace hubrt::hubd {

// Thread-safety: spdlog's base_sink serialises sink_it_ (formatting and queueing: bounded work,
// never a write).
class StderrSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  // `colors`: wrap each line's level name (the pattern's %^...%$) in ANSI colors.
  // `queue`: where the lines go (it counts what it drops); must outlive the sink.
  StderrSink(bool colors, LogQueue& queue) : colors_(colors), queue_(queue) {}

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override;
  void flush_() override {}  // the writer thread writes each line at once

 private:
  bool colors_;
  LogQueue& queue_;
};

}  // namespace hubrt::hubd
