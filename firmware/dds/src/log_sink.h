// The process's Cyclone log sink (oversize_samples.cc): Cyclone has one per process
// (dds_set_log_sink), so the oversize count, the security refusals and the forwarding of every
// line to hubd's log queue (forward_cyclone_log) share it.
#pragma once

#include <string_view>

namespace hubrt::dds::detail {

// Installs the sink once per process (later calls do nothing). Thread-safe.
void install_process_log_sink() noexcept;

// Writes one whole log line (its newline included) where Cyclone's lines go: to the function
// forward_cyclone_log set (hubd's bounded log queue), else on stderr. Never blocks when a forward
// is set; allocates nothing. Thread-safe.
void write_log_line(std::string_view line) noexcept;

}  // namespace hubrt::dds::detail
