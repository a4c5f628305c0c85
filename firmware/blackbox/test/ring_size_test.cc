// The ring a hub gets when its hub file names no size: it holds the whole span of the station's
// own samples at their largest, for the rates the station's hubs run at, and a slow hub's ring is
// a fraction of the 8 MiB every hub took before.
#include "hubrt/blackbox/ring_size.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/blackbox/ring.h"

namespace hubrt::blackbox {
namespace {

using std::chrono::seconds;

// The largest samples read from the simulated station's black box files (ring_size.h).
constexpr std::size_t kLargestState = 252;
constexpr std::size_t kCommand = 40;
constexpr std::size_t kLargestDiagnostics = 1260;

struct Hub {
  std::size_t nodes;
  double rate_hz;
  double diagnostics_hz;
};
void PrintTo(const Hub& hub, std::ostream* os) {
  *os << hub.nodes << " nodes at " << hub.rate_hz << " Hz, /diagnostics at " << hub.diagnostics_hz << " Hz";
}

// Plays `played` of a hub's traffic into `ring` at its rates, 1 ms per step; returns the newest time.
std::uint64_t play(Ring& ring, const Hub& hub, Duration played) {
  const RecordedRates rates = hub_recorded_rates(hub.nodes, hub.rate_hz, hub.diagnostics_hz);
  const std::vector<std::uint8_t> state(kLargestState, 1);
  const std::vector<std::uint8_t> command(kCommand, 2);
  const std::vector<std::uint8_t> diagnostics(kLargestDiagnostics, 3);
  struct Stream {
    double per_second;
    const std::vector<std::uint8_t>* bytes;
    double due = 0;
  };
  std::vector<Stream> streams = {{rates.states_per_second, &state},
                                 {rates.commands_per_second, &command},
                                 {rates.diagnostics_per_second, &diagnostics}};
  const auto steps = std::chrono::duration_cast<std::chrono::milliseconds>(played).count();
  std::uint64_t now_ns = 0;
  for (std::int64_t ms = 0; ms < steps; ++ms) {
    now_ns = static_cast<std::uint64_t>(ms) * 1'000'000;
    for (std::uint16_t s = 0; s < streams.size(); ++s) {
      Stream& stream = streams[s];
      if (stream.per_second <= 0) continue;
      // Several samples within one millisecond when the rate is above 1 kHz (a node count x rate).
      while (stream.due <= static_cast<double>(ms)) {
        ring.record(s, *stream.bytes, now_ns, now_ns);
        stream.due += 1000.0 / stream.per_second;
      }
    }
  }
  return now_ns;
}

// The log time of the oldest entry the ring still holds.
std::uint64_t oldest(const Ring& ring) {
  std::uint64_t first = std::numeric_limits<std::uint64_t>::max();
  ring.visit_unlocked([&](const RingEntry& e) { first = std::min(first, e.log_time); });
  return first;
}

class RingSizeForHub : public ::testing::TestWithParam<Hub> {};

TEST_P(RingSizeForHub, HoldsTheWholeSpanOfItsLargestSamples) {
  const Hub hub = GetParam();
  const Duration span = seconds(60);
  Ring ring(ring_bytes_for(span, hub_recorded_rates(hub.nodes, hub.rate_hz, hub.diagnostics_hz)));
  const std::uint64_t newest = play(ring, hub, seconds(90));  // past the span: the ring has wrapped
  ASSERT_GT(ring.evicted(), 0U) << "the ring never filled: the test would not see a short span";
  EXPECT_EQ(ring.refused(), 0U);
  const auto span_ns = static_cast<std::uint64_t>(std::chrono::nanoseconds(span).count());
  EXPECT_LE(oldest(ring), newest - span_ns)
      << "a " << hub.rate_hz << " Hz hub of " << hub.nodes << " nodes keeps only "
      << static_cast<double>(newest - oldest(ring)) / 1e9 << " s in " << ring.capacity() << " bytes";
}

// The station's hubs: the Dock ECU at its shipped 10 Hz and at the benchmarks' 100 Hz, the tool
// ECU's three nodes, a hub without /diagnostics, one at 200 Hz.
INSTANTIATE_TEST_SUITE_P(StationHubs, RingSizeForHub,
                         ::testing::Values(Hub{1, 10, 1}, Hub{1, 100, 1}, Hub{3, 10, 1}, Hub{1, 10, 0},
                                           Hub{2, 200, 2}),
                         [](const ::testing::TestParamInfo<Hub>& param) {
                           return "nodes" + std::to_string(param.param.nodes) + "_at_" +
                                  std::to_string(static_cast<int>(param.param.rate_hz)) + "Hz_diagnostics_" +
                                  std::to_string(static_cast<int>(param.param.diagnostics_hz)) + "Hz";
                         });

TEST(RingSize, ASlowHubTakesAFractionOfTheFixedSizeItHadBefore) {
  const std::size_t dock = ring_bytes_for(seconds(60), hub_recorded_rates(1, 10, 1));
  EXPECT_LE(dock, std::size_t{512} << 10);  // a 10 Hz Dock ECU: about 0.45 MiB, not 8
  EXPECT_EQ(dock % 4096, 0U);
  const std::size_t fast = ring_bytes_for(seconds(60), hub_recorded_rates(1, 100, 1));
  EXPECT_GT(fast, dock);
  EXPECT_LE(fast, std::size_t{3} << 20);
}

TEST(RingSize, StaysWithinItsBoundsWhateverTheRates) {
  EXPECT_EQ(ring_bytes_for(seconds(60), RecordedRates{}), kMinRingBytes);
  EXPECT_EQ(ring_bytes_for(seconds(1), hub_recorded_rates(1, 1, 0)), kMinRingBytes);
  EXPECT_EQ(ring_bytes_for(seconds(60), hub_recorded_rates(1, 1000, 1)), kMaxRingBytes);
  EXPECT_EQ(ring_bytes_for(seconds(3600), hub_recorded_rates(64, 1000, 10)), kMaxRingBytes);
  EXPECT_EQ(ring_bytes_for(seconds(60), RecordedRates{std::nan(""), 0, 0}), kMaxRingBytes);
  EXPECT_EQ(ring_bytes_for(seconds(60), RecordedRates{std::numeric_limits<double>::infinity(), 0, 0}),
            kMaxRingBytes);
}

}  // namespace
}  // namespace hubrt::blackbox
