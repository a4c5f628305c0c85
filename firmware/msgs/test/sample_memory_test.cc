#include "hubrt/msgs/sample_memory.h"

#include <cstring>

#include <gtest/gtest.h>

#include "hubrt/msgs/json.h"
#include "hubrt/msgs/set_field.h"

#include "reflect_test_types_reflect.h"

namespace hubrt::msgs {
namespace {

bool all_zero(const void* p, std::size_t n) {
  const auto* bytes = static_cast<const unsigned char*>(p);
  for (std::size_t i = 0; i < n; ++i) {
    if (bytes[i] != 0) return false;
  }
  return true;
}

// ASan (sanitizer build) reports any leak or double free here.
TEST(FreeContents, ReleasesEverythingFromJsonAllocatedAndZeroes) {
  hubrt_test_msg_dds__AllKinds_ s{};
  const auto& type = type_info_of<hubrt_test_msg_dds__AllKinds_>();
  ASSERT_TRUE(from_json(
      type, nlohmann::ordered_json::parse(R"({"text": "t", "inner": {"label": "l"}, "words": ["a", "b"],
                          "inners": [{"label": "x"}, {"label": "y"}], "names": ["n0", "n1"],
                          "pair": [{"label": "p0"}, {"label": "p1"}], "ints": [1, 2, 3], "u32": 7})"),
      &s));
  free_contents(type, &s);
  EXPECT_TRUE(all_zero(&s, sizeof s));
  free_contents(type, &s);  // a zero sample owns nothing: freeing again is harmless
}

TEST(FreeContents, WorksForNestedTypesWithoutDescriptor) {
  const auto& type = type_info_of<hubrt_test_msg_dds__Inner_>();
  ASSERT_EQ(type.descriptor, nullptr);
  hubrt_test_msg_dds__Inner_ s{};
  ASSERT_TRUE(set_field(type, &s, "label", "nested"));
  free_contents(type, &s);
  EXPECT_EQ(s.label, nullptr);
}

// Like dds_sample_free: a buffer the sample does not own (_release false) is left alone.
TEST(FreeContents, LeavesBorrowedSequenceBuffersAlone) {
  const auto& type = type_info_of<hubrt_test_msg_dds__AllKinds_>();
  hubrt_test_msg_dds__AllKinds_ s{};
  int32_t borrowed[3] = {1, 2, 3};
  s.ints._buffer = borrowed;
  s.ints._length = s.ints._maximum = 3;
  s.ints._release = false;
  free_contents(type, &s);
  EXPECT_EQ(borrowed[2], 3);
  EXPECT_EQ(s.ints._buffer, nullptr);
}

// Elements between _length and _maximum may own strings (Cyclone reuses buffers that way).
TEST(FreeContents, FreesElementsUpToTheMaximum) {
  const auto& type = type_info_of<hubrt_test_msg_dds__AllKinds_>();
  hubrt_test_msg_dds__AllKinds_ s{};
  s.words._buffer = static_cast<char**>(dds_alloc(2 * sizeof(char*)));
  s.words._buffer[0] = dds_string_dup("in use");
  s.words._buffer[1] = dds_string_dup("spare");
  s.words._length = 1;
  s.words._maximum = 2;
  s.words._release = true;
  free_contents(type, &s);  // ASan would report "spare" as leaked otherwise
  EXPECT_EQ(s.words._buffer, nullptr);
}

}  // namespace
}  // namespace hubrt::msgs
