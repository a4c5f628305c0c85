#include "sertype_probe.h"

#include <cstdint>
#include <cstring>

#include <dds/ddsi/ddsi_serdata.h>

#include "hubrt/dds/sample.h"

namespace hubrt::dds::detail {
namespace {

// Deletes an entity (and its children) when the scope ends.
class Scoped {
 public:
  explicit Scoped(dds_entity_t entity) noexcept : entity_(entity) {}
  ~Scoped() {
    if (entity_ > 0) dds_delete(entity_);
  }
  Scoped(const Scoped&) = delete;
  Scoped& operator=(const Scoped&) = delete;
  [[nodiscard]] dds_entity_t get() const noexcept { return entity_; }

 private:
  dds_entity_t entity_;
};

class ScopedQos {
 public:
  ScopedQos() : qos_(dds_create_qos()) {}
  ~ScopedQos() { dds_delete_qos(qos_); }
  ScopedQos(const ScopedQos&) = delete;
  ScopedQos& operator=(const ScopedQos&) = delete;
  [[nodiscard]] dds_qos_t* get() const noexcept { return qos_; }

 private:
  dds_qos_t* qos_;
};

// A partition no hubrt endpoint and no ROS 2 endpoint uses, so the probe matches only itself.
constexpr const char* kProbePartition = "hubrt_sertype_probe";

}  // namespace

bool is_sertype_probe(const dds_qos_t* qos) noexcept {
  std::uint32_t n = 0;
  char** names = nullptr;
  if (qos == nullptr || !dds_qget_partition(qos, &n, &names)) return false;
  bool probe = false;
  for (std::uint32_t i = 0; i < n; ++i) {
    probe = probe || std::strcmp(names[i], kProbePartition) == 0;
    dds_free(names[i]);
  }
  dds_free(names);
  return probe;
}

const struct ddsi_sertype* probe_topic_sertype(dds_entity_t participant, dds_entity_t topic,
                                               const dds_topic_descriptor_t& descriptor) {
  const ScopedQos group_qos;
  dds_qset_partition1(group_qos.get(), kProbePartition);
  const ScopedQos qos;
  // Reliable, keep-last 1, XCDR1 (the representation every hubrt QoS restricts to, qos.cc): the
  // sample is delivered to the local reader inside dds_write.
  dds_qset_reliability(qos.get(), DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_history(qos.get(), DDS_HISTORY_KEEP_LAST, 1);
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos.get(), 1, &xcdr1);
  const Scoped subscriber(dds_create_subscriber(participant, group_qos.get(), nullptr));
  const Scoped publisher(dds_create_publisher(participant, group_qos.get(), nullptr));
  if (subscriber.get() < 0 || publisher.get() < 0) return nullptr;
  const dds_entity_t reader = dds_create_reader(subscriber.get(), topic, qos.get(), nullptr);
  const dds_entity_t writer = dds_create_writer(publisher.get(), topic, qos.get(), nullptr);
  if (reader < 0 || writer < 0) return nullptr;
  const UntypedSample sample(descriptor);  // zeroed: null strings serialise as empty ones
  if (dds_write(writer, sample.data()) < 0) return nullptr;
  struct ddsi_serdata* serdata = nullptr;
  dds_sample_info_t info;
  if (dds_takecdr(reader, &serdata, 1, &info, DDS_ANY_STATE) != 1 || serdata == nullptr) return nullptr;
  const struct ddsi_sertype* sertype = serdata->type;
  ddsi_serdata_unref(serdata);
  return sertype;
}

}  // namespace hubrt::dds::detail
