// hubd logs to stderr. Under systemd (JOURNAL_STREAM set) it leaves out the timestamp the journal
// adds anyway and prefixes each line with its syslog priority, "<3>" for errors, so that
// `journalctl -p err` finds them.
#pragma once

#include <memory>
#include <string>

#include <spdlog/logger.h>

#include "hubrt/base/status.h"

namespace hubrt::hubd {

// Errors: kInvalidArgument for an unknown level name (trace, debug, info, warn, error, critical, off).
Expected<std::shared_ptr<spdlog::logger>> make_logger(const std::string& name, const std::string& level);

}  // namespace hubrt::hubd
