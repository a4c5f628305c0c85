#include "hubrt/dds/participant.h"

#include <memory>
#include <string>

#include "hubrt/dds/retcode.h"

namespace hubrt::dds {

Expected<Participant> Participant::create(const DomainConfig& config, std::string_view name,
                                          std::string_view user_data) {
  auto claim = detail::acquire_domain(config);
  if (!claim) return std::move(claim).error();
  // Participant QoS carries only the name and user data: the XCDR1/reliability policies of Qos
  // are for topics and endpoints.
  const std::unique_ptr<dds_qos_t, decltype(&dds_delete_qos)> qos(dds_create_qos(), &dds_delete_qos);
  if (!name.empty()) dds_qset_entity_name(qos.get(), std::string(name).c_str());
  if (!user_data.empty()) dds_qset_userdata(qos.get(), user_data.data(), user_data.size());
  const dds_entity_t handle = dds_create_participant(config.domain_id, qos.get(), nullptr);
  if (handle < 0) {
    return dds_error(handle, "create participant" +
                                 (name.empty() ? std::string() : " '" + std::string(name) + "'") +
                                 " in domain " + std::to_string(config.domain_id));
  }
  return Participant(std::move(*claim), EntityHandle(handle));
}

Guid Participant::guid() const noexcept {
  dds_guid_t guid{};
  if (dds_get_guid(handle_.get(), &guid) < 0) return Guid{};
  return Guid::from(guid);
}

}  // namespace hubrt::dds
