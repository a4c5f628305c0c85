// hubd logs to stderr. Under systemd (JOURNAL_STREAM set) it leaves out the timestamp the journal
// adds anyway and prefixes each line with its syslog priority, "<3>" for errors, so that
// `journalctl -p err` finds them. Lines reach stderr through a bounded queue and a writer thread
// (log_queue.h): nothing that logs waits for stderr. A line stderr does not take (a closed pipe)
// or that finds the queue full (a reader that stopped reading) is dropped and counted
// (stderr_sink.h), never fatal. Cyclone's own log lines take the same path.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include <spdlog/logger.h>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"

namespace hubrt::hubd {

// Errors: kInvalidArgument for an unknown level name (trace, debug, info, warn, error, critical, off).
// Also makes it spdlog's default logger. Call once.
Expected<std::shared_ptr<spdlog::logger>> make_logger(const std::string& name, const std::string& level);

// Log lines dropped so far: stderr refused them, or the queue to it was full. Thread-safe.
const std::atomic<std::uint64_t>& log_lines_dropped() noexcept;

// Waits up to `timeout` for the queued lines to be written (longer while they are being written:
// LogQueue::finish), then stops the writer thread (left blocked in write(2) when nobody reads
// stderr: the process ends around it). Call once, at the
// very end; later lines are dropped and counted. Returns true when every line was written.
bool finish_logging(Duration timeout) noexcept;
inline constexpr Duration kLogFinishTimeout = std::chrono::milliseconds(500);

}  // namespace hubrt::hubd
