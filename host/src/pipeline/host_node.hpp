// The host's core, as the edge's EdgeNode is the edge's: receives the messages, groups them by
// frame number, and runs a chain of stages on each frame group, complete or (timed out) flagged
// incomplete, on a worker thread: reception never waits for a stage. LCM is reached only by the
// caller (host_main), so tests drive the node without a network.
#pragma once

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "grouping/frame_grouper.hpp"
#include "pipeline/frame_work.hpp"
#include "pipeline/recent_values.hpp"

namespace syncap::pipeline {

struct HostNodeOptions {
  std::set<int> cameras{0};  // expected camera ids
  int max_lag_frames = 10;   // frames to wait for missing messages
  // Frame groups waiting for the worker before the oldest is dropped (and counted): 10 s at
  // 100 Hz. Only a host that cannot keep up ever fills it.
  std::size_t queue_capacity = 1000;
};

struct HostNodeStats {
  long groups = 0;  // handed out by the grouper
  long complete = 0;
  long processed = 0;    // through every stage
  long dropped = 0;      // dropped from a full queue
  RecentValues host_us;  // ready to the last stage's end, of the latest processed groups
  // The worker thread's CPU time in the stages of each of those groups: the host's own cost,
  // without the waits for a CPU that host_us holds on a loaded machine.
  RecentValues host_cpu_us;
};

class HostNode {
 public:
  HostNode(HostNodeOptions options, std::vector<std::unique_ptr<Stage>> stages);
  ~HostNode();  // finish() if not done
  HostNode(const HostNode&) = delete;
  HostNode& operator=(const HostNode&) = delete;

  // The receiving side (one thread). False (with grouper().error()) for a message the grouper
  // rejects.
  bool on_trigger(const trigger_t& trigger);
  bool on_blob_part(const blob_frame_t& part, std::string_view channel = {});
  bool on_silhouette_part(const silhouette_part_t& part, std::string_view channel = {});
  bool on_patch_part(const image_patch_t& part, std::string_view channel = {});
  // Hands the groups that are ready to the worker; returns how many.
  std::size_t poll();
  // Hands out every group still held, waits until the worker has run them all through the
  // stages, then calls each stage's finish(). Idempotent.
  void finish();

  const grouping::FrameGrouper& grouper() const { return grouper_; }
  // A copy, taken under the lock (the worker updates it).
  HostNodeStats stats() const;

 private:
  void hand_out(std::vector<grouping::FrameGroup> groups);
  void work();

  HostNodeOptions options_;
  std::vector<std::unique_ptr<Stage>> stages_;
  grouping::FrameGrouper grouper_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<FrameWork> queue_;
  bool closing_ = false;
  bool finished_ = false;
  HostNodeStats stats_;
  std::thread worker_;
};

}  // namespace syncap::pipeline
