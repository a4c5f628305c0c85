// Two hubs with the same name must never both run: both would publish the same State topics
// (interleaved, sequence numbers going backwards) and both would act on the same commands. These
// are the pure rules hubd applies (assembly/twin_watch.h does the DDS side):
//   - a "twin" is another participant writing one of this hub's State topics;
//   - which of two hubs is the later one: the one that started later (wall clock, carried in the
//     participant's USER_DATA as "hubrt.started_ns=<ns>;"), ties broken by the larger participant
//     GUID — both hubs see the same two stamps, so both reach the same verdict;
//   - what every node reports while a twin is there, and for a while after it left.
// Deterministic: time is passed in. Allocation-free except where noted.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/time.h"
#include "hubrt/dds/guid.h"
#include "hubrt/dds/writer_watch.h"
#include "hubrt/runtime/hub_alerts.h"
#include "hubrt/runtime/text_buffer.h"

namespace hubrt::assembly {

// The start stamp alone: "hubrt.started_ns=<ns>;" (what hubs before the identity below sent).
// Allocates.
std::string start_stamp_user_data(std::int64_t started_ns);
// The participant USER_DATA a hub publishes: its start stamp and which hub it is,
// "hubrt.started_ns=<ns>;hubrt.hub=<ros_namespace>/<hub>;". The identity travels in SPDP, so
// another hub knows it is a twin as soon as it discovers the participant, before any endpoint
// (SEDP) arrives. Allocates.
std::string hub_user_data(std::int64_t started_ns, std::string_view ros_namespace, std::string_view hub);
// The start stamp in a participant's USER_DATA; nullopt when it carries none (not a hub).
std::optional<std::int64_t> parse_start_stamp(std::string_view user_data) noexcept;
// The hub identity "<ros_namespace>/<hub>" in a participant's USER_DATA; nullopt when it carries
// none (not a hub, or a hub of an older hubrt that sent only its start stamp).
std::optional<std::string_view> parse_hub_identity(std::string_view user_data) noexcept;

struct HubStamp {
  std::int64_t started_ns = 0;
  dds::Guid participant;
};
// True when `a` is the later of the two hubs: it started later, or at the same nanosecond with
// the larger GUID. Exactly one of is_later(a, b) and is_later(b, a) holds for distinct GUIDs.
bool is_later(const HubStamp& a, const HubStamp& b) noexcept;

// True for the DDS topic names that carry this hub's States in either layout:
// "rt<ns>/<hub>/state" (hub layout) and "rt<ns>/<hub>/<node>/state" (node-type layout). Both, so
// that a twin running the other layout is caught too. Commands, /diagnostics and /sim topics
// (hubctl, hubsim, the sim bridge) never match.
bool is_own_state_topic(std::string_view dds_topic, std::string_view ros_namespace,
                        std::string_view hub) noexcept;

// One other participant writing this hub's States, in fixed storage (the cycle copies it).
struct TwinPeer {
  dds::Guid participant;
  runtime::TextBuffer<96> topic;  // ROS name of the first of its writers, e.g. "/dock_ecu/dock/state"
  std::uint32_t topics = 0;       // how many of this hub's State topics it writes
  runtime::TextBuffer<64> host;   // empty when DDS did not say
  runtime::TextBuffer<20> pid;    // empty when DDS did not say
  std::optional<std::int64_t> started_ns;  // its hub start stamp; nullopt: not a hub (e.g. a tool)
};

struct TwinSnapshot {
  static constexpr std::size_t kMaxPeers = 3;
  std::array<TwinPeer, kMaxPeers> peers{};
  std::size_t count = 0;  // peers in use
  std::size_t more = 0;   // further twins that did not fit
  // Every list with a twin counts one sighting, and `last` keeps its first twin: a twin that came
  // and went between two cycles is still reported (TwinMonitor compares the count).
  std::uint64_t sightings = 0;
  TwinPeer last{};
};

// Groups the watched writers by participant (the list from dds::WriterWatch). Allocates.
TwinSnapshot summarize_twins(const std::vector<dds::WatchedWriter>& writers);

// "host pi-tool pid 4242", or "participant <guid>" when DDS gave neither.
void describe_origin(const TwinPeer& peer, runtime::TextBuffer<128>& out) noexcept;

// The start-up check's verdict on what discovery has shown so far. Deterministic: time passed in.
// Rules (docs/twin-hubs.md, "Start-up check"):
//   - twin: a writer of this hub's States was seen, or a participant announced this hub's identity
//     in its USER_DATA (the verdict then waits up to `quiet` for its writers, to name them);
//   - alone: discovery has settled — no participant was newly discovered for `quiet` since the
//     check began (Cyclone answers a new participant's SPDP at once: SPDPResponseMaxDelay is 0 ms
//     by default, q_ddsi_discovery.c respond_to_spdp), and every hub discovered so far said which
//     hub it is (an older hub that sent only its start stamp could be a twin whose endpoints have
//     not arrived yet: that one makes the check wait out the whole window);
//   - alone as well once the window is over.
enum class StartupVerdict : std::uint8_t { kWait, kAlone, kTwin };

class StartupCheck {
 public:
  // `identity`: this hub's "<ros_namespace>/<hub>"; the check begins at `begin`.
  StartupCheck(std::string identity, Time begin, Duration window, Duration quiet)
      : identity_(std::move(identity)), begin_(begin), last_new_(begin), window_(window), quiet_(quiet) {}

  // `participants`: every other participant known now; `discovered`: how many were newly
  // discovered since the watch began (grows); `twin_writers`: writers of this hub's States seen.
  StartupVerdict update(const std::vector<dds::WatchedParticipant>& participants, std::uint64_t discovered,
                        std::size_t twin_writers, Time now) {
    return update(participants, discovered, now, twin_writers, now);
  }
  // The same, with `discovered_at`: when `discovered` last grew (dds::WriterWatch::
  // last_discovered_at), so that a check which looks only now and then (the caller did other work
  // meanwhile) restarts the quiet time from the discovery, not from when it looked. Clamped to
  // [begin, now]: never earlier than the check, never in the future.
  StartupVerdict update(const std::vector<dds::WatchedParticipant>& participants, std::uint64_t discovered,
                        Time discovered_at, std::size_t twin_writers, Time now);
  // When, if nothing new is discovered, the next update() can first return a verdict: the end of
  // the quiet time after the last newly discovered participant (or after a twin's identity was
  // seen), or the end of the window, whichever comes first. The start-up check sleeps until then
  // instead of polling at a fixed step, so its verdict comes when the rule allows, not up to one
  // polling step later. Valid after the last update(); begin + quiet before any.
  [[nodiscard]] Time decides_by() const noexcept;
  // True when the verdict came from a participant's identity before any of its writers was seen.
  [[nodiscard]] bool twin_by_identity() const noexcept { return claimed_; }
  // The participant that announced this hub's identity (meaningful when twin_by_identity()).
  [[nodiscard]] const dds::Guid& claimant() const noexcept { return claimant_; }
  // A twin known by its identity alone (SPDP) names only a participant GUID; its State writer
  // (SEDP) names the topic, host and pid an engineer needs to find it. update() waits for the
  // writer up to `quiet`, enough on a quiet host; on a loaded one (a fresh machine's test suite
  // with the TSan build beside it) the writer came after the verdict and the refusal named only
  // the GUID. So the refusal, once decided, waits up to this much longer for a name to give.
  static constexpr Duration kNamingGrace = std::chrono::seconds(2);
  // True while the refusal should still wait for a name: the verdict was a twin by identity alone,
  // `twin_writers` (writers of this hub's States seen now) is still 0, and kNamingGrace since the
  // verdict has not passed.
  [[nodiscard]] bool waits_for_name(std::size_t twin_writers, Time now) const noexcept {
    return twin_decided_at_ && twin_writers == 0 && now - *twin_decided_at_ < kNamingGrace;
  }

 private:
  std::string identity_;
  Time begin_;
  Time last_new_;
  Duration window_;
  Duration quiet_;
  std::uint64_t discovered_ = 0;
  bool unnamed_hub_ = false;  // a hub without an identity was seen: only the window ends the check
  bool claimed_ = false;
  Time claimed_at_{};
  dds::Guid claimant_{};
  std::optional<Time> twin_decided_at_;  // when update() first returned kTwin by identity
};

// Turns the twins seen each cycle into the hub's alerts and the verdict.
// Thread-safety: one thread (the cycle).
class TwinMonitor {
 public:
  // A twin that left is still reported for `hold`, so that the planner and operator see it even
  // when the later hub went away within a cycle or two.
  TwinMonitor(HubStamp self, Duration hold) noexcept : self_(self), hold_(hold) {}

  // Sets `alerts` (cleared first) from the twins present at `now`.
  void update(const TwinSnapshot& current, Time now, runtime::HubAlerts& alerts) noexcept;
  // True once a hub that started earlier than this one was seen: this one must go to its safe
  // state and exit. A twin that is no hub (no start stamp) is reported but never wins.
  [[nodiscard]] bool must_yield() const noexcept { return must_yield_; }
  // The hub this one yields to (meaningful when must_yield()).
  [[nodiscard]] const TwinPeer& yielded_to() const noexcept { return yielded_to_; }

 private:
  HubStamp self_;
  Duration hold_;
  TwinPeer last_seen_{};
  Time last_seen_at_{};
  bool seen_ = false;
  std::uint64_t sightings_ = 0;
  bool must_yield_ = false;
  TwinPeer yielded_to_{};
};

}  // namespace hubrt::assembly
