#include "hubrt/blackbox/ring_size.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace hubrt::blackbox {

RecordedRates hub_recorded_rates(std::size_t nodes, double rate_hz, double diagnostics_hz) noexcept {
  const auto n = static_cast<double>(nodes);
  return RecordedRates{n * rate_hz, n * kCommandsPerNodePerSecond, diagnostics_hz};
}

std::size_t ring_bytes_for(Duration span, const RecordedRates& rates) noexcept {
  const double seconds = std::chrono::duration<double>(span).count();
  const double per_second = rates.states_per_second * static_cast<double>(kStateEntryBytes) +
                            rates.commands_per_second * static_cast<double>(kCommandEntryBytes) +
                            rates.diagnostics_per_second * static_cast<double>(kDiagnosticsEntryBytes);
  const double wanted = seconds * per_second;
  // Checked in double first: a rate from a hub file is at most 1000 Hz and a span an hour, but a
  // NaN or an overflowing product must not wrap.
  if (!(wanted < static_cast<double>(kMaxRingBytes))) return kMaxRingBytes;
  if (!(wanted > 0)) return kMinRingBytes;
  constexpr std::size_t kPage = 4096;
  const auto bytes = static_cast<std::size_t>(std::ceil(wanted / kPage)) * kPage;
  return std::clamp(bytes, kMinRingBytes, kMaxRingBytes);
}

}  // namespace hubrt::blackbox
