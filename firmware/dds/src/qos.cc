#include "hubrt/dds/qos.h"

#include <utility>

namespace hubrt::dds {
namespace {

// Cyclone's own default for reliable writers: how long write() may block on a full history.
// With keep-last histories it never has to.
constexpr dds_duration_t kMaxBlockingTime = DDS_MSECS(100);

dds_qos_t* new_xcdr1_qos() {
  dds_qos_t* qos = dds_create_qos();
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
  return qos;
}

}  // namespace

Qos::Qos() : qos_(new_xcdr1_qos()) {}

Qos::~Qos() {
  dds_delete_qos(qos_);
}

Qos::Qos(const Qos& other) : qos_(dds_create_qos()) {
  (void)dds_copy_qos(qos_, other.qos_);
}

Qos& Qos::operator=(const Qos& other) {
  if (this != &other) {
    dds_reset_qos(qos_);
    (void)dds_copy_qos(qos_, other.qos_);
  }
  return *this;
}

// Swapping keeps both objects holding a valid dds_qos_t, so a moved-from Qos stays usable.
Qos::Qos(Qos&& other) noexcept : qos_(std::exchange(other.qos_, nullptr)) {
  other.qos_ = new_xcdr1_qos();
}

Qos& Qos::operator=(Qos&& other) noexcept {
  std::swap(qos_, other.qos_);
  return *this;
}

Qos Qos::ros2_default(std::int32_t depth) {
  Qos qos;
  qos.reliable().volatile_durability().keep_last(depth);
  return qos;
}

Qos Qos::sensor_data(std::int32_t depth) {
  Qos qos;
  qos.best_effort().volatile_durability().keep_last(depth);
  return qos;
}

Qos& Qos::reliable() {
  dds_qset_reliability(qos_, DDS_RELIABILITY_RELIABLE, kMaxBlockingTime);
  return *this;
}

Qos& Qos::best_effort() {
  dds_qset_reliability(qos_, DDS_RELIABILITY_BEST_EFFORT, 0);
  return *this;
}

Qos& Qos::volatile_durability() {
  dds_qset_durability(qos_, DDS_DURABILITY_VOLATILE);
  return *this;
}

Qos& Qos::transient_local() {
  dds_qset_durability(qos_, DDS_DURABILITY_TRANSIENT_LOCAL);
  return *this;
}

Qos& Qos::keep_last(std::int32_t depth) {
  dds_qset_history(qos_, DDS_HISTORY_KEEP_LAST, depth);
  return *this;
}

Qos& Qos::lifespan(Duration lifespan) {
  dds_qset_lifespan(qos_, lifespan.count());
  return *this;
}

Qos& Qos::keep_all() {
  dds_qset_history(qos_, DDS_HISTORY_KEEP_ALL, DDS_LENGTH_UNLIMITED);
  return *this;
}

}  // namespace hubrt::dds
