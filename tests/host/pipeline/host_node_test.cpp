#include "pipeline/host_node.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <thread>

namespace syncap::pipeline {
namespace {

// Records the frames it sees; can hold the worker until released.
class RecordingStage : public Stage {
 public:
  const char* name() const override { return "recording"; }
  void process(FrameWork& work) override {
    if (hold_) gate_.wait();
    frames.push_back(work.group.frame_number);
    complete.push_back(work.group.complete());
  }
  void finish() override { ++finishes; }
  void hold() { hold_ = true; }
  void release() { release_.set_value(); }
  std::vector<int64_t> frames;
  std::vector<bool> complete;
  int finishes = 0;

 private:
  bool hold_ = false;
  std::promise<void> release_;
  std::shared_future<void> gate_ = release_.get_future().share();
};

trigger_t trigger(int64_t frame) {
  trigger_t t{};
  t.frame_number = frame;
  return t;
}

blob_frame_t blobs(int camera, int64_t frame) {
  blob_frame_t f{};
  f.camera_id = static_cast<int16_t>(camera);
  f.frame_number = frame;
  f.part_count = 1;
  return f;
}

struct NodeWithRecorder {
  explicit NodeWithRecorder(std::set<int> cameras, std::size_t capacity = 1000) {
    auto stage = std::make_unique<RecordingStage>();
    recorder = stage.get();
    std::vector<std::unique_ptr<Stage>> stages;
    stages.push_back(std::move(stage));
    node = std::make_unique<HostNode>(HostNodeOptions{std::move(cameras), 2, capacity},
                                      std::move(stages));
  }
  RecordingStage* recorder;
  std::unique_ptr<HostNode> node;
};

TEST(HostNode, EveryGroupGoesThroughTheStagesInFrameOrderCompleteOrFlagged) {
  NodeWithRecorder n({0, 1});
  for (int64_t k = 0; k < 6; ++k) {
    n.node->on_trigger(trigger(k));
    n.node->on_blob_part(blobs(0, k));
    if (k != 2) n.node->on_blob_part(blobs(1, k));  // camera 1 loses frame 2
    n.node->poll();
  }
  n.node->finish();
  EXPECT_EQ(n.recorder->frames, (std::vector<int64_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(n.recorder->complete, (std::vector<bool>{true, true, false, true, true, true}));
  EXPECT_EQ(n.recorder->finishes, 1);
  n.node->finish();  // idempotent
  EXPECT_EQ(n.recorder->finishes, 1);
  const HostNodeStats s = n.node->stats();
  EXPECT_EQ(s.groups, 6);
  EXPECT_EQ(s.complete, 5);
  EXPECT_EQ(s.processed, 6);
  EXPECT_EQ(s.host_us.added(), 6u);
}

// A stage that takes long (or hangs) never holds up reception: the messages keep being grouped
// and handed to the queue while the worker waits.
TEST(HostNode, ASlowStageNeverBlocksReception) {
  NodeWithRecorder n({0});
  n.recorder->hold();
  const auto start = std::chrono::steady_clock::now();
  for (int64_t k = 0; k < 200; ++k) {
    n.node->on_trigger(trigger(k));
    n.node->on_blob_part(blobs(0, k));
    n.node->poll();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
  EXPECT_EQ(n.node->stats().groups, 200);
  EXPECT_LE(n.node->stats().processed, 1);
  n.recorder->release();
  n.node->finish();
  EXPECT_EQ(n.recorder->frames.size(), 200u);
}

TEST(HostNode, AFullQueueDropsTheOldestAndCountsThem) {
  NodeWithRecorder n({0}, /*capacity=*/10);
  n.recorder->hold();
  for (int64_t k = 0; k < 50; ++k) {
    n.node->on_trigger(trigger(k));
    n.node->on_blob_part(blobs(0, k));
    n.node->poll();
  }
  // Wait until the worker holds one frame in its stage, so the count below is exact.
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  n.recorder->release();
  n.node->finish();
  const HostNodeStats s = n.node->stats();
  EXPECT_EQ(s.groups, 50);
  EXPECT_EQ(s.processed + s.dropped, 50);
  EXPECT_GE(s.dropped, 39);
  EXPECT_EQ(n.recorder->frames.back(), 49) << "the newest frames are kept";
}

// Sleeps 30 ms (no CPU), then spins until its thread has used 10 ms of CPU time.
class WaitThenSpinStage : public Stage {
 public:
  const char* name() const override { return "wait-then-spin"; }
  void process(FrameWork&) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    const double start_us = thread_cpu_us();
    while (thread_cpu_us() - start_us < 10'000) {
    }
  }
};

// host_us is the wall time from the group's hand-out to the last stage's end; host_cpu_us the
// worker's CPU time in the stages (a stage that waits for a CPU, or sleeps, adds to the first
// only).
TEST(HostNode, TheHostsWallAndCpuTimePerGroupAreMeasuredApart) {
  std::vector<std::unique_ptr<Stage>> stages;
  stages.push_back(std::make_unique<WaitThenSpinStage>());
  HostNode node(HostNodeOptions{{0}, 2, 1000}, std::move(stages));
  node.on_trigger(trigger(0));
  node.on_blob_part(blobs(0, 0));
  node.poll();
  node.finish();
  const HostNodeStats s = node.stats();
  ASSERT_EQ(s.host_cpu_us.values().size(), 1u);
  EXPECT_GE(s.host_us.values()[0], 40'000);
  EXPECT_GE(s.host_cpu_us.values()[0], 10'000);
  EXPECT_LT(s.host_cpu_us.values()[0], s.host_us.values()[0] - 25'000);
}

TEST(RecentValues, KeepsTheLatestAndTheQuantilesAreNearestRank) {
  RecentValues v(4);
  for (int i = 1; i <= 10; ++i) v.add(i);
  EXPECT_EQ(v.added(), 10u);
  ASSERT_EQ(v.values().size(), 4u);
  EXPECT_DOUBLE_EQ(quantile(v.values(), 0.0), 7);
  EXPECT_DOUBLE_EQ(quantile(v.values(), 0.5), 8);
  EXPECT_DOUBLE_EQ(quantile(v.values(), 1.0), 10);
  EXPECT_DOUBLE_EQ(quantile({}, 0.5), 0);
}

}  // namespace
}  // namespace syncap::pipeline
