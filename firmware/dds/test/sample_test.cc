// Sample ownership. Leaks and double frees show up in the ASan build, which runs these too.
#include "hubrt/dds/sample.h"

#include <utility>

#include <gtest/gtest.h>

#include "hubrt/dds/topic.h"

#include "test_types_traits.h"

namespace hubrt::dds {
namespace {

using test::Ping;

void fill(Ping& ping, const char* text, std::uint32_t n_values) {
  ping.text = dds_string_dup(text);
  ping.values._buffer = static_cast<std::int32_t*>(dds_alloc(n_values * sizeof(std::int32_t)));
  ping.values._maximum = ping.values._length = n_values;
  ping.values._release = true;
  for (std::uint32_t i = 0; i < n_values; ++i) ping.values._buffer[i] = static_cast<std::int32_t>(i);
}

TEST(Sample, StartsZeroed) {
  Sample<Ping> sample;
  EXPECT_EQ(sample->seq, 0u);
  EXPECT_EQ(sample->text, nullptr);
  EXPECT_EQ(sample->values._buffer, nullptr);
}

TEST(Sample, MoveTransfersContentsAndEmptiesTheSource) {
  Sample<Ping> a;
  fill(*a, "owned by a", 4);
  const char* text = a->text;
  Sample<Ping> b = std::move(a);
  EXPECT_EQ(b->text, text);
  EXPECT_EQ(a->text, nullptr);            // NOLINT(bugprone-use-after-move): documented state
  EXPECT_EQ(a->values._buffer, nullptr);  // NOLINT(bugprone-use-after-move)

  Sample<Ping> c;
  fill(*c, "owned by c, freed on assignment", 2);
  c = std::move(b);
  EXPECT_STREQ(c->text, "owned by a");
  EXPECT_EQ(c->values._length, 4u);
}

TEST(UntypedSample, HasDescriptorSizeZeroedAndMoves) {
  UntypedSample sample(hubrt_test_msg_dds__Ping__desc);
  ASSERT_NE(sample.data(), nullptr);
  EXPECT_EQ(&sample.descriptor(), &hubrt_test_msg_dds__Ping__desc);
  auto* ping = static_cast<Ping*>(sample.data());
  EXPECT_EQ(ping->text, nullptr);
  EXPECT_EQ(ping->values._length, 0u);
  fill(*ping, "freed with the sample", 3);

  UntypedSample moved = std::move(sample);
  EXPECT_EQ(moved.data(), ping);
  EXPECT_EQ(sample.data(), nullptr);  // NOLINT(bugprone-use-after-move): documented state
}

TEST(TopicTypeCheck, SizeMismatchNamesTheTypeAndBothSizes) {
  EXPECT_TRUE(check_type_size(hubrt_test_msg_dds__Ping__desc, sizeof(Ping)));
  auto mismatch = check_type_size(hubrt_test_msg_dds__Ping__desc, sizeof(test::Counter));
  ASSERT_FALSE(mismatch);
  EXPECT_EQ(mismatch.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(mismatch.error().message.find("hubrt_test::msg::dds_::Ping_"), std::string::npos)
      << mismatch.error().message;
  EXPECT_NE(mismatch.error().message.find(std::to_string(sizeof(test::Counter))), std::string::npos);
}

}  // namespace
}  // namespace hubrt::dds
