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
};

SYNCAP_CMOCKA_MAIN(tests)
