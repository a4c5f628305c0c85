#include <map>
#include <mutex>
#include <string>
#include <utility>

#include <dds/dds.h>

#include "hubrt/dds/detail/domain_claim.h"
#include "hubrt/dds/retcode.h"

namespace hubrt::dds::detail {
namespace {

struct DomainEntry {
  dds_entity_t explicit_domain = 0;  // 0: Cyclone owns the domain's lifetime (implicit domain)
  std::size_t claims = 0;
};

// All claims, creations and deletions happen under one lock, so a domain being deleted by its
// last participant can never be mistaken for a live one by a participant being created.
struct Registry {
  std::mutex mutex;
  std::map<std::uint32_t, DomainEntry> domains;
};

Registry& registry() {
  // Never destroyed: participants that are themselves static may release claims during exit.
  static Registry* const instance = new Registry();  // NOLINT(cppcoreguidelines-owning-memory)
  return *instance;
}

}  // namespace

DomainClaim::DomainClaim(DomainClaim&& other) noexcept
    : domain_id_(other.domain_id_), engaged_(std::exchange(other.engaged_, false)) {}

DomainClaim& DomainClaim::operator=(DomainClaim&& other) noexcept {
  if (this != &other) {
    release();
    domain_id_ = other.domain_id_;
    engaged_ = std::exchange(other.engaged_, false);
  }
  return *this;
}

void DomainClaim::release() noexcept {
  if (!engaged_) return;
  engaged_ = false;
  Registry& reg = registry();
  const std::lock_guard lock(reg.mutex);
  const auto it = reg.domains.find(domain_id_);
  if (it == reg.domains.end()) return;
  if (--it->second.claims > 0) return;
  if (it->second.explicit_domain > 0) (void)dds_delete(it->second.explicit_domain);
  reg.domains.erase(it);
}

Expected<DomainClaim> acquire_domain(const DomainConfig& config) {
  Registry& reg = registry();
  const std::lock_guard lock(reg.mutex);
  DomainEntry& entry = reg.domains[config.domain_id];
  if (entry.claims == 0 && !config.cyclone_xml.empty()) {
    const dds_entity_t domain = dds_create_domain(config.domain_id, config.cyclone_xml.c_str());
    if (domain > 0) {
      entry.explicit_domain = domain;
    } else if (domain != DDS_RETCODE_PRECONDITION_NOT_MET) {
      // PRECONDITION_NOT_MET means the domain exists already (created by raw Cyclone calls in this
      // process): it is shared as it is. Anything else is a refusal of the configuration.
      reg.domains.erase(config.domain_id);
      return dds_error(domain, "create domain " + std::to_string(config.domain_id) +
                                   " with the given Cyclone XML configuration (Cyclone logs the "
                                   "offending element on stderr)");
    }
  }
  ++entry.claims;
  return DomainClaim(config.domain_id);
}

}  // namespace hubrt::dds::detail
