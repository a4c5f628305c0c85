// Counting the samples Cyclone discards for being larger than Internal/MaxSampleSize
// (dds/domain.h, kMaxSampleSizeBytes), so that /diagnostics can say a peer sends oversize data.
//
// Cyclone drops them inside its receive path and offers no status for it: SAMPLE_LOST and
// SAMPLE_REJECTED are raised by the reader history (dds_rhc_default.c), which such a sample never
// reaches. What it does is log one warning per dropped sample (Cyclone 0.10.2
// src/core/ddsi/src/q_receive.c, drop_oversize: "dropping oversize (%u > %u) sample ..." once
// the gap it pushes for the sample's sequence number had an effect, so once per sample, not per
// fragment; "... SPDP sample ..." for oversize discovery). count_oversize_samples() installs a
// Cyclone log sink (dds_set_log_sink, dds/ddsrt/log.h) that counts those warnings.
//
// Limits (from the same function): a sample from a writer this process has not discovered yet is
// dropped without a warning (there is no proxy writer to push the gap through), and so is one
// from a best-effort writer (nn_reorder_gap in q_radmin.c rejects gaps in that mode, so the gap
// "had no effect"). Such samples are dropped all the same; they are just not counted.
#pragma once

#include <cstdint>
#include <string_view>

namespace hubrt::dds {

// Installs the counting log sink, once per process (later calls do nothing). The sink writes
// every message on stderr exactly as Cyclone's default sink does, and adds the discard warnings
// to the count. Call before the first participant, so that no warning is missed. The sink runs
// on Cyclone's threads; counting is one relaxed atomic increment, no allocation.
// Thread-safe.
void count_oversize_samples() noexcept;

// Where the counting sink sends each of Cyclone's log lines (header, message and newline) and the
// rate-limited lines of security refusals (security_refusals.h), instead of writing them to stderr
// itself: hubd's bounded log queue, so that a Cyclone thread that logs —
// or the cycle inside a Cyclone call that logs — never waits for a stderr nobody reads. nullptr:
// stderr (the default). `forward` must not block and must be callable from any thread; it is
// called under Cyclone's log lock. Thread-safe.
using CycloneLogForward = void (*)(std::string_view line) noexcept;
void forward_cyclone_log(CycloneLogForward forward) noexcept;

// Whether count_oversize_samples() was called in this process.
[[nodiscard]] bool oversize_samples_counted() noexcept;

// Oversize samples Cyclone dropped in this process since count_oversize_samples(), over all
// domains and topics. Thread-safe, lock-free.
[[nodiscard]] std::uint64_t oversize_samples_dropped() noexcept;

// Whether `message` (a Cyclone log message without its header) is Cyclone's discard warning for
// an oversize sample. Exposed for tests.
[[nodiscard]] bool is_oversize_drop_message(std::string_view message) noexcept;

}  // namespace hubrt::dds
