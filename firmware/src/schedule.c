#include "schedule.h"

uint64_t syncap_schedule_rate_uhz(double rate_hz) { return (uint64_t)(rate_hz * 1e6 + 0.5); }

// With N = 1e15 and D = rate_uhz, split index = q*D + r and N = nq*D + nr:
//   index*N/D = q*N + r*nq + r*nr/D
// where r*nq <= N and r*nr < D*D <= 1e18, so nothing overflows before the result itself does.
int64_t syncap_schedule_offset_ns(uint64_t rate_uhz, uint64_t index) {
  const uint64_t n = SYNCAP_NS_UHZ_PER_PERIOD;
  const uint64_t q = index / rate_uhz;
  const uint64_t r = index % rate_uhz;
  return (int64_t)(q * n + r * (n / rate_uhz) + r * (n % rate_uhz) / rate_uhz);
}

// A floating-point estimate, corrected with the exact offsets (it is off by at most one or two).
uint64_t syncap_schedule_index_at(uint64_t rate_uhz, int64_t elapsed_ns) {
  const double estimate = (double)elapsed_ns * (double)rate_uhz / (double)SYNCAP_NS_UHZ_PER_PERIOD;
  uint64_t index = (uint64_t)estimate;
  while (index > 0 && syncap_schedule_offset_ns(rate_uhz, index) > elapsed_ns) --index;
  while (syncap_schedule_offset_ns(rate_uhz, index + 1) <= elapsed_ns) ++index;
  return index;
}
