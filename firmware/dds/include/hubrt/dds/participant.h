// A DDS domain participant: the root every topic, reader, writer and waitset hangs from.
#pragma once

#include <cstdint>
#include <string_view>
#include <utility>

#include <dds/dds.h>

#include "hubrt/base/status.h"
#include "hubrt/dds/detail/domain_claim.h"
#include "hubrt/dds/domain.h"
#include "hubrt/dds/entity.h"
#include "hubrt/dds/guid.h"

namespace hubrt::dds {

// Move-only owner of a Cyclone participant. Destroying it deletes the participant and with it
// every entity created from it (topics, readers, writers, conditions, waitsets): destroy those
// first or not at all — their own destructors then do nothing harmful.
// Thread-safety: create() is thread-safe; a Participant may be used from several threads for
// creating entities (Cyclone serialises), but moving or destroying it must not race with use.
class Participant {
 public:
  // Joins config.domain_id. With a non-empty config.cyclone_xml the domain is created with that
  // configuration unless it already exists in this process (see DomainConfig: first wins).
  // `name` (optional) is published as the participant's entity name (seen by discovery);
  // `user_data` (optional) as its USER_DATA QoS, which every other participant reads from the
  // DCPSParticipant builtin topic (hubd puts its start stamp there, see assembly/twin_watch.h).
  // Errors: the Cyclone refusal of the XML ("create domain N with the given Cyclone XML
  // configuration: ...") or of the participant ("create participant in domain N: ..."),
  // e.g. kInvalidArgument for a domain id above kMaxDomainId.
  static Expected<Participant> create(const DomainConfig& config, std::string_view name = {},
                                      std::string_view user_data = {});

  ~Participant() = default;
  Participant(Participant&&) noexcept = default;
  // Deletes the participant this one held before giving up its claim on that domain.
  Participant& operator=(Participant&& other) noexcept {
    if (this != &other) {
      handle_ = std::move(other.handle_);
      domain_ = std::move(other.domain_);
    }
    return *this;
  }
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  [[nodiscard]] dds_entity_t handle() const noexcept { return handle_.get(); }
  [[nodiscard]] std::uint32_t domain_id() const noexcept { return domain_.domain_id(); }
  // The participant's GUID as discovery reports it; a zero Guid if Cyclone refuses (deleted).
  [[nodiscard]] Guid guid() const noexcept;

 private:
  Participant(detail::DomainClaim domain, EntityHandle handle) noexcept
      : domain_(std::move(domain)), handle_(std::move(handle)) {}

  // Declared first so it is released last: the participant must be gone before the domain it
  // lives in may be deleted.
  detail::DomainClaim domain_;
  EntityHandle handle_;
};

}  // namespace hubrt::dds
