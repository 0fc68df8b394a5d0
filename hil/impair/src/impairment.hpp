// The impairments `tc netem` would apply to a datagram (loss, duplication, reordering, a flipped
// bit), decided in user space because sch_netem is not available on the bench's machines (no
// kernel modules, not even inside a private namespace: "Specified qdisc kind is unknown").
//
// Every decision is a hash of (seed, channel, the message's index on its channel), not a shared
// random stream: each sender publishes its channel in order, so the same run injects the same
// faults into the same messages whatever the interleaving of channels at the relay.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace syncap::hil {

struct ImpairmentRates {
  double loss = 0;       // probability that a message is dropped
  double duplicate = 0;  // that it is sent twice
  double reorder = 0;    // that it is held back, so that the ones behind it overtake it
  double corrupt = 0;    // that one bit of it is flipped
};

struct ImpairmentDecision {
  bool drop = false;
  bool duplicate = false;
  bool reorder = false;
  std::optional<uint64_t> flipped_bit;  // bit index in the message, counted from its first byte
};

class Impairment {
 public:
  Impairment(ImpairmentRates rates, uint64_t seed) : rates_(rates), seed_(seed) {}

  // The fate of message number `index` (0-based) on `channel`, `size` bytes long. A dropped
  // message is neither duplicated, reordered nor corrupted; an empty one is never corrupted.
  ImpairmentDecision decide(std::string_view channel, uint64_t index, uint64_t size) const;

  const ImpairmentRates& rates() const { return rates_; }

 private:
  ImpairmentRates rates_;
  uint64_t seed_;
};

// Flips bit `bit` (bit 0: the lowest bit of byte 0) of `data`.
void flip_bit(uint8_t* data, uint64_t bit);

}  // namespace syncap::hil
