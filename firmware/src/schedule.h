// Internal: the pulse schedule as exact integer arithmetic.
#pragma once

#include <stdint.h>

// 1e9 ns/s times 1e6 uHz/Hz: the period in ns is this divided by the rate in uHz.
#define SYNCAP_NS_UHZ_PER_PERIOD UINT64_C(1000000000000000)

// rate_hz (already validated) as a whole number of micro-hertz, rounded to nearest.
uint64_t syncap_schedule_rate_uhz(double rate_hz);

// floor(index * 1e9 / rate) ns, exact: the time of pulse `index` after pulse 0.
int64_t syncap_schedule_offset_ns(uint64_t rate_uhz, uint64_t index);

// The largest index whose offset is <= elapsed_ns (elapsed_ns >= 0).
uint64_t syncap_schedule_index_at(uint64_t rate_uhz, int64_t elapsed_ns);
