// Internal to syncap-trigger: the timing benchmark's record of rising-edge errors.
#pragma once

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "syncap/trigger/trigger.h"
#include "trigger_options.h"

struct trigger_bench {
  int64_t* errors_ns;  // each rising edge's error against its schedule; NULL when not benching
  size_t count;
  size_t capacity;
};

// Room for every pulse of a run of `seconds` at `rate_hz`; false when out of memory.
bool trigger_bench_init(struct trigger_bench* b, double rate_hz, int64_t seconds);
// One edge's error; beyond the room it is left out.
void trigger_bench_record(struct trigger_bench* b, int64_t error_ns);
// "syncap-trigger: bench ...": p50, p99 and max error with the core's late and missed counts
// (sorts the errors).
void trigger_bench_print(struct trigger_bench* b, const struct trigger_options* o,
                         const struct syncap_trigger* trigger);
void trigger_bench_free(struct trigger_bench* b);
