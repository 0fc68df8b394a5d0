#include <math.h>

#include "schedule.h"
#include "syncap/trigger/config.h"

void syncap_trigger_config_init(struct syncap_trigger_config* config) {
  *config = (struct syncap_trigger_config){
      .rate_hz = 30.0,
      .pulse_width_ns = 1000000,
      .late_tolerance_ns = 100000,
      .count = SYNCAP_TRIGGER_FOREVER,
      .num_lines = 1,
      .debounce_ns = 5000000,
  };
}

int64_t syncap_trigger_min_period_ns(double rate_hz) {
  return syncap_schedule_offset_ns(syncap_schedule_rate_uhz(rate_hz), 1);
}

static enum syncap_trigger_error validate_rate(double rate_hz) {
  if (!isfinite(rate_hz)) return SYNCAP_TRIGGER_ERR_RATE_NOT_FINITE;
  if (rate_hz < SYNCAP_TRIGGER_MIN_RATE_HZ) return SYNCAP_TRIGGER_ERR_RATE_TOO_LOW;
  if (rate_hz > SYNCAP_TRIGGER_MAX_RATE_HZ) return SYNCAP_TRIGGER_ERR_RATE_TOO_HIGH;
  return SYNCAP_TRIGGER_OK;
}

// Checked against the shortest interval between pulses: the falling edge must come before the
// next rising edge even where the schedule's rounding makes an interval 1 ns short.
static enum syncap_trigger_error validate_width(int64_t width_ns, int64_t min_period_ns) {
  if (width_ns <= 0) return SYNCAP_TRIGGER_ERR_WIDTH_NOT_POSITIVE;
  if (width_ns >= min_period_ns) return SYNCAP_TRIGGER_ERR_WIDTH_NOT_BELOW_PERIOD;
  return SYNCAP_TRIGGER_OK;
}

static enum syncap_trigger_error validate_lines(const struct syncap_trigger_config* config,
                                                int64_t min_period_ns) {
  if (config->num_lines == 0) return SYNCAP_TRIGGER_ERR_NO_LINES;
  if (config->num_lines > SYNCAP_TRIGGER_MAX_LINES) return SYNCAP_TRIGGER_ERR_TOO_MANY_LINES;
  for (size_t i = 0; i < config->num_lines; ++i) {
    if (config->phase_ns[i] < 0) return SYNCAP_TRIGGER_ERR_PHASE_NEGATIVE;
    if (config->phase_ns[i] >= min_period_ns) return SYNCAP_TRIGGER_ERR_PHASE_NOT_BELOW_PERIOD;
    if (config->phase_ns[i] > min_period_ns - config->pulse_width_ns) {
      return SYNCAP_TRIGGER_ERR_PHASE_PLUS_WIDTH_BEYOND_PERIOD;
    }
  }
  return SYNCAP_TRIGGER_OK;
}

enum syncap_trigger_error syncap_trigger_config_validate(
    const struct syncap_trigger_config* config) {
  enum syncap_trigger_error error = validate_rate(config->rate_hz);
  if (error != SYNCAP_TRIGGER_OK) return error;
  const int64_t min_period_ns = syncap_trigger_min_period_ns(config->rate_hz);
  error = validate_width(config->pulse_width_ns, min_period_ns);
  if (error != SYNCAP_TRIGGER_OK) return error;
  if (config->late_tolerance_ns < 0) return SYNCAP_TRIGGER_ERR_TOLERANCE_NEGATIVE;
  error = validate_lines(config, min_period_ns);
  if (error != SYNCAP_TRIGGER_OK) return error;
  if (config->debounce_ns < 0) return SYNCAP_TRIGGER_ERR_DEBOUNCE_NEGATIVE;
  return SYNCAP_TRIGGER_OK;
}

const char* syncap_trigger_strerror(enum syncap_trigger_error error) {
  switch (error) {
    case SYNCAP_TRIGGER_OK:
      return "success";
    case SYNCAP_TRIGGER_ERR_RATE_NOT_FINITE:
      return "rate is not a finite number";
    case SYNCAP_TRIGGER_ERR_RATE_TOO_LOW:
      return "rate is below 0.01 Hz";
    case SYNCAP_TRIGGER_ERR_RATE_TOO_HIGH:
      return "rate is above 1000 Hz";
    case SYNCAP_TRIGGER_ERR_WIDTH_NOT_POSITIVE:
      return "pulse width must be greater than 0";
    case SYNCAP_TRIGGER_ERR_WIDTH_NOT_BELOW_PERIOD:
      return "pulse width must be shorter than the period";
    case SYNCAP_TRIGGER_ERR_TOLERANCE_NEGATIVE:
      return "late tolerance must not be negative";
    case SYNCAP_TRIGGER_ERR_NO_LINES:
      return "at least one output line is needed";
    case SYNCAP_TRIGGER_ERR_TOO_MANY_LINES:
      return "too many output lines (at most 32)";
    case SYNCAP_TRIGGER_ERR_PHASE_NEGATIVE:
      return "line phase offset must not be negative";
    case SYNCAP_TRIGGER_ERR_PHASE_NOT_BELOW_PERIOD:
      return "line phase offset must be shorter than the period";
    case SYNCAP_TRIGGER_ERR_PHASE_PLUS_WIDTH_BEYOND_PERIOD:
      return "line phase offset plus pulse width must not exceed the period";
    case SYNCAP_TRIGGER_ERR_DEBOUNCE_NEGATIVE:
      return "debounce time must not be negative";
    case SYNCAP_TRIGGER_ERR_ALREADY_RUNNING:
      return "the trigger is already running";
    case SYNCAP_TRIGGER_ERR_NOT_RUNNING:
      return "the trigger is not running";
    case SYNCAP_TRIGGER_ERR_NO_MEMORY:
      return "out of memory";
  }
  return "unknown trigger error";
}
