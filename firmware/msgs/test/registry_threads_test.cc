// all_types() is built on first use; several threads using it first at the same moment must all
// get the one complete registry (TSan checks the rest in the thread-sanitizer build).
#include <atomic>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/msgs/all_types.h"

namespace hubrt::msgs {
namespace {

TEST(AllTypesThreads, ConcurrentFirstUseSeesOneCompleteRegistry) {
  constexpr int kThreads = 8;
  std::atomic<int> waiting{kThreads};
  std::vector<const TypeRegistry*> seen(kThreads, nullptr);
  std::vector<const TypeInfo*> found(kThreads, nullptr);
  std::vector<std::thread> threads;
  threads.reserve(kThreads);
  for (int i = 0; i < kThreads; ++i) {
    threads.emplace_back([&, i] {
      // Start together so that the first use really is concurrent.
      waiting.fetch_sub(1);
      while (waiting.load() > 0) std::this_thread::yield();
      seen[i] = &all_types();
      found[i] = all_types().find("hub_msgs/msg/DockState");
    });
  }
  for (auto& t : threads) t.join();
  for (int i = 0; i < kThreads; ++i) {
    EXPECT_EQ(seen[i], seen[0]);
    ASSERT_NE(found[i], nullptr);
    EXPECT_EQ(found[i]->dds_name, "hub_msgs::msg::dds_::DockState_");
  }
}

}  // namespace
}  // namespace hubrt::msgs
