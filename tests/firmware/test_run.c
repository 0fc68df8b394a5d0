// The run state machine: idle -> running -> stopped, count runs and their last pulse.
#include "cmocka_main.h"

#include "syncap/trigger/trigger.h"
#include "trigger_fixture.h"

static void new_trigger_is_idle(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_trigger(100.0, 0);
  assert_int_equal(syncap_trigger_state(trigger), SYNCAP_TRIGGER_IDLE);
  struct syncap_trigger_pulse pulse;
  assert_int_equal(syncap_trigger_due_pulse(trigger, 0, &pulse), SYNCAP_TRIGGER_ERR_NOT_RUNNING);
  syncap_trigger_free(trigger);
}

static void count_run_flags_only_its_last_pulse(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(100.0, 3, 0);
  for (uint64_t k = 0; k < 3; ++k) {
    assert_int_equal(syncap_trigger_state(trigger), SYNCAP_TRIGGER_RUNNING);
    const struct syncap_trigger_pulse pulse = drive_next_on_time(trigger);
    assert_int_equal(pulse.index, k);
    assert_int_equal(pulse.flags, k == 2 ? SYNCAP_TRIGGER_FLAG_LAST : 0);
  }
  assert_int_equal(syncap_trigger_state(trigger), SYNCAP_TRIGGER_STOPPED);
  struct syncap_trigger_pulse pulse;
  assert_int_equal(syncap_trigger_due_pulse(trigger, syncap_trigger_rise_ns(trigger, 3), &pulse),
                   SYNCAP_TRIGGER_ERR_NOT_RUNNING);
  struct syncap_trigger_stats stats;
  syncap_trigger_get_stats(trigger, &stats);
  assert_int_equal(stats.pulses, 3);
  syncap_trigger_free(trigger);
}

static void count_of_one_is_first_and_last(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(100.0, 1, 0);
  const struct syncap_trigger_pulse pulse = drive_next_on_time(trigger);
  assert_int_equal(pulse.index, 0);
  assert_int_equal(pulse.flags, SYNCAP_TRIGGER_FLAG_LAST);
  assert_int_equal(syncap_trigger_state(trigger), SYNCAP_TRIGGER_STOPPED);
  syncap_trigger_free(trigger);
}

// A count run woken long after its end still drives (and flags) its last pulse.
static void count_run_never_skips_its_last_pulse(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(100.0, 5, 0);
  const struct syncap_trigger_pulse pulse = drive_at(trigger, syncap_trigger_rise_ns(trigger, 10));
  assert_int_equal(pulse.index, 4);
  assert_int_equal(pulse.missed, 4);
  assert_int_equal(pulse.flags & (SYNCAP_TRIGGER_FLAG_LAST | SYNCAP_TRIGGER_FLAG_MISSED),
                   SYNCAP_TRIGGER_FLAG_LAST | SYNCAP_TRIGGER_FLAG_MISSED);
  assert_int_equal(syncap_trigger_state(trigger), SYNCAP_TRIGGER_STOPPED);
  syncap_trigger_free(trigger);
}

static void forever_run_never_flags_last(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(1000.0, SYNCAP_TRIGGER_FOREVER, 0);
  for (uint64_t k = 0; k < 10000; ++k) {
    assert_int_equal(drive_next_on_time(trigger).flags, 0);
  }
  assert_int_equal(syncap_trigger_state(trigger), SYNCAP_TRIGGER_RUNNING);
  syncap_trigger_free(trigger);
}

static void stop_before_start_is_refused(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_trigger(100.0, 0);
  assert_int_equal(syncap_trigger_stop(trigger), SYNCAP_TRIGGER_ERR_NOT_RUNNING);
  assert_int_equal(syncap_trigger_state(trigger), SYNCAP_TRIGGER_IDLE);
  syncap_trigger_free(trigger);
}

static void double_start_is_refused_and_keeps_the_run(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(100.0, 0, 1000);
  drive_next_on_time(trigger);
  assert_int_equal(syncap_trigger_start(trigger, 999999), SYNCAP_TRIGGER_ERR_ALREADY_RUNNING);
  assert_int_equal(syncap_trigger_rise_ns(trigger, 0), 1000);
  assert_int_equal(drive_next_on_time(trigger).index, 1);
  syncap_trigger_free(trigger);
}

static void stop_ends_the_run(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(100.0, 0, 0);
  struct syncap_trigger_pulse pulse;
  assert_int_equal(syncap_trigger_due_pulse(trigger, 0, &pulse), SYNCAP_TRIGGER_OK);
  assert_int_equal(syncap_trigger_stop(trigger), SYNCAP_TRIGGER_OK);
  assert_int_equal(syncap_trigger_state(trigger), SYNCAP_TRIGGER_STOPPED);
  assert_int_equal(syncap_trigger_edge_driven(trigger, &pulse, 0), SYNCAP_TRIGGER_ERR_NOT_RUNNING);
  assert_int_equal(syncap_trigger_due_pulse(trigger, 0, &pulse), SYNCAP_TRIGGER_ERR_NOT_RUNNING);
  assert_int_equal(syncap_trigger_stop(trigger), SYNCAP_TRIGGER_ERR_NOT_RUNNING);
  syncap_trigger_free(trigger);
}

static void restart_after_stop_begins_at_frame_zero(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(100.0, 0, 0);
  drive_next_on_time(trigger);
  drive_next_on_time(trigger);
  assert_int_equal(syncap_trigger_stop(trigger), SYNCAP_TRIGGER_OK);
  assert_int_equal(syncap_trigger_start(trigger, 7000000000), SYNCAP_TRIGGER_OK);
  assert_int_equal(syncap_trigger_next_rise_ns(trigger), 7000000000);
  assert_int_equal(drive_next_on_time(trigger).index, 0);
  struct syncap_trigger_stats stats;
  syncap_trigger_get_stats(trigger, &stats);
  assert_int_equal(stats.pulses, 1);
  syncap_trigger_free(trigger);
}

// A started trigger at 100 Hz (t_k = k * 10 ms), 1 ms pulses, lines with the given phases in ns.
static struct syncap_trigger* new_phased_trigger(const int64_t* phases, size_t num_lines) {
  struct syncap_trigger_config config;
  syncap_trigger_config_init(&config);
  config.rate_hz = 100.0;
  config.pulse_width_ns = 1000000;
  config.num_lines = num_lines;
  for (size_t i = 0; i < num_lines; ++i) config.phase_ns[i] = phases[i];
  enum syncap_trigger_error error = SYNCAP_TRIGGER_OK;
  struct syncap_trigger* trigger = syncap_trigger_new(&config, &error);
  assert_int_equal(error, SYNCAP_TRIGGER_OK);
  assert_non_null(trigger);
  assert_int_equal(syncap_trigger_start(trigger, 0), SYNCAP_TRIGGER_OK);
  return trigger;
}

static void assert_event(const struct syncap_trigger_event* event, int64_t time_ns, uint32_t lines,
                         int level) {
  assert_int_equal(event->time_ns, time_ns);
  assert_int_equal(event->lines, lines);
  assert_int_equal(event->level, level);
}

// All lines at phase 0: one bulk rise and one bulk fall, as before phases.
static void equal_phases_merge_into_one_set(void** state) {
  (void)state;
  const int64_t phases[] = {0, 0, 0};
  struct syncap_trigger* trigger = new_phased_trigger(phases, 3);
  struct syncap_trigger_event events[SYNCAP_TRIGGER_MAX_EVENTS];
  assert_int_equal(syncap_trigger_pulse_events(trigger, 2, events), 2);
  assert_event(&events[0], 20000000, 0x7, 1);
  assert_event(&events[1], 21000000, 0x7, 0);
  syncap_trigger_free(trigger);
}

// Line 1 rises while line 0 is still high (overlap); lines 0 and 2 share a phase; line 3 rises
// exactly when line 0 falls, so the fall comes first. Listed out of order on purpose.
static void overlapping_phases_are_ordered_by_time(void** state) {
  (void)state;
  const int64_t phases[] = {250000, 750000, 250000, 1250000, 0};
  struct syncap_trigger* trigger = new_phased_trigger(phases, 5);
  struct syncap_trigger_event events[SYNCAP_TRIGGER_MAX_EVENTS];
  assert_int_equal(syncap_trigger_pulse_events(trigger, 1, events), 8);
  const int64_t t = 10000000;
  assert_event(&events[0], t, 0x10, 1);
  assert_event(&events[1], t + 250000, 0x5, 1);
  assert_event(&events[2], t + 750000, 0x2, 1);
  assert_event(&events[3], t + 1000000, 0x10, 0);
  assert_event(&events[4], t + 1250000, 0x5, 0);
  assert_event(&events[5], t + 1250000, 0x8, 1);
  assert_event(&events[6], t + 1750000, 0x2, 0);
  assert_event(&events[7], t + 2250000, 0x8, 0);
  syncap_trigger_free(trigger);
}

// The pulse's first edge is the smallest phase: next_rise and the LATE check follow it.
static void pulse_times_follow_the_smallest_phase(void** state) {
  (void)state;
  const int64_t phases[] = {500000, 300000};
  struct syncap_trigger* trigger = new_phased_trigger(phases, 2);
  assert_int_equal(syncap_trigger_next_rise_ns(trigger), 300000);
  struct syncap_trigger_pulse pulse;
  assert_int_equal(syncap_trigger_due_pulse(trigger, 300000, &pulse), SYNCAP_TRIGGER_OK);
  assert_int_equal(pulse.index, 0);
  assert_int_equal(pulse.rise_ns, 300000);
  assert_int_equal(pulse.fall_ns, 1500000);
  assert_int_equal(syncap_trigger_edge_driven(trigger, &pulse, 350000), SYNCAP_TRIGGER_OK);
  assert_int_equal(pulse.flags & SYNCAP_TRIGGER_FLAG_LATE, 0);
  assert_int_equal(syncap_trigger_next_rise_ns(trigger), 10300000);
  // Woken just before pulse 2's first edge: pulse 1, not a skip.
  assert_int_equal(syncap_trigger_due_pulse(trigger, 20299999, &pulse), SYNCAP_TRIGGER_OK);
  assert_int_equal(pulse.index, 1);
  assert_int_equal(pulse.missed, 0);
  syncap_trigger_free(trigger);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(new_trigger_is_idle),
    cmocka_unit_test(count_run_flags_only_its_last_pulse),
    cmocka_unit_test(count_of_one_is_first_and_last),
    cmocka_unit_test(count_run_never_skips_its_last_pulse),
    cmocka_unit_test(forever_run_never_flags_last),
    cmocka_unit_test(stop_before_start_is_refused),
    cmocka_unit_test(double_start_is_refused_and_keeps_the_run),
    cmocka_unit_test(stop_ends_the_run),
    cmocka_unit_test(restart_after_stop_begins_at_frame_zero),
    cmocka_unit_test(equal_phases_merge_into_one_set),
    cmocka_unit_test(overlapping_phases_are_ordered_by_time),
    cmocka_unit_test(pulse_times_follow_the_smallest_phase),
};

SYNCAP_CMOCKA_MAIN(tests)
