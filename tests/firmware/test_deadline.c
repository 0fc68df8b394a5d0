// Deadline accounting: on time, late beyond the tolerance, whole missed periods skipped.
#include "cmocka_main.h"

#include "syncap/trigger/trigger.h"
#include "trigger_fixture.h"

#define PERIOD_NS 10000000  // 100 Hz
#define START_NS 1000000000

static struct syncap_trigger_stats stats_of(const struct syncap_trigger* trigger) {
  struct syncap_trigger_stats stats;
  syncap_trigger_get_stats(trigger, &stats);
  return stats;
}

static struct syncap_trigger_pulse due_at(const struct syncap_trigger* trigger, int64_t now_ns) {
  struct syncap_trigger_pulse pulse;
  assert_int_equal(syncap_trigger_due_pulse(trigger, now_ns, &pulse), SYNCAP_TRIGGER_OK);
  return pulse;
}

static void edge_within_tolerance_is_on_time(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(100.0, 0, START_NS);
  struct syncap_trigger_pulse pulse = due_at(trigger, START_NS);
  syncap_trigger_edge_driven(trigger, &pulse, START_NS + FIXTURE_TOLERANCE_NS);
  assert_int_equal(pulse.flags, 0);
  assert_int_equal(stats_of(trigger).late, 0);
  syncap_trigger_free(trigger);
}

static void edge_beyond_tolerance_is_late(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(100.0, 0, START_NS);
  struct syncap_trigger_pulse pulse = due_at(trigger, START_NS);
  syncap_trigger_edge_driven(trigger, &pulse, START_NS + FIXTURE_TOLERANCE_NS + 1);
  assert_int_equal(pulse.flags, SYNCAP_TRIGGER_FLAG_LATE);
  assert_int_equal(stats_of(trigger).late, 1);
  assert_int_equal(stats_of(trigger).pulses, 1);
  syncap_trigger_free(trigger);
}

static void early_wake_gets_the_next_pulse(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(100.0, 0, START_NS);
  const struct syncap_trigger_pulse pulse = due_at(trigger, START_NS - 5 * PERIOD_NS);
  assert_int_equal(pulse.index, 0);
  assert_int_equal(pulse.missed, 0);
  assert_int_equal(pulse.rise_ns, START_NS);
  assert_int_equal(pulse.fall_ns, START_NS + FIXTURE_WIDTH_NS);
  syncap_trigger_free(trigger);
}

// Less than a whole period late: the pulse is driven late, nothing is skipped.
static void wake_just_before_the_successor_is_late_not_missed(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(100.0, 0, START_NS);
  const struct syncap_trigger_pulse pulse = drive_at(trigger, START_NS + PERIOD_NS - 1);
  assert_int_equal(pulse.index, 0);
  assert_int_equal(pulse.flags, SYNCAP_TRIGGER_FLAG_LATE);
  syncap_trigger_free(trigger);
}

static void wake_at_the_successor_skips_one(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(100.0, 0, START_NS);
  const struct syncap_trigger_pulse pulse = drive_at(trigger, START_NS + PERIOD_NS);
  assert_int_equal(pulse.index, 1);
  assert_int_equal(pulse.missed, 1);
  assert_int_equal(pulse.flags, SYNCAP_TRIGGER_FLAG_MISSED);
  syncap_trigger_free(trigger);
}

// Frame numbers stay pulse indices: after skipping 1, 2 and 3 the next frame is 4, then 5.
static void missed_periods_are_skipped_and_counted(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(100.0, 0, START_NS);
  drive_next_on_time(trigger);
  const struct syncap_trigger_pulse late = drive_at(trigger, START_NS + 4 * PERIOD_NS + 50000);
  assert_int_equal(late.index, 4);
  assert_int_equal(late.missed, 3);
  assert_int_equal(late.flags, SYNCAP_TRIGGER_FLAG_MISSED);
  const struct syncap_trigger_pulse next = drive_next_on_time(trigger);
  assert_int_equal(next.index, 5);
  assert_int_equal(next.flags, 0);
  const struct syncap_trigger_stats stats = stats_of(trigger);
  assert_int_equal(stats.pulses, 3);
  assert_int_equal(stats.missed, 3);
  assert_int_equal(stats.late, 0);
  syncap_trigger_free(trigger);
}

static void due_pulse_changes_nothing(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_started_trigger(100.0, 0, START_NS);
  const struct syncap_trigger_pulse first = due_at(trigger, START_NS + 3 * PERIOD_NS);
  const struct syncap_trigger_pulse again = due_at(trigger, START_NS + 3 * PERIOD_NS);
  assert_int_equal(first.index, again.index);
  assert_int_equal(first.missed, again.missed);
  assert_int_equal(first.flags, again.flags);
  assert_int_equal(syncap_trigger_next_rise_ns(trigger), START_NS);
  assert_int_equal(stats_of(trigger).missed, 0);
  syncap_trigger_free(trigger);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(edge_within_tolerance_is_on_time),
    cmocka_unit_test(edge_beyond_tolerance_is_late),
    cmocka_unit_test(early_wake_gets_the_next_pulse),
    cmocka_unit_test(wake_just_before_the_successor_is_late_not_missed),
    cmocka_unit_test(wake_at_the_successor_skips_one),
    cmocka_unit_test(missed_periods_are_skipped_and_counted),
    cmocka_unit_test(due_pulse_changes_nothing),
};

SYNCAP_CMOCKA_MAIN(tests)
