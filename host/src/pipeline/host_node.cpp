#include "pipeline/host_node.hpp"

#include <algorithm>
#include <cmath>

namespace syncap::pipeline {

HostNode::HostNode(HostNodeOptions options, std::vector<std::unique_ptr<Stage>> stages)
    : options_(std::move(options)),
      stages_(std::move(stages)),
      grouper_(options_.cameras, options_.max_lag_frames),
      worker_([this] { work(); }) {}

HostNode::~HostNode() { finish(); }

bool HostNode::on_trigger(const trigger_t& trigger) { return grouper_.add_trigger(trigger); }

bool HostNode::on_blob_part(const blob_frame_t& part, std::string_view channel) {
  return grouper_.add_blob_part(part, channel);
}

bool HostNode::on_patch_part(const image_patch_t& part, std::string_view channel) {
  return grouper_.add_patch_part(part, channel);
}

bool HostNode::on_silhouette_part(const silhouette_part_t& part, std::string_view channel) {
  return grouper_.add_silhouette_part(part, channel);
}

std::size_t HostNode::poll() {
  std::vector<grouping::FrameGroup> ready = grouper_.pop_ready();
  const std::size_t count = ready.size();
  hand_out(std::move(ready));
  return count;
}

void HostNode::hand_out(std::vector<grouping::FrameGroup> groups) {
  if (groups.empty()) return;
  const auto now = std::chrono::steady_clock::now();
  {
    const std::lock_guard lock(mutex_);
    for (grouping::FrameGroup& g : groups) {
      ++stats_.groups;
      if (g.complete()) ++stats_.complete;
      if (queue_.size() >= options_.queue_capacity) {
        queue_.pop_front();  // the oldest: live output wants the newest frames
        ++stats_.dropped;
      }
      FrameWork work;
      work.group = std::move(g);
      work.ready = now;
      queue_.push_back(std::move(work));
    }
  }
  wake_.notify_one();
}

void HostNode::work() {
  for (;;) {
    FrameWork work;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return closing_ || !queue_.empty(); });
      if (queue_.empty()) return;  // closing, and everything done
      work = std::move(queue_.front());
      queue_.pop_front();
    }
    work.cpu_start_us = thread_cpu_us();
    for (const auto& stage : stages_) stage->process(work);
    const double cpu_us = thread_cpu_us() - work.cpu_start_us;
    const double us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - work.ready)
            .count();
    const std::lock_guard lock(mutex_);
    stats_.host_us.add(us);
    stats_.host_cpu_us.add(cpu_us);
    ++stats_.processed;
  }
}

void HostNode::finish() {
  if (finished_) return;
  finished_ = true;
  hand_out(grouper_.flush());
  {
    const std::lock_guard lock(mutex_);
    closing_ = true;
  }
  wake_.notify_one();
  worker_.join();
  for (const auto& stage : stages_) stage->finish();
}

HostNodeStats HostNode::stats() const {
  const std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace syncap::pipeline
