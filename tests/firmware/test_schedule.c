// The pulse schedule: exact edge times from the start, no drift, a 64-bit frame counter.
#include "cmocka_main.h"

#include "syncap/trigger/trigger.h"
#include "trigger_fixture.h"

#define START_NS INT64_C(5000000000)
#define K_PAST_2_POW_32 ((UINT64_C(1) << 32) + 5)

static void first_pulse_rises_at_start(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(30.0, 0, START_NS);
  assert_int_equal(syncap_trigger_rise_ns(trigger, 0), START_NS);
  assert_int_equal(syncap_trigger_fall_ns(trigger, 0), START_NS + FIXTURE_WIDTH_NS);
  assert_int_equal(syncap_trigger_next_rise_ns(trigger), START_NS);
  syncap_trigger_free(trigger);
}

// t_k = start + floor(k * 1e9 / 30): 33333333, 66666666, then exactly 1e8 at k = 3.
static void edges_round_down_without_accumulating(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(30.0, 0, START_NS);
  assert_int_equal(syncap_trigger_rise_ns(trigger, 1), START_NS + 33333333);
  assert_int_equal(syncap_trigger_fall_ns(trigger, 1), START_NS + 33333333 + FIXTURE_WIDTH_NS);
  assert_int_equal(syncap_trigger_rise_ns(trigger, 2), START_NS + 66666666);
  assert_int_equal(syncap_trigger_rise_ns(trigger, 3), START_NS + 100000000);
  syncap_trigger_free(trigger);
}

// 2^32 + 5 is a multiple of 3, so at 30 Hz its edge is exactly (2^32 + 5) / 3 * 1e8 ns; adding up
// a rounded period instead would be off by more than a second.
static void no_drift_past_2_pow_32(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(30.0, 0, START_NS);
  const int64_t expected = (int64_t)(K_PAST_2_POW_32 / 3) * 100000000;
  assert_int_equal(syncap_trigger_rise_ns(trigger, K_PAST_2_POW_32), START_NS + expected);
  assert_int_equal(syncap_trigger_rise_ns(trigger, K_PAST_2_POW_32 + 1),
                   START_NS + expected + 33333333);
  syncap_trigger_free(trigger);
}

// 29.97 Hz has no exact binary period; expected values are floor(k * 1e15 / 29970000) from
// arbitrary-precision arithmetic.
static void no_drift_at_a_fractional_rate(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(29.97, 0, 0);
  assert_int_equal(syncap_trigger_rise_ns(trigger, K_PAST_2_POW_32), INT64_C(143308885585585585));
  assert_int_equal(syncap_trigger_rise_ns(trigger, K_PAST_2_POW_32 + 1),
                   INT64_C(143308885618952285));
  syncap_trigger_free(trigger);
}

static void slowest_and_fastest_rates_are_exact(void** state) {
  (void)state;
  struct syncap_trigger* slow = new_started_trigger(0.01, 0, 0);
  assert_int_equal(syncap_trigger_rise_ns(slow, 1), INT64_C(100000000000));
  struct syncap_trigger* fast = new_started_trigger(1000.0, 0, 0);
  assert_int_equal(syncap_trigger_rise_ns(fast, K_PAST_2_POW_32),
                   (int64_t)K_PAST_2_POW_32 * 1000000);
  syncap_trigger_free(slow);
  syncap_trigger_free(fast);
}

// Rounding down each edge makes intervals floor(period) or ceil(period), never anything else.
static void intervals_are_floor_or_ceil_of_period(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(30.0, 0, 0);
  for (uint64_t k = 0; k < 10000; ++k) {
    const int64_t interval =
        syncap_trigger_rise_ns(trigger, k + 1) - syncap_trigger_rise_ns(trigger, k);
    assert_in_range(interval, 33333333, 33333334);
  }
  syncap_trigger_free(trigger);
}

// Reaching pulse 2^32 + 5 by waking up there: the frame counter and missed count are 64-bit.
static void frame_counter_passes_2_pow_32(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(1000.0, 0, START_NS);
  const struct syncap_trigger_pulse pulse =
      drive_at(trigger, syncap_trigger_rise_ns(trigger, K_PAST_2_POW_32));
  assert_true(pulse.index == K_PAST_2_POW_32);
  assert_true(pulse.missed == K_PAST_2_POW_32);
  assert_int_equal(syncap_trigger_next_rise_ns(trigger),
                   syncap_trigger_rise_ns(trigger, K_PAST_2_POW_32 + 1));
  assert_true(drive_next_on_time(trigger).index == K_PAST_2_POW_32 + 1);
  struct syncap_trigger_stats stats;
  syncap_trigger_get_stats(trigger, &stats);
  assert_true(stats.missed == K_PAST_2_POW_32);
  assert_int_equal(stats.pulses, 2);
  syncap_trigger_free(trigger);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(first_pulse_rises_at_start),
    cmocka_unit_test(edges_round_down_without_accumulating),
    cmocka_unit_test(no_drift_past_2_pow_32),
    cmocka_unit_test(no_drift_at_a_fractional_rate),
    cmocka_unit_test(slowest_and_fastest_rates_are_exact),
    cmocka_unit_test(intervals_are_floor_or_ceil_of_period),
    cmocka_unit_test(frame_counter_passes_2_pow_32),
};

SYNCAP_CMOCKA_MAIN(tests)
