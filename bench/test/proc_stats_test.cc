// bench/support/proc_stats: the memory figures read for a process.
#include "proc_stats.h"

#include <unistd.h>

#include <cstddef>
#include <memory>

#include <gtest/gtest.h>

namespace hubrt::bench {
namespace {

TEST(ProcStats, AnonymousMemoryIsThePartOfTheResidentSetNoFileBacks) {
  auto before = read_proc(getpid());
  ASSERT_TRUE(before) << before.error().message;
  EXPECT_GT(before->anon_mb, 0.0);
  EXPECT_LE(before->anon_mb, before->rss_mb);
  // 16 MB of heap, every page written: resident and anonymous both grow by about that (a little
  // less would mean pages were not all touched yet; the bound leaves room for that).
  constexpr std::size_t kBytes = std::size_t{16} << 20;
  const auto block = std::make_unique<char[]>(kBytes);
  for (std::size_t i = 0; i < kBytes; i += 4096) block[i] = static_cast<char>(i / 4096 % 100 + 1);
  auto after = read_proc(getpid());
  ASSERT_TRUE(after) << after.error().message;
  EXPECT_GE(after->anon_mb - before->anon_mb, 12.0);
  EXPECT_GE(after->rss_mb - before->rss_mb, 12.0);
  EXPECT_LE(after->anon_mb, after->rss_mb);
  // Keeps the writes from being optimised away.
  EXPECT_EQ(block[std::size_t{3} * 4096], 4);
}

}  // namespace
}  // namespace hubrt::bench
