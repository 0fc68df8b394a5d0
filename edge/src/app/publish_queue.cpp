#include "app/publish_queue.hpp"

#include <algorithm>

namespace syncap::edge {

PublishQueue::PublishQueue(std::size_t capacity)
    : capacity_(std::max<std::size_t>(capacity, 1)), thread_([this] { run(); }) {}

PublishQueue::~PublishQueue() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void PublishQueue::push(Job job) {
  {
    std::lock_guard lock(mutex_);
    if (jobs_.size() >= capacity_) {
      jobs_.pop_front();
      ++dropped_;
    }
    jobs_.push_back(std::move(job));
  }
  wake_.notify_one();
}

void PublishQueue::flush() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return jobs_.empty() && !sending_; });
}

PublishQueueStats PublishQueue::stats() const {
  std::lock_guard lock(mutex_);
  return {jobs_.size(), capacity_, dropped_, published_};
}

void PublishQueue::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || !jobs_.empty(); });
    if (jobs_.empty()) return;  // stop, and everything sent
    Job job = std::move(jobs_.front());
    jobs_.pop_front();
    sending_ = true;
    lock.unlock();
    job();
    lock.lock();
    sending_ = false;
    ++published_;
    if (jobs_.empty()) idle_.notify_all();
  }
}

}  // namespace syncap::edge
