// Start/stop input edges in the trigger core: debounce per input, and edges that the run state
// does not allow (stop before start, start while running) are ignored.
#include "cmocka_main.h"

#include "syncap/trigger/trigger.h"
#include "trigger_fixture.h"

#define MS INT64_C(1000000)
#define DEBOUNCE_NS (5 * MS)

static struct syncap_trigger* new_debounced_trigger(void) {
  struct syncap_trigger_config config;
  syncap_trigger_config_init(&config);
  assert_int_equal(config.debounce_ns, DEBOUNCE_NS);  // the default
  config.rate_hz = 100.0;
  enum syncap_trigger_error error = SYNCAP_TRIGGER_OK;
  struct syncap_trigger* trigger = syncap_trigger_new(&config, &error);
  assert_non_null(trigger);
  return trigger;
}

static enum syncap_trigger_input_action start_at(struct syncap_trigger* trigger, int64_t t) {
  return syncap_trigger_input_edge(trigger, SYNCAP_TRIGGER_INPUT_START, t, t + 10 * MS);
}

static enum syncap_trigger_input_action stop_at(struct syncap_trigger* trigger, int64_t t) {
  return syncap_trigger_input_edge(trigger, SYNCAP_TRIGGER_INPUT_STOP, t, 0);
}

static void start_edge_starts_a_run_at_the_given_time(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_debounced_trigger();
  assert_int_equal(start_at(trigger, 1000 * MS), SYNCAP_TRIGGER_INPUT_STARTED);
  assert_int_equal(syncap_trigger_state(trigger), SYNCAP_TRIGGER_RUNNING);
  assert_int_equal(syncap_trigger_next_rise_ns(trigger), 1010 * MS);
  syncap_trigger_free(trigger);
}

// A bouncing switch: edges 0, 0.3, 1, 4.9 ms after the first are one press.
static void bouncing_start_edges_start_once(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_debounced_trigger();
  const int64_t t0 = 1000 * MS;
  assert_int_equal(start_at(trigger, t0), SYNCAP_TRIGGER_INPUT_STARTED);
  const int64_t bounces[] = {t0 + 300000, t0 + MS, t0 + DEBOUNCE_NS - 1};
  for (size_t i = 0; i < 3; ++i) {
    assert_int_equal(start_at(trigger, bounces[i]), SYNCAP_TRIGGER_INPUT_BOUNCE);
  }
  assert_int_equal(syncap_trigger_next_rise_ns(trigger), t0 + 10 * MS);  // the run was kept
  // After the window an edge counts again; while running a start is ignored, not a new run.
  assert_int_equal(start_at(trigger, t0 + DEBOUNCE_NS), SYNCAP_TRIGGER_INPUT_IGNORED);
  syncap_trigger_free(trigger);
}

static void bouncing_stop_edges_stop_once(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_debounced_trigger();
  assert_int_equal(start_at(trigger, 0), SYNCAP_TRIGGER_INPUT_STARTED);
  assert_int_equal(stop_at(trigger, 100 * MS), SYNCAP_TRIGGER_INPUT_STOPPED);
  assert_int_equal(syncap_trigger_state(trigger), SYNCAP_TRIGGER_STOPPED);
  assert_int_equal(stop_at(trigger, 101 * MS), SYNCAP_TRIGGER_INPUT_BOUNCE);
  assert_int_equal(stop_at(trigger, 200 * MS), SYNCAP_TRIGGER_INPUT_IGNORED);
  syncap_trigger_free(trigger);
}

static void stop_before_start_is_ignored_and_start_still_works(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_debounced_trigger();
  assert_int_equal(stop_at(trigger, 0), SYNCAP_TRIGGER_INPUT_IGNORED);
  assert_int_equal(syncap_trigger_state(trigger), SYNCAP_TRIGGER_IDLE);
  // The debounce is per input: a start right after the stop edge counts.
  assert_int_equal(start_at(trigger, MS), SYNCAP_TRIGGER_INPUT_STARTED);
  syncap_trigger_free(trigger);
}

// A bounce never extends the window: a train of edges 1 ms apart gives a new press every 5 ms.
static void bounce_window_runs_from_the_last_counted_edge(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_debounced_trigger();
  unsigned counted = 0;
  for (int64_t t = 0; t < 20 * MS; t += MS) {
    if (stop_at(trigger, t) != SYNCAP_TRIGGER_INPUT_BOUNCE) ++counted;
  }
  assert_int_equal(counted, 4);  // at 0, 5, 10, 15 ms
  syncap_trigger_free(trigger);
}

static void start_stop_start_begins_a_new_run_at_frame_zero(void** state) {
  (void)state;
  struct syncap_trigger* trigger = new_debounced_trigger();
  assert_int_equal(start_at(trigger, 0), SYNCAP_TRIGGER_INPUT_STARTED);
  drive_next_on_time(trigger);
  drive_next_on_time(trigger);
  assert_int_equal(stop_at(trigger, 50 * MS), SYNCAP_TRIGGER_INPUT_STOPPED);
  assert_int_equal(start_at(trigger, 100 * MS), SYNCAP_TRIGGER_INPUT_STARTED);
  assert_int_equal(drive_next_on_time(trigger).index, 0);
  syncap_trigger_free(trigger);
}

static void zero_debounce_counts_every_edge(void** state) {
  (void)state;
  struct syncap_trigger_config config;
  syncap_trigger_config_init(&config);
  config.debounce_ns = 0;
  enum syncap_trigger_error error = SYNCAP_TRIGGER_OK;
  struct syncap_trigger* trigger = syncap_trigger_new(&config, &error);
  assert_non_null(trigger);
  assert_int_equal(start_at(trigger, 0), SYNCAP_TRIGGER_INPUT_STARTED);
  assert_int_equal(stop_at(trigger, 0), SYNCAP_TRIGGER_INPUT_STOPPED);
  assert_int_equal(start_at(trigger, 1), SYNCAP_TRIGGER_INPUT_STARTED);
  syncap_trigger_free(trigger);
}

static void negative_debounce_is_rejected(void** state) {
  (void)state;
  struct syncap_trigger_config config;
  syncap_trigger_config_init(&config);
  config.debounce_ns = -1;
  assert_int_equal(syncap_trigger_config_validate(&config), SYNCAP_TRIGGER_ERR_DEBOUNCE_NEGATIVE);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(start_edge_starts_a_run_at_the_given_time),
    cmocka_unit_test(bouncing_start_edges_start_once),
    cmocka_unit_test(bouncing_stop_edges_stop_once),
    cmocka_unit_test(stop_before_start_is_ignored_and_start_still_works),
    cmocka_unit_test(bounce_window_runs_from_the_last_counted_edge),
    cmocka_unit_test(start_stop_start_begins_a_new_run_at_frame_zero),
    cmocka_unit_test(zero_debounce_counts_every_edge),
    cmocka_unit_test(negative_debounce_is_rejected),
};

SYNCAP_CMOCKA_MAIN(tests)
