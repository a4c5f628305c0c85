// Internal to hubrt::dds (Participant holds one); not for direct use.
// Process-wide bookkeeping of the domains our participants live in, so that a domain created
// with an explicit Cyclone configuration stays alive exactly as long as one of our participants
// uses it, and several participants in one process can share it.
#pragma once

#include <cstdint>

#include "hubrt/base/status.h"
#include "hubrt/dds/domain.h"

namespace hubrt::dds::detail {

// One participant's claim on its domain; releasing the last claim deletes a domain this layer
// created explicitly. Move-only.
class DomainClaim {
 public:
  DomainClaim() noexcept = default;
  ~DomainClaim() { release(); }
  DomainClaim(const DomainClaim&) = delete;
  DomainClaim& operator=(const DomainClaim&) = delete;
  DomainClaim(DomainClaim&& other) noexcept;
  DomainClaim& operator=(DomainClaim&& other) noexcept;

  [[nodiscard]] std::uint32_t domain_id() const noexcept { return domain_id_; }
  void release() noexcept;

 private:
  friend Expected<DomainClaim> acquire_domain(const DomainConfig& config);
  explicit DomainClaim(std::uint32_t domain_id) noexcept : domain_id_(domain_id), engaged_(true) {}

  std::uint32_t domain_id_ = 0;
  bool engaged_ = false;
};

// Claims config.domain_id. The first claim with a non-empty cyclone_xml creates the domain with
// that configuration (dds_create_domain); later claims share whatever exists. A domain that was
// created outside this layer (raw Cyclone calls) is used as it is.
// Errors: Cyclone's refusal of the configuration, as an Error naming the domain.
// Thread-safe.
Expected<DomainClaim> acquire_domain(const DomainConfig& config);

}  // namespace hubrt::dds::detail
