// The generated typed accessors (<idl>_typed.h) on the test types of reflect_test_types.idl:
// strings cut on UTF-8 boundaries, sequences held to their bound in storage owned by the message,
// copies that never share storage, and no allocation in any of it.
#include <atomic>
#include <cstdlib>
#include <new>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "reflect_test_types_typed.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// Counts every allocation of this test program (the typed accessors must make none).
void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// Not inlined: at -Os (the cross presets) GCC inlined the sized delete into gtest's factory and
// took the free() of this replacement for a mismatch with that factory's `new` (-Wmismatched-new-delete).
[[gnu::noinline]] void operator delete(void* p) noexcept {
  std::free(p);
}
[[gnu::noinline]] void operator delete(void* p, std::size_t /*size*/) noexcept {
  std::free(p);
}

namespace hubrt::msgs::typed {
namespace {

TEST(Utf8Prefix, CutsBeforeACharacterThatWouldNotFitWhole) {
  EXPECT_EQ(utf8_prefix("abc", 8), "abc");
  EXPECT_EQ(utf8_prefix("abcdefgh", 8), "abcdefgh");
  EXPECT_EQ(utf8_prefix("abcdefgh!", 8), "abcdefgh");
  EXPECT_EQ(utf8_prefix("abcdefg\xC3\xA9", 8), "abcdefg");         // é would need bytes 8-9
  EXPECT_EQ(utf8_prefix("abcdef\xC3\xA9!", 8), "abcdef\xC3\xA9");  // é fits whole
  EXPECT_EQ(utf8_prefix("abcde\xF0\x9F\x98\x80", 8), "abcde");     // 4-byte emoji, 3 fit
  EXPECT_EQ(utf8_prefix("\xE2\x82\xAC\xE2\x82\xAC\xE2\x82\xAC", 8), "\xE2\x82\xAC\xE2\x82\xAC");  // €€€
}

TEST(TypedString, SetterCutsAtTheBoundOnAUtf8BoundaryAndSaysSo) {
  hubrt_test::Bounded message;
  EXPECT_TRUE(message.set_label("lock"));
  EXPECT_EQ(message.label(), "lock");
  EXPECT_FALSE(message.set_label("abcdefg\xC3\xA9"));
  EXPECT_EQ(message.label(), "abcdefg");
  EXPECT_EQ(message.wire().label[6], 'g');
  EXPECT_EQ(message.wire().label[7], '\0');
  // A shorter value leaves nothing of the longer one behind.
  EXPECT_TRUE(message.set_label("ab"));
  EXPECT_EQ(std::string(message.wire().label, sizeof message.wire().label),
            std::string("ab") + std::string(7, '\0'));
}

TEST(TypedSequence, OwningTypeBindsItsStorageAtTheBound) {
  hubrt_test::Bounded message;
  const auto& wire = message.wire();
  EXPECT_EQ(wire.notes._maximum, 3u);
  EXPECT_EQ(wire.notes._length, 0u);
  EXPECT_FALSE(wire.notes._release);  // Cyclone must never free our storage
  EXPECT_EQ(wire.slots._maximum, 4u);
  EXPECT_EQ(message.slots().capacity(), 4u);
  EXPECT_EQ(message.numbers().capacity(), 2u);
}

TEST(TypedSequence, PushBackStopsAtTheBound) {
  hubrt_test::Bounded message;
  auto notes = message.notes();
  EXPECT_TRUE(notes.push_back("one"));
  EXPECT_TRUE(notes.push_back("two"));
  EXPECT_TRUE(notes.push_back("three-long"));  // cut to string<6>
  EXPECT_FALSE(notes.push_back("four"));
  ASSERT_EQ(notes.size(), 3u);
  EXPECT_EQ(message.view().notes()[2], "three-");
  EXPECT_TRUE(notes.full());

  auto slots = message.slots();
  for (int i = 0; i < 4; ++i) {
    auto slot = slots.append();
    ASSERT_TRUE(slot.has_value());
    slot->set_name("s" + std::to_string(i));
    slot->set_occupied(i % 2 == 1);
  }
  EXPECT_FALSE(slots.append().has_value());
  EXPECT_FALSE(slots.resize(5));
  EXPECT_EQ(slots.size(), 4u);
  EXPECT_EQ(message.view().slots()[3].name(), "s3");
  EXPECT_TRUE(message.view().slots()[3].occupied());

  slots.resize(1);
  EXPECT_EQ(message.wire().slots._length, 1u);
  slots.resize(2);  // the regrown element is zero, not the old "s1"
  EXPECT_EQ(slots[1].name(), "");
  EXPECT_FALSE(slots[1].occupied());
  slots.clear();
  EXPECT_TRUE(message.view().slots().empty());
}

TEST(TypedSequence, ARefOverASampleNobodyBoundHoldsNothing) {
  hubrt_test_msg_dds__Bounded_ raw{};
  hubrt_test::BoundedRef ref(raw);
  EXPECT_EQ(ref.notes().capacity(), 0u);
  EXPECT_FALSE(ref.notes().push_back("x"));
  EXPECT_FALSE(ref.slots().append().has_value());
  EXPECT_EQ(raw.notes._length, 0u);
}

TEST(TypedOwning, NestedSequencesGetStorageInTheOutermostOwner) {
  hubrt_test::Outer outer;
  EXPECT_EQ(outer.inner().notes().capacity(), 3u);
  EXPECT_TRUE(outer.inner().notes().push_back("deep"));
  EXPECT_TRUE(outer.tags().push_back("t"));
  EXPECT_EQ(outer.view().inner().notes()[0], "deep");
}

TEST(TypedOwning, CopiesCopyElementsAndNeverShareStorage) {
  hubrt_test::Bounded original;
  original.set_count(7);
  original.notes().push_back("a");
  original.slots().append()->set_name("x");
  hubrt_test::Bounded copy(original);
  EXPECT_NE(copy.wire().notes._buffer, original.wire().notes._buffer);
  original.notes()[0].assign("changed");
  original.slots()[0].set_name("y");
  EXPECT_EQ(copy.count(), 7u);
  EXPECT_EQ(copy.view().notes()[0], "a");
  EXPECT_EQ(copy.view().slots()[0].name(), "x");

  // From a wire sample someone else owns (e.g. one Cyclone delivered): elements copied, cut at the bound.
  hubrt_test_msg_dds__Bounded_ raw{};
  char notes[5][7] = {"n0", "n1", "n2", "n3", "n4"};
  raw.notes._buffer = notes;
  raw.notes._length = 5;
  raw.notes._maximum = 5;
  const hubrt_test::Bounded taken(raw);
  EXPECT_EQ(taken.view().notes().size(), 3u);
  EXPECT_NE(taken.wire().notes._buffer, raw.notes._buffer);
  EXPECT_EQ(taken.view().notes()[2], "n2");
}

TEST(TypedAccessors, NothingAllocates) {
  hubrt_test::Outer outer;
  hubrt_test::Bounded other;
  const long before = g_allocations.load();
  for (int round = 0; round < 100; ++round) {
    outer.inner().set_label("label-too-long");
    outer.inner().notes().clear();
    while (outer.inner().notes().push_back("note")) {
    }
    outer.inner().slots().resize(0);
    while (auto slot = outer.inner().slots().append()) slot->set_name("slot");
    outer.tags().push_back("tag");
    outer.tags().clear();
    other = hubrt_test::Bounded(outer.wire().inner);
  }
  EXPECT_EQ(g_allocations.load(), before);
  EXPECT_EQ(other.view().slots().size(), 4u);
}

}  // namespace
}  // namespace hubrt::msgs::typed
