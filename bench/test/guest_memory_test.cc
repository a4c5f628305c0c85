// bench/support/guest_memory: the guest's share of a qemu-user process, from its smaps.
#include "guest_memory.h"

#include <chrono>

#include <gtest/gtest.h>

#include "hubrt/test_support/child_process.h"

namespace hubrt::bench {
namespace {

// The layout seen with Debian 12's qemu-aarch64-static running the arm64 board hubd (2026-11-28),
// shortened: the guest program, a library and anonymous memory low; qemu's heap, executable and
// translation buffer high.
constexpr const char* kEmulator = "/usr/bin/qemu-aarch64-static";
constexpr const char* kSmaps =
    "5500000000-55000b3000 r--p 00000000 fe:01 123 /build/cross-arm64/firmware/hubd/board/dock_ecu/hubd\n"
    "Size:                716 kB\n"
    "Rss:                 640 kB\n"
    "Pss:                 640 kB\n"
    "Anonymous:             0 kB\n"
    "55000d4000-5500176000 rw-p 00000000 00:00 0 \n"
    "Rss:                 524 kB\n"
    "Anonymous:           524 kB\n"
    "5502fa0000-55030c3000 r--p 00000000 fe:01 456 /sysroot/usr/lib/aarch64-linux-gnu/libddsc.so.0.10.2\n"
    "Rss:                1024 kB\n"
    "Anonymous:             0 kB\n"
    "5503000000-5503002000 rw-p 00160000 fe:01 456 /sysroot/usr/lib/aarch64-linux-gnu/libddsc.so.0.10.2\n"
    "Rss:                   8 kB\n"
    "Anonymous:             4 kB\n"
    "555567106000-555567594000 rw-p 00000000 00:00 0                          [heap]\n"
    "Rss:                4556 kB\n"
    "Anonymous:          4556 kB\n"
    "7fc05c000000-7fc063fff000 rwxp 00000000 00:00 0 \n"
    "Rss:                8192 kB\n"
    "Anonymous:          8192 kB\n"
    "7fc069800000-7fc069a28000 r--p 00000000 fe:01 789 /usr/bin/qemu-aarch64-static\n"
    "Rss:                2208 kB\n";

TEST(GuestMemory, CountsTheMappingsBelowTheEmulatorsOwn) {
  const auto kb = guest_rss_kb(kSmaps, kEmulator);
  ASSERT_TRUE(kb.has_value());
  EXPECT_DOUBLE_EQ(kb->rss, 640 + 524 + 1024 + 8);
  // Of it anonymous: the guest's own anonymous mapping and the page of the library's data it wrote.
  EXPECT_DOUBLE_EQ(kb->anon, 524 + 4);
}

TEST(GuestMemory, TheLowestOfHeapAndExecutableIsTheBoundary) {
  // Without the [heap] line the executable's mapping bounds the guest: the translation buffer
  // below it is then counted too (which is why the heap matters).
  std::string without_heap = kSmaps;
  const auto heap = without_heap.find("555567106000");
  const auto next = without_heap.find("7fc05c000000");
  without_heap.erase(heap, next - heap);
  const auto kb = guest_rss_kb(without_heap, kEmulator);
  ASSERT_TRUE(kb.has_value());
  EXPECT_DOUBLE_EQ(kb->rss, 640 + 524 + 1024 + 8 + 8192);
  EXPECT_DOUBLE_EQ(kb->anon, 524 + 4 + 8192);
}

TEST(GuestMemory, NotAnEmulatorsMapsIsNoFigure) {
  EXPECT_FALSE(guest_rss_kb("5500000000-5500001000 r--p 00000000 fe:01 1 /bin/true\nRss: 4 kB\n", kEmulator));
  EXPECT_FALSE(guest_rss_kb("", kEmulator));
}

TEST(GuestMemory, ANativeProcessHasNone) {
  // A child rather than this test itself, which the cross tier runs under qemu-user. There the
  // child is a copy of qemu until its exec of /bin/sh is done: asked only once the shell speaks.
  auto child = test_support::ChildProcess::start("/bin/sh", {"-c", "echo started; exec sleep 600"});
  ASSERT_TRUE(child.is_ok()) << child.error().message;
  ASSERT_TRUE(child->wait_for_output("started", std::chrono::seconds(20))) << child->stderr_text();
  EXPECT_FALSE(emulated_guest_rss_mb(child->pid()).has_value());
  EXPECT_FALSE(emulated_guest_rss_mb(-1).has_value());  // no such process: no figure, no crash
}

}  // namespace
}  // namespace hubrt::bench
