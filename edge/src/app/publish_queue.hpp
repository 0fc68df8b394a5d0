// Publishing off the acquisition path: messages wait in a bounded queue that one thread of its
// own sends (LCM publish can block on a full socket buffer or a slow network stack). When the
// queue is full the oldest message is dropped and counted: late data is worth less than the
// next frame, and acquisition never waits for the network.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

namespace syncap::edge {

struct PublishQueueStats {
  std::size_t depth = 0;  // messages waiting now
  std::size_t capacity = 0;
  int64_t dropped = 0;    // since start
  int64_t published = 0;  // since start
};

class PublishQueue {
 public:
  using Job = std::function<void()>;  // sends one message

  // Starts the sending thread.
  explicit PublishQueue(std::size_t capacity);
  // Sends what is still queued, then stops the thread.
  ~PublishQueue();
  PublishQueue(const PublishQueue&) = delete;
  PublishQueue& operator=(const PublishQueue&) = delete;

  // Never blocks on the sending: a full queue drops its oldest job.
  void push(Job job);
  // Waits until every job pushed so far has been sent (or dropped).
  void flush();
  PublishQueueStats stats() const;

 private:
  void run();

  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;  // a job arrived, or stop
  std::condition_variable idle_;  // the queue ran empty and nothing is being sent
  std::deque<Job> jobs_;
  bool sending_ = false;
  bool stop_ = false;
  int64_t dropped_ = 0;
  int64_t published_ = 0;
  std::thread thread_;  // last: starts after the members it uses
};

}  // namespace syncap::edge
