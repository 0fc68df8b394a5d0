// Config validation: the bounds of rate, width, tolerance, lines and phases.
#include "cmocka_main.h"

#include <math.h>

#include "syncap/trigger/config.h"
#include "syncap/trigger/trigger.h"

static struct syncap_trigger_config config_at(double rate_hz) {
  struct syncap_trigger_config config;
  syncap_trigger_config_init(&config);
  config.rate_hz = rate_hz;
  config.pulse_width_ns = 1000;
  return config;
}

static enum syncap_trigger_error validate(struct syncap_trigger_config config) {
  return syncap_trigger_config_validate(&config);
}

static void defaults_are_valid(void** state) {
  (void)state;
  struct syncap_trigger_config config;
  syncap_trigger_config_init(&config);
  assert_int_equal(syncap_trigger_config_validate(&config), SYNCAP_TRIGGER_OK);
}

static void rate_accepts_both_bounds(void** state) {
  (void)state;
  assert_int_equal(validate(config_at(0.01)), SYNCAP_TRIGGER_OK);
  assert_int_equal(validate(config_at(1000.0)), SYNCAP_TRIGGER_OK);
}

static void rate_rejects_below_minimum(void** state) {
  (void)state;
  assert_int_equal(validate(config_at(0.009)), SYNCAP_TRIGGER_ERR_RATE_TOO_LOW);
  assert_int_equal(validate(config_at(0.0)), SYNCAP_TRIGGER_ERR_RATE_TOO_LOW);
  assert_int_equal(validate(config_at(-30.0)), SYNCAP_TRIGGER_ERR_RATE_TOO_LOW);
}

static void rate_rejects_above_maximum(void** state) {
  (void)state;
  assert_int_equal(validate(config_at(1000.1)), SYNCAP_TRIGGER_ERR_RATE_TOO_HIGH);
}

static void rate_rejects_nan_and_infinity(void** state) {
  (void)state;
  assert_int_equal(validate(config_at(NAN)), SYNCAP_TRIGGER_ERR_RATE_NOT_FINITE);
  assert_int_equal(validate(config_at(INFINITY)), SYNCAP_TRIGGER_ERR_RATE_NOT_FINITE);
}

static void width_rejects_zero_and_negative(void** state) {
  (void)state;
  struct syncap_trigger_config config = config_at(30.0);
  config.pulse_width_ns = 0;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_ERR_WIDTH_NOT_POSITIVE);
  config.pulse_width_ns = -1;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_ERR_WIDTH_NOT_POSITIVE);
}

// At 30 Hz the period is 33333333.3 ns; intervals are 33333333 or 33333334 ns.
static void width_must_be_shorter_than_period(void** state) {
  (void)state;
  struct syncap_trigger_config config = config_at(30.0);
  config.pulse_width_ns = 33333332;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_OK);
  config.pulse_width_ns = 33333333;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_ERR_WIDTH_NOT_BELOW_PERIOD);
  config = config_at(1000.0);
  config.pulse_width_ns = 1000000;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_ERR_WIDTH_NOT_BELOW_PERIOD);
}

static void tolerance_rejects_negative(void** state) {
  (void)state;
  struct syncap_trigger_config config = config_at(30.0);
  config.late_tolerance_ns = -1;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_ERR_TOLERANCE_NEGATIVE);
}

static void lines_reject_none_and_too_many(void** state) {
  (void)state;
  struct syncap_trigger_config config = config_at(30.0);
  config.num_lines = 0;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_ERR_NO_LINES);
  config.num_lines = SYNCAP_TRIGGER_MAX_LINES + 1;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_ERR_TOO_MANY_LINES);
  config.num_lines = SYNCAP_TRIGGER_MAX_LINES;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_OK);
}

static void phase_rejects_negative(void** state) {
  (void)state;
  struct syncap_trigger_config config = config_at(30.0);
  config.num_lines = 2;
  config.phase_ns[1] = -1;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_ERR_PHASE_NEGATIVE);
}

static void phase_must_be_shorter_than_period(void** state) {
  (void)state;
  struct syncap_trigger_config config = config_at(100.0);
  config.num_lines = 2;
  config.pulse_width_ns = 1;
  config.phase_ns[1] = 9999999;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_OK);
  config.phase_ns[1] = 10000000;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_ERR_PHASE_NOT_BELOW_PERIOD);
}

// Every line falls before the next pulse's first rise: phase + width <= period.
static void phase_plus_width_must_fit_in_the_period(void** state) {
  (void)state;
  struct syncap_trigger_config config = config_at(100.0);
  config.num_lines = 2;
  config.pulse_width_ns = 1000000;
  config.phase_ns[1] = 9000000;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_OK);
  config.phase_ns[1] = 9000001;
  assert_int_equal(validate(config), SYNCAP_TRIGGER_ERR_PHASE_PLUS_WIDTH_BEYOND_PERIOD);
}

static void every_error_has_its_own_message(void** state) {
  (void)state;
  for (int a = SYNCAP_TRIGGER_OK; a <= SYNCAP_TRIGGER_ERR_NO_MEMORY; ++a) {
    const char* message = syncap_trigger_strerror((enum syncap_trigger_error)a);
    assert_non_null(message);
    for (int b = SYNCAP_TRIGGER_OK; b < a; ++b) {
      assert_string_not_equal(message, syncap_trigger_strerror((enum syncap_trigger_error)b));
    }
  }
}

static void new_refuses_an_invalid_config(void** state) {
  (void)state;
  const struct syncap_trigger_config config = config_at(1000.1);
  enum syncap_trigger_error error = SYNCAP_TRIGGER_OK;
  assert_null(syncap_trigger_new(&config, &error));
  assert_int_equal(error, SYNCAP_TRIGGER_ERR_RATE_TOO_HIGH);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(defaults_are_valid),
    cmocka_unit_test(rate_accepts_both_bounds),
    cmocka_unit_test(rate_rejects_below_minimum),
    cmocka_unit_test(rate_rejects_above_maximum),
    cmocka_unit_test(rate_rejects_nan_and_infinity),
    cmocka_unit_test(width_rejects_zero_and_negative),
    cmocka_unit_test(width_must_be_shorter_than_period),
    cmocka_unit_test(tolerance_rejects_negative),
    cmocka_unit_test(lines_reject_none_and_too_many),
    cmocka_unit_test(phase_rejects_negative),
    cmocka_unit_test(phase_must_be_shorter_than_period),
    cmocka_unit_test(phase_plus_width_must_fit_in_the_period),
    cmocka_unit_test(every_error_has_its_own_message),
    cmocka_unit_test(new_refuses_an_invalid_config),
};

SYNCAP_CMOCKA_MAIN(tests)
