// The remote participants a secured participant does not let in, seen from discovery (issue 34
// point 4). Cyclone 0.10.2 puts every remote participant on DCPSParticipant as soon as its SPDP
// arrives, before the security handshake (src/core/ddsi/src/ddsi_proxy_participant.c,
// new_proxy_participant), and keeps it there when the handshake fails; its endpoints are announced
// over encrypted discovery (hubrt's governance: enable_discovery_protection), so only an
// authenticated participant's endpoints ever appear on DCPSPublication/DCPSSubscription. A remote
// participant that shows no endpoint for longer than a grace period — or that leaves without one
// after a third of it — is therefore one DDS Security refused: without security at all (nothing of
// it is logged: Cyclone drops its plain discovery silently), of another identity CA, with
// credentials expired or revoked.
//
// Limits: a participant of the station that has no endpoint at all for that long (a process that
// joins and creates nothing) is counted as well; every hubrt program creates its endpoints at
// once. A refused participant that leaves within a third of the grace period is not counted. Only
// meaningful for a participant secured with discovery protection.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>

#include "hubrt/base/status.h"
#include "hubrt/dds/entity.h"
#include "hubrt/dds/guid.h"
#include "hubrt/dds/participant.h"

namespace hubrt::dds {

class PeerAuthenticationWatch {
 public:
  static constexpr std::size_t kMaxPeers = 256;  // remembered at once; beyond, newcomers are not watched
  // Long enough for a handshake and the encrypted discovery after it on a loaded machine.
  static constexpr std::chrono::seconds kDefaultGrace{15};

  // Creates listening readers of DCPSParticipant, DCPSPublication and DCPSSubscription on
  // `participant` (which must outlive the watch). Errors: Cyclone's refusal naming the topic.
  static Expected<std::unique_ptr<PeerAuthenticationWatch>> start(
      const Participant& participant, std::chrono::nanoseconds grace = kDefaultGrace);
  // Deletes the readers; Cyclone's dds_delete waits for listener calls in progress.
  ~PeerAuthenticationWatch();
  PeerAuthenticationWatch(const PeerAuthenticationWatch&) = delete;
  PeerAuthenticationWatch& operator=(const PeerAuthenticationWatch&) = delete;

  struct Counts {
    std::uint64_t unauthenticated_now = 0;  // alive, no endpoint for longer than the grace period
    std::uint64_t refused = 0;              // distinct participants refused since start (see above)
  };
  // The counts at `now` (std::chrono::steady_clock). Never allocates or blocks: while Cyclone's
  // listener holds the table, the counts of the last call are returned. Thread-safe.
  Counts counts(std::chrono::steady_clock::time_point now) noexcept;

 private:
  struct Peer {
    Guid key;
    std::chrono::steady_clock::time_point first_seen{};
    std::chrono::steady_clock::time_point left{};
    bool used = false;
    bool alive = false;
    bool has_endpoint = false;
    bool counted = false;
    bool settled = false;  // left and judged: the slot may be reused
  };
  PeerAuthenticationWatch(Guid self, std::chrono::nanoseconds grace) : self_(self), grace_(grace) {}
  static void on_data_available(dds_entity_t reader, void* arg) noexcept;
  void refresh() noexcept;
  Peer* find_or_add(const Guid& key, std::chrono::steady_clock::time_point now) noexcept;

  Guid self_;
  std::chrono::nanoseconds grace_;
  std::mutex mutex_;
  std::array<Peer, kMaxPeers> peers_{};
  Counts last_{};
  std::atomic<bool> ready_{false};
  EntityHandle participants_;
  EntityHandle publications_;
  EntityHandle subscriptions_;
};

}  // namespace hubrt::dds
