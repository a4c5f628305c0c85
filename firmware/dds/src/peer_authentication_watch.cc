#include "hubrt/dds/peer_authentication_watch.h"

#include <algorithm>
#include <array>
#include <tuple>

#include <dds/dds.h>
#include <fmt/format.h>

#include "hubrt/dds/security_refusals.h"

#include "builtin_reader.h"

namespace hubrt::dds {
namespace {

// Taken in chunks of this many, always: Cyclone keeps one loan per reader and fills as many
// pointers as its largest loan ever was (writer_watch.cc says why), so the size never changes.
constexpr std::size_t kChunk = 64;

// Takes every sample `reader` holds, handing each (valid or not) with its info to `visit`.
// False when the reader is gone.
template <class Sample, class Visit>
bool take_all(dds_entity_t reader, Visit&& visit) noexcept {
  std::array<void*, kChunk> samples{};
  std::array<dds_sample_info_t, kChunk> infos{};
  for (;;) {
    samples.fill(nullptr);  // null entries: Cyclone lends its own memory
    const dds_return_t n = dds_take(reader, samples.data(), infos.data(), kChunk, kChunk);
    if (n < 0) return false;
    for (dds_return_t i = 0; i < n; ++i) visit(*static_cast<const Sample*>(samples[i]), infos[i]);
    if (n > 0) (void)dds_return_loan(reader, samples.data(), n);
    if (static_cast<std::size_t>(n) < kChunk) return true;
  }
}

}  // namespace

Expected<std::unique_ptr<PeerAuthenticationWatch>> PeerAuthenticationWatch::start(
    const Participant& participant, std::chrono::nanoseconds grace) {
  std::unique_ptr<PeerAuthenticationWatch> watch(new PeerAuthenticationWatch(participant.guid(), grace));
  for (auto [topic, name, slot] :
       {std::tuple{DDS_BUILTIN_TOPIC_DCPSPARTICIPANT, "DCPSParticipant", &watch->participants_},
        std::tuple{DDS_BUILTIN_TOPIC_DCPSPUBLICATION, "DCPSPublication", &watch->publications_},
        std::tuple{DDS_BUILTIN_TOPIC_DCPSSUBSCRIPTION, "DCPSSubscription", &watch->subscriptions_}}) {
    auto reader = detail::listening_builtin_reader(participant, topic, name, "watch peer authentication",
                                                   watch.get(), &PeerAuthenticationWatch::on_data_available);
    if (!reader) return std::move(reader).error();
    *slot = std::move(*reader);
  }
  watch->ready_ = true;
  watch->refresh();  // what was discovered before the listeners were in place
  return watch;
}

PeerAuthenticationWatch::~PeerAuthenticationWatch() {
  ready_ = false;
  subscriptions_.reset();
  publications_.reset();
  participants_.reset();
}

void PeerAuthenticationWatch::on_data_available(dds_entity_t /*reader*/, void* arg) noexcept {
  auto* watch = static_cast<PeerAuthenticationWatch*>(arg);
  if (watch->ready_) watch->refresh();
}

PeerAuthenticationWatch::Peer* PeerAuthenticationWatch::find_or_add(
    const Guid& key, std::chrono::steady_clock::time_point now) noexcept {
  Peer* free = nullptr;
  for (Peer& p : peers_) {
    if (p.used && p.key == key) return &p;
    if (free == nullptr && (!p.used || p.settled)) free = &p;  // one gone and judged leaves its slot
  }
  if (free == nullptr) return nullptr;
  *free = Peer{key, now, {}, true, true, false, false, false};
  return free;
}

void PeerAuthenticationWatch::refresh() noexcept {
  const std::lock_guard lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  (void)take_all<dds_builtintopic_participant_t>(
      participants_.get(), [&](const dds_builtintopic_participant_t& p, const dds_sample_info_t& info) {
        const Guid key = Guid::from(p.key);
        if (key == self_) return;
        if (info.instance_state == DDS_IST_ALIVE) {
          if (info.valid_data) (void)find_or_add(key, now);
          return;
        }
        for (Peer& peer : peers_) {  // disposed or no writers: it left
          if (peer.used && peer.key == key && peer.alive) {
            peer.alive = false;
            peer.left = now;
          }
        }
      });
  const auto endpoint = [&](const dds_builtintopic_endpoint_t& e, const dds_sample_info_t& info) {
    if (!info.valid_data || info.instance_state != DDS_IST_ALIVE) return;
    const Guid key = Guid::from(e.participant_key);
    if (key == self_) return;
    if (Peer* peer = find_or_add(key, now)) peer->has_endpoint = true;
  };
  (void)take_all<dds_builtintopic_endpoint_t>(publications_.get(), endpoint);
  (void)take_all<dds_builtintopic_endpoint_t>(subscriptions_.get(), endpoint);
}

PeerAuthenticationWatch::Counts PeerAuthenticationWatch::counts(
    std::chrono::steady_clock::time_point now) noexcept {
  const std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return last_;
  Counts out{0, last_.refused};
  for (Peer& p : peers_) {
    if (!p.used || p.settled) continue;
    // One that left is judged on how long it was there: long enough to have authenticated.
    const bool refused =
        !p.has_endpoint && (p.alive ? now - p.first_seen >= grace_ : p.left - p.first_seen >= grace_ / 3);
    if (refused && p.alive) ++out.unauthenticated_now;
    if (refused && !p.counted) {
      p.counted = true;
      ++out.refused;
      // Logged (rate-limited) as Cyclone's own refusals are: nothing else says so.
      std::array<char, 200> reason{};
      const auto& g = p.key.bytes;
      const std::size_t size = std::min(
          fmt::format_to_n(
              reason.data(), reason.size(),
              "participant {:02x}{:02x}{:02x}{:02x}:{:02x}{:02x}{:02x}{:02x}:{:02x}{:02x}{:02x}{:02x} "
              "{} without authenticating (no security, another identity CA, or credentials not "
              "valid): none of its topics was shown",
              g[0], g[1], g[2], g[3], g[4], g[5], g[6], g[7], g[8], g[9], g[10], g[11],
              p.alive ? "stays" : "left")
              .size,
          reason.size());
      detail::report_refusal(RefusedWhat::kParticipant, std::string_view(reason.data(), size));
    }
    if (!p.alive) p.settled = true;
  }
  last_ = out;
  return out;
}

}  // namespace hubrt::dds
