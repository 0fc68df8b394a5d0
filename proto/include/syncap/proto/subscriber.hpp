// Typed LCM subscriptions with std::function handlers and named decode errors.
//
// LCM 1.3's C++ API takes member-function handlers only, and reports an undecodable message by a
// bare line on stderr. Subscriber decodes each message itself (proto::try_decode: the generated
// decoders throw on a negative array length), so a malformed one is counted for its channel,
// reaches the error handler with its channel, type and size, and never stops the messages after
// it. A flood of them is reported at most once a second per channel, with the count meanwhile.
//
// LCM's receive thread queues what arrives until handle() takes it, at most 30 messages a
// subscription by default, and drops the rest without a word. One regex subscription for the blob
// messages of 6 cameras holds 5 frames then: a host whose main thread fell 5 frames behind lost
// messages (the likely cause of a CI failure). Subscriber gives each subscription room for
// seconds of traffic instead.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "syncap/proto/decode.hpp"

namespace syncap::proto {

class Subscriber {
 public:
  using ErrorHandler = std::function<void(const std::string& message)>;

  // Messages a subscription keeps waiting for handle(): 10 s of 6 cameras' blob messages at
  // 30 Hz. A held message costs its own size; more than this means the process cannot keep up.
  static constexpr int kDefaultQueueCapacity = 2000;

  // A channel's malformed messages are reported to `on_error` at most this often.
  static constexpr std::chrono::seconds kReportInterval{1};

  // `on_error` gets a line for the first malformed message of a channel, then at most one a
  // kReportInterval per channel; by default such messages are counted only.
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
  // Malformed messages by channel.
  const std::map<std::string, long>& malformed_by_channel() const { return by_channel_; }

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
      const DecodeResult decoded = try_decode(rbuf->data, rbuf->data_size, msg);
      if (!decoded.ok()) {
        owner->report(channel, "malformed " + std::string(Msg::getTypeName()) + " on channel " +
                                   channel + " (" + std::to_string(rbuf->data_size) +
                                   " bytes): " + decoded.error);
        return;
      }
      fn(msg, channel);
    }
    Subscriber* owner;
    std::function<void(const Msg&, const std::string&)> fn;
  };

  struct ChannelReports {
    std::chrono::steady_clock::time_point last;
    long unreported = 0;  // malformed since the last report
  };

  void report(const std::string& channel, const std::string& message) {
    ++malformed_;
    const long count = ++by_channel_[channel];
    ChannelReports& r = reports_[channel];
    const auto now = std::chrono::steady_clock::now();
    if (count > 1 && now - r.last < kReportInterval) {
      ++r.unreported;
      return;
    }
    std::string line = message;
    if (r.unreported > 0) {
      line +=
          " (and " + std::to_string(r.unreported) + " more on this channel since the last report)";
    }
    r.last = now;
    r.unreported = 0;
    if (on_error_) on_error_(line);
  }

  lcm::LCM& lcm_;
  ErrorHandler on_error_;
  int queue_capacity_;
  std::vector<std::unique_ptr<HandlerBase>> handlers_;
  long malformed_ = 0;
  std::map<std::string, long> by_channel_;
  std::map<std::string, ChannelReports> reports_;
};

}  // namespace syncap::proto
