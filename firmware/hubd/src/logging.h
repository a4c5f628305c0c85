// hubd logs to stderr. Under systemd (JOURNAL_STREAM set) it leaves out the timestamp the journal
// adds anyway and prefixes each line with its syslog priority, "<3>" for errors, so that
// `journalctl -p err` finds them. A line stderr does not take (a closed pipe) is dropped and
// counted (stderr_sink.h), never fatal.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include <spdlog/logger.h>

#include "hubrt/base/status.h"

namespace hubrt::hubd {

// Errors: kInvalidArgument for an unknown level name (trace, debug, info, warn, error, critical, off).
// Also makes it spdlog's default logger. Call once.
Expected<std::shared_ptr<spdlog::logger>> make_logger(const std::string& name, const std::string& level);

// Log lines dropped so far because stderr refused them. Thread-safe.
const std::atomic<std::uint64_t>& log_lines_dropped() noexcept;

}  // namespace hubrt::hubd
