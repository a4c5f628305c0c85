// The ROS 1 codec against roscpp's own serialisation (roscpp_serialization: the bytes a roscpp
// publisher of the same fields sends), and the refusals of hostile or over-bound input.
#include "hubrt/ros1/codec.h"

#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ros/serialization.h>
#include <ros/time.h>

#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/sample_memory.h"

#include "dock_reflect.h"
#include "dock_typed.h"

namespace hubrt::ros1 {
namespace {

using DockStateWire = hub_msgs_msg_dds__DockState_;
using DockCommandWire = hub_msgs_msg_dds__DockCommand_;

hub_msgs::DockState example_state() {
  hub_msgs::DockState state;
  state.header().stamp().set_sec(1700000000);
  state.header().stamp().set_nanosec(250000000);
  state.header().set_seq(42);
  state.header().set_lifecycle(3);
  state.set_name("dock");
  state.echo().set_target_type("dock");
  state.echo().set_target_name("dock");
  state.echo().set_action("monitor");
  state.set_fresh_msg(true);
  state.set_t_plus(1.5F);
  state.set_got_reset(false);
  state.error_list().push_back("sensor smart_tool: read failed");
  auto slot = state.slots().append();
  slot->set_name("smart_tool");
  slot->set_occupied(true);
  slot = state.slots().append();
  slot->set_name("spare");
  slot->set_occupied(false);
  return state;
}

// The same fields serialised by roscpp, one by one, in .msg order.
std::vector<std::uint8_t> roscpp_bytes_of_example() {
  const ros::Time stamp(1700000000, 250000000);
  const std::uint64_t seq = 42;
  const std::uint8_t lifecycle = 3;
  const std::string name = "dock";
  const std::string tt = "dock";
  const std::string tn = "dock";
  const std::string action = "monitor";
  const std::uint8_t fresh = 1;
  const float t_plus = 1.5F;
  const std::uint8_t got_reset = 0;
  // roscpp's vector serialiser does not compile as C++20 (allocator rebind): the count by hand.
  const std::uint32_t error_count = 1;
  const std::string error0 = "sensor smart_tool: read failed";
  const std::uint32_t slot_count = 2;
  const std::string slot0 = "smart_tool";
  const std::uint8_t occ0 = 1;
  const std::string slot1 = "spare";
  const std::uint8_t occ1 = 0;
  namespace ser = ros::serialization;
  const std::uint32_t size =
      ser::serializationLength(stamp) + ser::serializationLength(seq) + ser::serializationLength(lifecycle) +
      ser::serializationLength(name) + ser::serializationLength(tt) + ser::serializationLength(tn) +
      ser::serializationLength(action) + 1 + 4 + 1 + 4 + ser::serializationLength(error0) + 4 +
      ser::serializationLength(slot0) + 1 + ser::serializationLength(slot1) + 1;
  std::vector<std::uint8_t> out(size);
  ser::OStream stream(out.data(), size);
  stream << stamp << seq << lifecycle << name << tt << tn << action << fresh << t_plus << got_reset
         << error_count << error0 << slot_count << slot0 << occ0 << slot1 << occ1;
  return out;
}

const msgs::TypeInfo& dock_state_type() {
  return msgs::type_info_of<DockStateWire>();
}

TEST(Ros1Codec, EncodesAsRoscppSerialisesTheSameFields) {
  const auto state = example_state();
  std::vector<std::uint8_t> out;
  encode(dock_state_type(), &state.wire(), out);
  EXPECT_EQ(out, roscpp_bytes_of_example());
}

TEST(Ros1Codec, DecodesWhatRoscppSerialisedAndRoundTrips) {
  const auto bytes = roscpp_bytes_of_example();
  DockStateWire sample{};
  ASSERT_FALSE(decode(dock_state_type(), bytes, &sample).has_value());
  EXPECT_EQ(sample.header.seq, 42U);
  EXPECT_EQ(sample.header.stamp.sec, 1700000000);
  EXPECT_EQ(sample.header.stamp.nanosec, 250000000U);
  EXPECT_STREQ(sample.echo.action, "monitor");
  ASSERT_EQ(sample.slots._length, 2U);
  EXPECT_STREQ(sample.slots._buffer[0].name, "smart_tool");
  EXPECT_TRUE(sample.slots._buffer[0].occupied);
  ASSERT_EQ(sample.error_list._length, 1U);
  std::vector<std::uint8_t> again;
  encode(dock_state_type(), &sample, again);
  EXPECT_EQ(again, bytes);
  msgs::free_contents(dock_state_type(), &sample);
}

std::vector<std::uint8_t> command_bytes(const std::string& tt, const std::string& tn,
                                        const std::string& action) {
  namespace ser = ros::serialization;
  const std::uint32_t size =
      ser::serializationLength(tt) + ser::serializationLength(tn) + ser::serializationLength(action);
  std::vector<std::uint8_t> out(size);
  ser::OStream stream(out.data(), size);
  stream << tt << tn << action;
  return out;
}

TEST(Ros1Codec, OverBoundStringIsRefusedNamingTheFieldNeverCut) {
  const auto bytes = command_bytes("dock", "dock", std::string(65, 'a'));  // action is string<=64
  DockCommandWire sample{};
  const auto error = decode(msgs::type_info_of<DockCommandWire>(), bytes, &sample);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->problem, DecodeProblem::kOverBound);
  EXPECT_EQ(error->field, "action");
  EXPECT_NE(error->message.find("bound of 64"), std::string::npos) << error->message;
  EXPECT_STREQ(sample.action, "");  // left zeroed, not cut to 64 bytes

  const auto at_bound = command_bytes("dock", "dock", std::string(64, 'a'));
  EXPECT_FALSE(decode(msgs::type_info_of<DockCommandWire>(), at_bound, &sample).has_value());
  EXPECT_EQ(std::strlen(sample.action), 64U);
}

TEST(Ros1Codec, OverBoundSequenceIsRefusedNamingTheField) {
  auto state = example_state();
  std::vector<std::uint8_t> bytes;
  encode(dock_state_type(), &state.wire(), bytes);
  // Rewrite the slots count (after everything before it) to 17 > bound 16.
  std::vector<std::uint8_t> prefix;
  state.slots().clear();
  encode(dock_state_type(), &state.wire(), prefix);
  const std::uint32_t seventeen = 17;
  std::memcpy(bytes.data() + prefix.size() - 4, &seventeen, 4);
  DockStateWire sample{};
  const auto error = decode(dock_state_type(), bytes, &sample);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->problem, DecodeProblem::kOverBound);
  EXPECT_EQ(error->field, "slots");
  EXPECT_EQ(sample.slots._buffer, nullptr);
}

TEST(Ros1Codec, HostileBytesAreRefusedWithoutCrashOrLeak) {
  DockCommandWire sample{};
  const auto& type = msgs::type_info_of<DockCommandWire>();
  auto good = command_bytes("dock", "dock", "monitor");
  // Truncated anywhere.
  for (std::size_t n = 0; n < good.size(); ++n) {
    const auto error = decode(type, std::span(good.data(), n), &sample);
    ASSERT_TRUE(error.has_value()) << n;
    EXPECT_EQ(error->problem, DecodeProblem::kMalformed);
  }
  // Trailing bytes.
  auto longer = good;
  longer.push_back(0);
  EXPECT_TRUE(decode(type, longer, &sample).has_value());
  // A length far beyond the message.
  auto huge = good;
  const std::uint32_t big = 0xFFFFFFF0U;
  std::memcpy(huge.data(), &big, 4);
  EXPECT_EQ(decode(type, huge, &sample)->problem, DecodeProblem::kMalformed);
  // Invalid UTF-8 and an embedded NUL.
  EXPECT_EQ(decode(type, command_bytes("dock", "do\xC0\xAF", "monitor"), &sample)->problem,
            DecodeProblem::kBadText);
  EXPECT_EQ(decode(type, command_bytes("dock", std::string("d\0k", 3), "monitor"), &sample)->field,
            "target_name");
}

TEST(Ros1Codec, HugeUnboundedSequenceCountAllocatesNothing) {
  // SimSignals has unbounded sequences: a count of 2^32-1 with no bytes behind it is refused
  // before the buffer would be allocated (ASan would report a multi-gigabyte allocation).
  const msgs::TypeInfo* type = msgs::all_types().find("hub_msgs/msg/SimSignals");
  ASSERT_NE(type, nullptr);
  std::vector<std::uint8_t> bytes = {1, 0, 0, 0, 'h', 0xFF, 0xFF, 0xFF, 0xFF};
  std::vector<std::uint8_t> sample(type->size, 0);
  const auto error = decode(*type, bytes, sample.data());
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->field, "signals");
  msgs::free_contents(*type, sample.data());
}

}  // namespace
}  // namespace hubrt::ros1
