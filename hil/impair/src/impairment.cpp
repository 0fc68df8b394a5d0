#include "impairment.hpp"

namespace syncap::hil {
namespace {

// SplitMix64's finaliser: a well-mixed 64-bit value from any 64-bit input.
uint64_t mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// FNV-1a of the channel name.
uint64_t channel_hash(std::string_view channel) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (const char c : channel) h = (h ^ static_cast<uint8_t>(c)) * 0x100000001b3ULL;
  return h;
}

// A uniform number in [0, 1) from 53 bits of `x`.
double unit(uint64_t x) { return static_cast<double>(x >> 11) * 0x1.0p-53; }

}  // namespace

ImpairmentDecision Impairment::decide(std::string_view channel, uint64_t index,
                                      uint64_t size) const {
  // One independent draw per impairment: successive outputs of a stream keyed by the message.
  uint64_t state = mix(seed_ ^ mix(channel_hash(channel) ^ mix(index)));
  auto draw = [&state] {
    state = mix(state);
    return state;
  };
  ImpairmentDecision d;
  d.drop = unit(draw()) < rates_.loss;
  const bool duplicate = unit(draw()) < rates_.duplicate;
  const bool reorder = unit(draw()) < rates_.reorder;
  const bool corrupt = unit(draw()) < rates_.corrupt;
  const uint64_t bit = draw();
  if (d.drop) return d;
  d.duplicate = duplicate;
  d.reorder = reorder;
  if (corrupt && size > 0) d.flipped_bit = bit % (size * 8);
  return d;
}

void flip_bit(uint8_t* data, uint64_t bit) {
  data[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
}

}  // namespace syncap::hil
