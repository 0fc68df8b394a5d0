// Shared by the trigger core tests: a trigger with a given rate and count, 1 us pulses, 100 us
// late tolerance, failing the test when it cannot be made.
#pragma once

#include "cmocka_main.h"

#include "syncap/trigger/trigger.h"

#define FIXTURE_WIDTH_NS 1000
#define FIXTURE_TOLERANCE_NS 100000

static inline struct syncap_trigger* new_trigger(double rate_hz, uint64_t count) {
  struct syncap_trigger_config config;
  syncap_trigger_config_init(&config);
  config.rate_hz = rate_hz;
  config.pulse_width_ns = FIXTURE_WIDTH_NS;
  config.late_tolerance_ns = FIXTURE_TOLERANCE_NS;
  config.count = count;
  enum syncap_trigger_error error = SYNCAP_TRIGGER_OK;
  struct syncap_trigger* trigger = syncap_trigger_new(&config, &error);
  assert_int_equal(error, SYNCAP_TRIGGER_OK);
  assert_non_null(trigger);
  return trigger;
}

static inline struct syncap_trigger* new_started_trigger(double rate_hz, uint64_t count,
                                                         int64_t start_ns) {
  struct syncap_trigger* trigger = new_trigger(rate_hz, count);
  assert_int_equal(syncap_trigger_start(trigger, start_ns), SYNCAP_TRIGGER_OK);
  return trigger;
}

// Drives the pulse due at now_ns with its edge exactly at now_ns; returns it.
static inline struct syncap_trigger_pulse drive_at(struct syncap_trigger* trigger, int64_t now_ns) {
  struct syncap_trigger_pulse pulse;
  assert_int_equal(syncap_trigger_due_pulse(trigger, now_ns, &pulse), SYNCAP_TRIGGER_OK);
  assert_int_equal(syncap_trigger_edge_driven(trigger, &pulse, now_ns), SYNCAP_TRIGGER_OK);
  return pulse;
}

// Drives the next pulse exactly on time; returns it.
static inline struct syncap_trigger_pulse drive_next_on_time(struct syncap_trigger* trigger) {
  return drive_at(trigger, syncap_trigger_next_rise_ns(trigger));
}
