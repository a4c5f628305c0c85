// The process's Cyclone log sink (oversize_samples.cc): Cyclone has one per process
// (dds_set_log_sink), so the oversize count and the security refusals share it.
#pragma once

namespace hubrt::dds::detail {

// Installs the sink once per process (later calls do nothing). Thread-safe.
void install_process_log_sink() noexcept;

}  // namespace hubrt::dds::detail
