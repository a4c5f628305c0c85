#include "hubrt/dds/qos.h"

#include <utility>

#include <gtest/gtest.h>

namespace hubrt::dds {
namespace {

struct Policies {
  dds_reliability_kind_t reliability = DDS_RELIABILITY_BEST_EFFORT;
  dds_durability_kind_t durability = DDS_DURABILITY_TRANSIENT;
  dds_history_kind_t history = DDS_HISTORY_KEEP_ALL;
  std::int32_t depth = -1;
  std::uint32_t representations = 0;
  dds_data_representation_id_t first_representation = -1;
};

Policies read(const dds_qos_t* qos) {
  Policies p;
  dds_duration_t blocking = 0;
  EXPECT_TRUE(dds_qget_reliability(qos, &p.reliability, &blocking));
  EXPECT_TRUE(dds_qget_durability(qos, &p.durability));
  EXPECT_TRUE(dds_qget_history(qos, &p.history, &p.depth));
  dds_data_representation_id_t* values = nullptr;
  EXPECT_TRUE(dds_qget_data_representation(qos, &p.representations, &values));
  if (values != nullptr) {
    p.first_representation = values[0];
    dds_free(values);
  }
  return p;
}

TEST(Qos, Ros2DefaultIsReliableVolatileKeepLast10Xcdr1) {
  const Policies p = read(Qos::ros2_default().get());
  EXPECT_EQ(p.reliability, DDS_RELIABILITY_RELIABLE);
  EXPECT_EQ(p.durability, DDS_DURABILITY_VOLATILE);
  EXPECT_EQ(p.history, DDS_HISTORY_KEEP_LAST);
  EXPECT_EQ(p.depth, 10);
  EXPECT_EQ(p.representations, 1u);
  EXPECT_EQ(p.first_representation, DDS_DATA_REPRESENTATION_XCDR1);
}

TEST(Qos, SensorDataIsBestEffortVolatileKeepLast5Xcdr1) {
  const Policies p = read(Qos::sensor_data().get());
  EXPECT_EQ(p.reliability, DDS_RELIABILITY_BEST_EFFORT);
  EXPECT_EQ(p.durability, DDS_DURABILITY_VOLATILE);
  EXPECT_EQ(p.history, DDS_HISTORY_KEEP_LAST);
  EXPECT_EQ(p.depth, 5);
  EXPECT_EQ(p.first_representation, DDS_DATA_REPRESENTATION_XCDR1);
}

TEST(Qos, DepthIsConfigurable) {
  EXPECT_EQ(read(Qos::ros2_default(3).get()).depth, 3);
  EXPECT_EQ(read(Qos::sensor_data(1).get()).depth, 1);
  EXPECT_EQ(read(Qos::ros2_default().keep_last(25).get()).depth, 25);
}

TEST(Qos, BuilderStepsChangeOnlyTheirPolicy) {
  Qos qos = Qos::ros2_default();
  qos.transient_local().keep_all();
  const Policies p = read(qos.get());
  EXPECT_EQ(p.reliability, DDS_RELIABILITY_RELIABLE);
  EXPECT_EQ(p.durability, DDS_DURABILITY_TRANSIENT_LOCAL);
  EXPECT_EQ(p.history, DDS_HISTORY_KEEP_ALL);
  EXPECT_EQ(p.first_representation, DDS_DATA_REPRESENTATION_XCDR1);
}

TEST(Qos, CopiesAreDeepAndMovedFromStaysXcdr1) {
  Qos original = Qos::sensor_data(7);
  Qos copy = original;
  original.keep_last(2).reliable();
  EXPECT_EQ(read(copy.get()).depth, 7);
  EXPECT_EQ(read(copy.get()).reliability, DDS_RELIABILITY_BEST_EFFORT);

  Qos moved = std::move(original);
  EXPECT_EQ(read(moved.get()).depth, 2);
  ASSERT_NE(original.get(), nullptr);  // NOLINT(bugprone-use-after-move): documented state
  dds_data_representation_id_t* values = nullptr;
  std::uint32_t n = 0;
  ASSERT_TRUE(dds_qget_data_representation(original.get(), &n, &values));  // NOLINT(bugprone-use-after-move)
  ASSERT_EQ(n, 1u);
  EXPECT_EQ(values[0], DDS_DATA_REPRESENTATION_XCDR1);
  dds_free(values);

  copy = moved;
  EXPECT_EQ(read(copy.get()).depth, 2);
}

// What discovery reads of a writer's QoS makes the same QoS again (hubctl play offers what was
// recorded), every policy a recording keeps.
TEST(Qos, OfferedQosReadsBackWhatFromOfferedSets) {
  OfferedQos offered;
  offered.reliability = OfferedQos::Reliability::kBestEffort;
  offered.durability = OfferedQos::Durability::kTransientLocal;
  offered.history = OfferedQos::History::kKeepLast;
  offered.depth = 42;
  offered.deadline = std::chrono::milliseconds(250);
  offered.lifespan = std::chrono::seconds(2);
  offered.liveliness = OfferedQos::Liveliness::kManualByTopic;
  offered.liveliness_lease = std::chrono::seconds(3);
  EXPECT_EQ(read_offered_qos(Qos::from_offered(offered).get()), offered);
  OfferedQos all;
  all.history = OfferedQos::History::kKeepAll;
  const OfferedQos read_all = read_offered_qos(Qos::from_offered(all).get());
  EXPECT_EQ(read_all.history, OfferedQos::History::kKeepAll);
  EXPECT_EQ(read_all.deadline, Duration::max());
  EXPECT_EQ(read_all.reliability, OfferedQos::Reliability::kReliable);
  EXPECT_EQ(read_offered_qos(Qos::ros2_default().get()).depth, 10);
}

}  // namespace
}  // namespace hubrt::dds
