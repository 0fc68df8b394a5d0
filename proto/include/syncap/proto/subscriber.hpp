// Typed LCM subscriptions with std::function handlers and named decode errors.
//
// LCM 1.3's C++ API takes member-function handlers only, and reports an undecodable message by a
// bare line on stderr. Subscriber decodes each message itself, so a malformed one reaches the
// error handler with its channel, type and size, and never stops the messages after it.
//
// LCM's receive thread queues what arrives until handle() takes it, at most 30 messages a
// subscription by default, and drops the rest without a word. One regex subscription for the blob
// messages of 6 cameras holds 5 frames then: a host whose main thread fell 5 frames behind lost
// messages (the likely cause of a CI failure). Subscriber gives each subscription room for
// seconds of traffic instead.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace syncap::proto {

class Subscriber {
 public:
  using ErrorHandler = std::function<void(const std::string& message)>;

  // Messages a subscription keeps waiting for handle(): 10 s of 6 cameras' blob messages at
  // 30 Hz. A held message costs its own size; more than this means the process cannot keep up.
  static constexpr int kDefaultQueueCapacity = 2000;

  // `on_error` gets one line per malformed message; by default such messages are counted only.
  explicit Subscriber(lcm::LCM& lcm, ErrorHandler on_error = {},
                      int queue_capacity = kDefaultQueueCapacity)
      : lcm_(lcm), on_error_(std::move(on_error)), queue_capacity_(queue_capacity) {}
  Subscriber(const Subscriber&) = delete;
  Subscriber& operator=(const Subscriber&) = delete;
  ~Subscriber() {
    for (auto& h : handlers_) lcm_.unsubscribe(h->subscription);
  }

  // `channel` is an LCM channel regex ("SYNCAP_BLOBS_.*").
  template <class Msg>
  void subscribe(const std::string& channel,
                 std::function<void(const Msg&, const std::string& channel)> handler) {
    auto h = std::make_unique<Handler<Msg>>(this, std::move(handler));
    h->subscription = lcm_.subscribe(channel, &Handler<Msg>::on_raw, h.get());
    h->subscription->setQueueCapacity(queue_capacity_);
    handlers_.push_back(std::move(h));
  }

  long malformed() const { return malformed_; }

 private:
  struct HandlerBase {
    virtual ~HandlerBase() = default;
    lcm::Subscription* subscription = nullptr;
  };

  template <class Msg>
  struct Handler : HandlerBase {
    Handler(Subscriber* subscriber, std::function<void(const Msg&, const std::string&)> handler)
        : owner(subscriber), fn(std::move(handler)) {}
    void on_raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
      Msg msg;
      if (msg.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) < 0) {
        owner->report("malformed " + std::string(Msg::getTypeName()) + " on channel " + channel +
                      " (" + std::to_string(rbuf->data_size) + " bytes): decode failed");
        return;
      }
      fn(msg, channel);
    }
    Subscriber* owner;
    std::function<void(const Msg&, const std::string&)> fn;
  };

  void report(const std::string& message) {
    ++malformed_;
    if (on_error_) on_error_(message);
  }

  lcm::LCM& lcm_;
  ErrorHandler on_error_;
  int queue_capacity_;
  std::vector<std::unique_ptr<HandlerBase>> handlers_;
  long malformed_ = 0;
};

}  // namespace syncap::proto
