#include "hubrt/dds/oversize_samples.h"

#include <atomic>
#include <cstdio>

#include <dds/dds.h>

#include "hubrt/dds/security_refusals.h"

#include "log_sink.h"

namespace hubrt::dds {
namespace {

// The start of both discard warnings of drop_oversize() in Cyclone 0.10.2
// src/core/ddsi/src/q_receive.c.
constexpr std::string_view kDropPrefix = "dropping oversize (";

std::atomic<std::uint64_t> g_dropped{0};
std::atomic<bool> g_oversize_counted{false};
std::atomic<bool> g_sink_installed{false};
std::atomic<CycloneLogForward> g_forward{nullptr};

// dds_log_write_fn_t. `data->message` is preceded by `data->hdrsize` bytes of header and
// followed by a newline: what Cyclone's default sink (src/ddsrt/src/log.c, default_sink) writes.
// A security refusal is written by observe_security_log instead, rate-limited.
void count_and_forward(void* /*arg*/, const dds_log_data_t* data) {
  const std::string_view message(data->message, data->size);
  if ((data->priority & DDS_LC_WARNING) != 0 && is_oversize_drop_message(message))
    g_dropped.fetch_add(1, std::memory_order_relaxed);
  if ((data->priority & (DDS_LC_WARNING | DDS_LC_ERROR)) != 0 &&
      detail::observe_security_log(data->file != nullptr ? data->file : "",
                                   data->function != nullptr ? data->function : "", message)) {
    return;
  }
  detail::write_log_line({data->message - data->hdrsize, data->hdrsize + data->size + 1});
}

}  // namespace

namespace detail {

void write_log_line(std::string_view line) noexcept {
  if (const CycloneLogForward forward = g_forward.load(std::memory_order_acquire); forward != nullptr) {
    forward(line);
    return;
  }
  (void)std::fwrite(line.data(), 1, line.size(), stderr);
  (void)std::fflush(stderr);
}

void install_process_log_sink() noexcept {
  if (g_sink_installed.exchange(true, std::memory_order_acq_rel)) return;
  // dds_set_log_sink takes Cyclone's log lock for writing, so no thread still uses the old sink
  // when it returns (src/ddsrt/src/log.c, set_log_sink).
  dds_set_log_sink(&count_and_forward, nullptr);
  // Warnings are in Cyclone's default log mask; make sure they stay there.
  dds_set_log_mask(dds_get_log_mask() | DDS_LC_WARNING | DDS_LC_ERROR);
}

}  // namespace detail

bool is_oversize_drop_message(std::string_view message) noexcept {
  return message.starts_with(kDropPrefix);
}

void count_oversize_samples() noexcept {
  if (g_oversize_counted.exchange(true, std::memory_order_acq_rel)) return;
  detail::install_process_log_sink();
}

void forward_cyclone_log(CycloneLogForward forward) noexcept {
  g_forward.store(forward, std::memory_order_release);
}

bool oversize_samples_counted() noexcept {
  return g_oversize_counted.load(std::memory_order_acquire);
}

std::uint64_t oversize_samples_dropped() noexcept {
  return g_dropped.load(std::memory_order_relaxed);
}

}  // namespace hubrt::dds
