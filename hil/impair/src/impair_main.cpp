// syncap-hil-impair: relays every LCM message from one URL to another, dropping, duplicating,
// reordering and corrupting a chosen share of them (what `tc netem` does to datagrams, in user
// space: docs/design/reliability.md, "Faults"). The replay bench points the trigger and the edges
// at the input URL and the host and lcm-logger at the output URL.
#include <lcm/lcm.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstring>
#include <ctime>
#include <deque>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "impairment.hpp"
#include "syncap/cli/options.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/clock.hpp"

namespace {

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }

namespace cli = syncap::cli;

struct Options {
  std::string in, out, stats;
  syncap::hil::ImpairmentRates rates;
  int reorder_delay_ms = 10;
  uint64_t seed = 1;
  bool quiet = false;
};

// "0.05" or "5%": a probability in [0, 1]; the text becomes the fraction CLI11 then converts.
CLI::Validator probability() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const bool percent = !text.empty() && text.back() == '%';
        std::optional<double> v =
            cli::finite_number(percent ? text.substr(0, text.size() - 1) : text);
        if (v && percent) *v /= 100;
        if (!v || *v < 0 || *v > 1)
          return "'" + text + "': expected a probability, 0 to 1 or 0% to 100%";
        text = cli::number_text(*v);
        return {};
      },
      "0..1 or 0%..100%");
}

constexpr const char* kDescription =
    "usage: syncap-hil-impair --in URL --out URL [options]\n"
    "Relays every LCM message received on --in to --out, impaired as below; decisions are a\n"
    "hash of (seed, channel, the message's index on its channel), so a run is reproducible.\n";

constexpr const char* kFooter =
    "Prints 'syncap-hil-impair: relaying IN -> OUT ...' once listening, and on SIGINT/SIGTERM\n"
    "(after sending the messages still held) 'syncap-hil-impair: received N, forwarded N,\n"
    "dropped N, duplicated N, reordered N, corrupted N'. Exit 0; 1 when an LCM URL cannot be\n"
    "opened or FILE written; 2 for wrong arguments.";

void add_impairment_options(CLI::App& app, Options& o) {
  auto& r = o.rates;
  cli::add_checked(app, "--loss", r.loss, "P", probability(),
                   "drop a message with probability P: 0.05 or 5% (default 0)");
  cli::add_checked(app, "--duplicate", r.duplicate, "P", probability(),
                   "send a message twice (default 0)");
  cli::add_checked(app, "--reorder", r.reorder, "P", probability(),
                   "hold a message back --reorder-delay-ms, so that later ones\n"
                   "overtake it (default 0)");
  cli::add_checked(app, "--reorder-delay-ms", o.reorder_delay_ms, "N", cli::whole_in(1, 10000),
                   "how long a reordered message is held, 1..10000 (default 10)");
  cli::add_checked(app, "--corrupt", r.corrupt, "P", probability(),
                   "flip one bit of a message, anywhere in it (default 0)");
  cli::add_checked(app, "--seed", o.seed, "N", cli::whole_in<uint64_t>(0, UINT64_MAX),
                   "seed of the decisions (default 1)");
}

// Parses into `o`; the exit status when the run is over already (help, usage error).
std::optional<int> parse_options(int argc, char** argv, Options& o) {
  cli::App app("syncap-hil-impair", kDescription, kFooter);
  app.add_option("--in", o.in, "LCM URL the senders publish on (received with a 4 MiB buffer)")
      ->option_text("URL")
      ->required();
  app.add_option("--out", o.out, "LCM URL the impaired messages are published on")
      ->option_text("URL")
      ->required();
  add_impairment_options(app, o);
  app.add_option("--stats", o.stats, "at exit, write the counts (total and per channel) as JSON")
      ->option_text("FILE");
  app.add_flag("--quiet", o.quiet, "no start line and no summary");
  return cli::parse_main(app, argc, argv, [&o] {
    if (o.in == o.out)
      throw CLI::ValidationError("--in and --out are both '" + o.in + "': the relay would loop");
  });
}

int64_t monotonic_ns() { return syncap::proto::monotonic_now_ns(); }

struct Counts {
  long received = 0, forwarded = 0, dropped = 0, duplicated = 0, reordered = 0, corrupted = 0;
};

nlohmann::json counts_json(const Counts& c) {
  return {{"received", c.received},     {"forwarded", c.forwarded}, {"dropped", c.dropped},
          {"duplicated", c.duplicated}, {"reordered", c.reordered}, {"corrupted", c.corrupted}};
}

class Relay {
 public:
  Relay(const Options& options, lcm_t* out)
      : options_(options), impairment_(options.rates, options.seed), out_(out) {}

  void on_message(const lcm_recv_buf_t* rbuf, const char* channel_name) {
    const std::string channel = channel_name;
    Counts& on_channel = by_channel_[channel];
    const auto index = static_cast<uint64_t>(on_channel.received);
    count(on_channel, &Counts::received);
    const auto d = impairment_.decide(channel, index, rbuf->data_size);
    if (d.drop) {
      count(on_channel, &Counts::dropped);
      return;
    }
    Held message{channel, {}, 0, d.duplicate};
    const auto* bytes = static_cast<const uint8_t*>(rbuf->data);
    message.data.assign(bytes, bytes + rbuf->data_size);
    if (d.flipped_bit) {
      syncap::hil::flip_bit(message.data.data(), *d.flipped_bit);
      count(on_channel, &Counts::corrupted);
    }
    if (d.reorder) {
      count(on_channel, &Counts::reordered);
      message.release_ns = monotonic_ns() + int64_t{options_.reorder_delay_ms} * 1'000'000;
      held_.push_back(std::move(message));
      return;
    }
    send(message);
  }

  // Milliseconds until the oldest held message is due (at most `idle_ms`).
  int wait_ms(int idle_ms) const {
    if (held_.empty()) return idle_ms;
    const int64_t left = held_.front().release_ns - monotonic_ns();
    return static_cast<int>(std::clamp<int64_t>(left / 1'000'000, 0, idle_ms));
  }

  // Sends the held messages that are due (all of them when `all`).
  void release(bool all) {
    const int64_t now = monotonic_ns();
    while (!held_.empty() && (all || held_.front().release_ns <= now)) {
      send(held_.front());
      held_.pop_front();
    }
  }

  std::string summary() const {
    return "syncap-hil-impair: received " + std::to_string(total_.received) + ", forwarded " +
           std::to_string(total_.forwarded) + ", dropped " + std::to_string(total_.dropped) +
           ", duplicated " + std::to_string(total_.duplicated) + ", reordered " +
           std::to_string(total_.reordered) + ", corrupted " + std::to_string(total_.corrupted);
  }

  nlohmann::json stats() const {
    nlohmann::json channels = nlohmann::json::object();
    for (const auto& [channel, c] : by_channel_) channels[channel] = counts_json(c);
    const auto& r = options_.rates;
    return {{"rates",
             {{"loss", r.loss},
              {"duplicate", r.duplicate},
              {"reorder", r.reorder},
              {"corrupt", r.corrupt},
              {"reorder_delay_ms", options_.reorder_delay_ms},
              {"seed", options_.seed}}},
            {"total", counts_json(total_)},
            {"channels", channels}};
  }

 private:
  struct Held {
    std::string channel;
    std::vector<uint8_t> data;
    int64_t release_ns;
    bool duplicate;
  };

  void count(Counts& on_channel, long Counts::*field) {
    ++(on_channel.*field);
    ++(total_.*field);
  }

  void send(const Held& message) {
    Counts& on_channel = by_channel_[message.channel];
    const int copies = message.duplicate ? 2 : 1;
    for (int i = 0; i < copies; ++i) {
      if (lcm_publish(out_, message.channel.c_str(), message.data.data(),
                      static_cast<unsigned>(message.data.size())) == 0) {
        count(on_channel, &Counts::forwarded);
      }
    }
    if (message.duplicate) count(on_channel, &Counts::duplicated);
  }

  const Options& options_;
  syncap::hil::Impairment impairment_;
  lcm_t* out_;
  std::deque<Held> held_;  // reordered messages, in release order (one delay for all)
  std::map<std::string, Counts> by_channel_;
  Counts total_;
};

void on_lcm_message(const lcm_recv_buf_t* rbuf, const char* channel, void* relay) {
  static_cast<Relay*>(relay)->on_message(rbuf, channel);
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (const auto status = parse_options(argc, argv, options)) return *status;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const std::string in_url = syncap::proto::receiving_lcm_url(options.in);
  lcm_t* in = lcm_create(in_url.c_str());
  lcm_t* out = lcm_create(options.out.c_str());
  if (in == nullptr || out == nullptr) {
    std::cerr << "syncap-hil-impair: cannot open LCM at " << (in ? options.out : in_url) << "\n";
    return 1;
  }
  Relay relay(options, out);
  lcm_subscribe(in, ".*", on_lcm_message, &relay);
  if (!options.quiet) {
    const auto& r = options.rates;
    std::cout << "syncap-hil-impair: relaying " << options.in << " -> " << options.out << " (loss "
              << r.loss << ", duplicate " << r.duplicate << ", reorder " << r.reorder << " by "
              << options.reorder_delay_ms << " ms, corrupt " << r.corrupt << ", seed "
              << options.seed << ")" << std::endl;
  }
  int status = 0;
  while (!g_stop) {
    // A signal interrupts the wait (-1 with g_stop set): that is the way out, not a failure.
    if (lcm_handle_timeout(in, relay.wait_ms(100)) < 0 && !g_stop) {
      std::cerr << "syncap-hil-impair: receiving on " << in_url << " failed\n";
      status = 1;
      break;
    }
    relay.release(false);
  }
  relay.release(true);
  if (!options.quiet) std::cout << relay.summary() << std::endl;
  if (!options.stats.empty()) {
    std::ofstream file(options.stats);
    file << relay.stats().dump(2) << "\n";
    if (!file) {
      std::cerr << "syncap-hil-impair: cannot write " << options.stats << "\n";
      status = 1;
    }
  }
  lcm_destroy(in);
  lcm_destroy(out);
  return status;
}
