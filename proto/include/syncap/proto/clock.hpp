// The two clocks every process stamps its messages with, in ns: CLOCK_MONOTONIC (the trigger's
// edge times and the edges' frame arrivals, comparable on one board) and CLOCK_REALTIME (across
// machines, as far as NTP/PTP keeps them together). steady_clock and system_clock are these two
// clocks on Linux with glibc; asking the kernel by name keeps the messages' meaning explicit.
#pragma once

#include <cstdint>
#include <ctime>

namespace syncap::proto {

inline int64_t clock_now_ns(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

inline int64_t monotonic_now_ns() { return clock_now_ns(CLOCK_MONOTONIC); }
inline int64_t realtime_now_ns() { return clock_now_ns(CLOCK_REALTIME); }

}  // namespace syncap::proto
