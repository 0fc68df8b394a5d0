// syncap-trigger --bench: every rising edge's error against its schedule, and its percentiles
// (trigger_bench.h, docs/design/trigger.md "Benchmark mode").
#include "trigger_bench.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>

bool trigger_bench_init(struct trigger_bench* b, double rate_hz, int64_t seconds) {
  // Room for every pulse of the run (count = rate * seconds).
  b->capacity = (size_t)(rate_hz * (double)seconds) + 1;
  b->count = 0;
  b->errors_ns = calloc(b->capacity, sizeof(int64_t));
  return b->errors_ns != NULL;
}

void trigger_bench_record(struct trigger_bench* b, int64_t error_ns) {
  if (b->count == b->capacity) return;
  b->errors_ns[b->count++] = error_ns;
}

void trigger_bench_free(struct trigger_bench* b) {
  free(b->errors_ns);
  b->errors_ns = NULL;
}

static int compare_ns(const void* a, const void* b) {
  const int64_t x = *(const int64_t*)a;
  const int64_t y = *(const int64_t*)b;
  return (x > y) - (x < y);
}

// Nearest-rank percentile of sorted values.
static int64_t percentile(const int64_t* sorted, size_t count, double p) {
  size_t rank = (size_t)(p / 100.0 * (double)count + 0.999999);
  if (rank < 1) rank = 1;
  if (rank > count) rank = count;
  return sorted[rank - 1];
}

void trigger_bench_print(struct trigger_bench* b, const struct trigger_options* o,
                         const struct syncap_trigger* trigger) {
  struct syncap_trigger_stats stats;
  syncap_trigger_get_stats(trigger, &stats);
  if (b->count == 0) {
    printf("syncap-trigger: bench: no pulses\n");
    return;
  }
  qsort(b->errors_ns, b->count, sizeof(int64_t), compare_ns);
  printf(
      "syncap-trigger: bench %g Hz, %zu edges on chip %s: rising-edge error p50 %.1f us, "
      "p99 %.1f us, max %.1f us (late=%" PRIu64 " missed=%" PRIu64 ")\n",
      o->rate_hz, b->count, o->chip, (double)percentile(b->errors_ns, b->count, 50.0) / 1000.0,
      (double)percentile(b->errors_ns, b->count, 99.0) / 1000.0,
      (double)b->errors_ns[b->count - 1] / 1000.0, stats.late, stats.missed);
}
