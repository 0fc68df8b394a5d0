// Trigger configuration and its validation. Pure C, no I/O.
#pragma once

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SYNCAP_TRIGGER_MIN_RATE_HZ 0.01
#define SYNCAP_TRIGGER_MAX_RATE_HZ 1000.0
#define SYNCAP_TRIGGER_MAX_LINES 32
// Value of syncap_trigger_config.count for a run that lasts until it is stopped.
#define SYNCAP_TRIGGER_FOREVER 0

// Every error the trigger core reports; each config violation has its own code.
enum syncap_trigger_error {
  SYNCAP_TRIGGER_OK = 0,
  SYNCAP_TRIGGER_ERR_RATE_NOT_FINITE,
  SYNCAP_TRIGGER_ERR_RATE_TOO_LOW,
  SYNCAP_TRIGGER_ERR_RATE_TOO_HIGH,
  SYNCAP_TRIGGER_ERR_WIDTH_NOT_POSITIVE,
  SYNCAP_TRIGGER_ERR_WIDTH_NOT_BELOW_PERIOD,
  SYNCAP_TRIGGER_ERR_TOLERANCE_NEGATIVE,
  SYNCAP_TRIGGER_ERR_NO_LINES,
  SYNCAP_TRIGGER_ERR_TOO_MANY_LINES,
  SYNCAP_TRIGGER_ERR_PHASE_NEGATIVE,
  SYNCAP_TRIGGER_ERR_PHASE_NOT_BELOW_PERIOD,
  SYNCAP_TRIGGER_ERR_PHASE_PLUS_WIDTH_BEYOND_PERIOD,
  SYNCAP_TRIGGER_ERR_DEBOUNCE_NEGATIVE,
  SYNCAP_TRIGGER_ERR_ALREADY_RUNNING,
  SYNCAP_TRIGGER_ERR_NOT_RUNNING,
  SYNCAP_TRIGGER_ERR_NO_MEMORY,
};

struct syncap_trigger_config {
  // Pulses per second, SYNCAP_TRIGGER_MIN_RATE_HZ..SYNCAP_TRIGGER_MAX_RATE_HZ. The schedule holds
  // it as a whole number of micro-hertz, so that it is an exact fraction on every architecture.
  double rate_hz;
  // High time of a pulse: > 0 and shorter than the shortest interval between two pulses.
  int64_t pulse_width_ns;
  // A rising edge driven more than this after its scheduled time is LATE; >= 0.
  int64_t late_tolerance_ns;
  // Pulses per run, or SYNCAP_TRIGGER_FOREVER.
  uint64_t count;
  // Output lines, 1..SYNCAP_TRIGGER_MAX_LINES, each with a delay of its edges after the pulse's
  // scheduled time: 0 <= phase < period, and phase + width <= period, so that every line has
  // fallen before the next pulse's first rising edge.
  size_t num_lines;
  int64_t phase_ns[SYNCAP_TRIGGER_MAX_LINES];
  // Start/stop input edges closer than this to the previous edge of the same input are bounces
  // and ignored; >= 0.
  int64_t debounce_ns;
};

// Fills in the defaults: 30 Hz, 1 ms pulses, 100 us tolerance, forever, one line at phase 0,
// 5 ms debounce.
void syncap_trigger_config_init(struct syncap_trigger_config* config);

// SYNCAP_TRIGGER_OK, or the first violation found (rate, then width, tolerance, lines, phases,
// debounce).
enum syncap_trigger_error syncap_trigger_config_validate(
    const struct syncap_trigger_config* config);

// The shortest interval between two rising edges at rate_hz, in ns (the period rounded down).
int64_t syncap_trigger_min_period_ns(double rate_hz);

// A static English sentence describing the error; never NULL.
const char* syncap_trigger_strerror(enum syncap_trigger_error error);

#ifdef __cplusplus
}
#endif
