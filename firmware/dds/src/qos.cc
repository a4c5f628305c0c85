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

Duration duration_of(dds_duration_t d) noexcept {
  return d == DDS_INFINITY ? Duration::max() : Duration(d);
}

dds_duration_t dds_duration_of(Duration d) noexcept {
  return d == Duration::max() ? DDS_INFINITY : d.count();
}

}  // namespace

OfferedQos read_offered_qos(const dds_qos_t* qos) noexcept {
  OfferedQos out;
  if (qos == nullptr) return out;
  dds_reliability_kind_t reliability{};
  dds_duration_t blocking = 0;
  if (dds_qget_reliability(qos, &reliability, &blocking))
    out.reliability = reliability == DDS_RELIABILITY_RELIABLE ? OfferedQos::Reliability::kReliable
                                                              : OfferedQos::Reliability::kBestEffort;
  dds_durability_kind_t durability{};
  if (dds_qget_durability(qos, &durability)) {
    switch (durability) {
      case DDS_DURABILITY_VOLATILE:
        out.durability = OfferedQos::Durability::kVolatile;
        break;
      case DDS_DURABILITY_TRANSIENT_LOCAL:
        out.durability = OfferedQos::Durability::kTransientLocal;
        break;
      case DDS_DURABILITY_TRANSIENT:
        out.durability = OfferedQos::Durability::kTransient;
        break;
      case DDS_DURABILITY_PERSISTENT:
        out.durability = OfferedQos::Durability::kPersistent;
        break;
    }
  }
  dds_history_kind_t history{};
  std::int32_t depth = 1;
  if (dds_qget_history(qos, &history, &depth)) {
    out.history =
        history == DDS_HISTORY_KEEP_ALL ? OfferedQos::History::kKeepAll : OfferedQos::History::kKeepLast;
    out.depth = depth;
  }
  dds_duration_t d = 0;
  if (dds_qget_deadline(qos, &d)) out.deadline = duration_of(d);
  if (dds_qget_lifespan(qos, &d)) out.lifespan = duration_of(d);
  dds_liveliness_kind_t liveliness{};
  if (dds_qget_liveliness(qos, &liveliness, &d)) {
    out.liveliness = liveliness == DDS_LIVELINESS_AUTOMATIC ? OfferedQos::Liveliness::kAutomatic
                     : liveliness == DDS_LIVELINESS_MANUAL_BY_PARTICIPANT
                         ? OfferedQos::Liveliness::kManualByParticipant
                         : OfferedQos::Liveliness::kManualByTopic;
    out.liveliness_lease = duration_of(d);
  }
  return out;
}

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

Qos Qos::from_offered(const OfferedQos& offered) {
  Qos qos;
  if (offered.reliability == OfferedQos::Reliability::kReliable) {
    qos.reliable();
  } else {
    qos.best_effort();
  }
  static constexpr dds_durability_kind_t kDurability[] = {
      DDS_DURABILITY_VOLATILE, DDS_DURABILITY_TRANSIENT_LOCAL, DDS_DURABILITY_TRANSIENT,
      DDS_DURABILITY_PERSISTENT};
  dds_qset_durability(qos.qos_, kDurability[static_cast<int>(offered.durability)]);
  if (offered.history == OfferedQos::History::kKeepAll) {
    qos.keep_all();
  } else {
    qos.keep_last(offered.depth > 0 ? offered.depth : 1);
  }
  dds_qset_deadline(qos.qos_, dds_duration_of(offered.deadline));
  dds_qset_lifespan(qos.qos_, dds_duration_of(offered.lifespan));
  static constexpr dds_liveliness_kind_t kLiveliness[] = {
      DDS_LIVELINESS_AUTOMATIC, DDS_LIVELINESS_MANUAL_BY_PARTICIPANT, DDS_LIVELINESS_MANUAL_BY_TOPIC};
  dds_qset_liveliness(qos.qos_, kLiveliness[static_cast<int>(offered.liveliness)],
                      dds_duration_of(offered.liveliness_lease));
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

Qos& Qos::dispose_on_unregister(bool dispose) {
  dds_qset_writer_data_lifecycle(qos_, dispose);
  return *this;
}

Qos& Qos::keep_all() {
  dds_qset_history(qos_, DDS_HISTORY_KEEP_ALL, DDS_LENGTH_UNLIMITED);
  return *this;
}

}  // namespace hubrt::dds
