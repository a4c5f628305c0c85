#include "matched_count.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include "hubrt/dds/retcode.h"

namespace hubrt::dds::detail {
namespace {

dds_return_t read_matched(dds_entity_t endpoint, EndpointKind kind, std::uint32_t& count) noexcept {
  if (kind == EndpointKind::kWriter) {
    dds_publication_matched_status_t status{};
    const dds_return_t rc = dds_get_publication_matched_status(endpoint, &status);
    count = status.current_count;
    return rc;
  }
  dds_subscription_matched_status_t status{};
  const dds_return_t rc = dds_get_subscription_matched_status(endpoint, &status);
  count = status.current_count;
  return rc;
}

}  // namespace

Result<std::uint32_t> matched_count(dds_entity_t endpoint, EndpointKind kind) noexcept {
  std::uint32_t count = 0;
  const dds_return_t rc = read_matched(endpoint, kind, count);
  if (rc < 0) return to_status(rc);
  return count;
}

Expected<void> wait_for_matched(dds_entity_t endpoint, EndpointKind kind, std::uint32_t wanted,
                                Duration timeout, const std::string& what) {
  // Polled rather than awaited on a waitset: waiting on the entity's status condition would mean
  // changing its status mask, which also governs its listeners. Discovery takes milliseconds, so
  // a 2 ms poll costs nothing here, and this is only used by tests and tools.
  constexpr Duration kPollInterval = std::chrono::milliseconds(2);
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + timeout;
  for (;;) {
    std::uint32_t count = 0;
    const dds_return_t rc = read_matched(endpoint, kind, count);
    if (rc < 0) return dds_error(rc, what);
    if (count >= wanted) return {};
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) {
      return make_error(ErrorCode::kTimeout, what + ": " + std::to_string(count) + " matched after " +
                                                 std::to_string(to_seconds(now - start)) + " s, wanted " +
                                                 std::to_string(wanted));
    }
    std::this_thread::sleep_for(std::min<Duration>(kPollInterval, deadline - now));
  }
}

}  // namespace hubrt::dds::detail
