#include "app/publish_queue.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <mutex>
#include <vector>

namespace syncap::edge {
namespace {

// The sending thread stuck in a slow publish: pushing never waits, the oldest message goes.
TEST(PublishQueue, FullQueueDropsTheOldestAndNeverBlocks) {
  std::promise<void> sending_first;
  std::promise<void> network_free;
  std::shared_future<void> free = network_free.get_future().share();
  std::mutex mutex;
  std::vector<int> sent;
  PublishQueue queue(3);
  auto job = [&](int id) {
    return [&, id] {
      if (id == 0) {
        sending_first.set_value();
        free.wait();  // the network is slow
      }
      std::lock_guard lock(mutex);
      sent.push_back(id);
    };
  };
  queue.push(job(0));
  sending_first.get_future().wait();
  for (int id = 1; id <= 5; ++id) queue.push(job(id));  // returns at once though 0 hangs
  PublishQueueStats stats = queue.stats();
  EXPECT_EQ(stats.depth, 3u);
  EXPECT_EQ(stats.capacity, 3u);
  EXPECT_EQ(stats.dropped, 2);
  network_free.set_value();
  queue.flush();
  EXPECT_EQ(sent, (std::vector<int>{0, 3, 4, 5}));
  stats = queue.stats();
  EXPECT_EQ(stats.depth, 0u);
  EXPECT_EQ(stats.published, 4);
}

TEST(PublishQueue, SendsEverythingQueuedBeforeItStops) {
  std::atomic<int> sent{0};
  {
    PublishQueue queue(1000);
    for (int i = 0; i < 500; ++i) queue.push([&] { ++sent; });
  }
  EXPECT_EQ(sent.load(), 500);
}

}  // namespace
}  // namespace syncap::edge
