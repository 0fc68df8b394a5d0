// One trigger output: its pulse schedule, run state and deadline accounting. Pure C, no I/O; the
// only allocation is syncap_trigger_new. All times are CLOCK_MONOTONIC nanoseconds.
//
// A run: syncap_trigger_start, then per pulse
//   sleep until syncap_trigger_next_rise_ns();
//   syncap_trigger_due_pulse(now)        -> which pulse to drive (skips whole missed periods);
//   syncap_trigger_pulse_events(index)   -> its edges per line, in time order;
//   drive the first (rising) one, then syncap_trigger_edge_driven(edge time) -> LATE or not,
//   advance; then sleep to and drive each further event of the pulse;
// until the state leaves RUNNING (count reached) or syncap_trigger_stop.
#pragma once

#include <stdint.h>

#include "syncap/trigger/config.h"

#ifdef __cplusplus
extern "C" {
#endif

// Pulse flags; the same bits as syncap_trigger_t.flags (proto/msg/trigger_t.lcm).
#define SYNCAP_TRIGGER_FLAG_LATE 0x1u
#define SYNCAP_TRIGGER_FLAG_MISSED 0x2u
#define SYNCAP_TRIGGER_FLAG_LAST 0x4u

// idle --start--> running --stop or last pulse--> stopped --start--> running (a new run)
enum syncap_trigger_state {
  SYNCAP_TRIGGER_IDLE,
  SYNCAP_TRIGGER_RUNNING,
  SYNCAP_TRIGGER_STOPPED,
};

struct syncap_trigger;

// Each line rises phase_ns after the pulse's scheduled time t_k and falls pulse_width_ns later.
#define SYNCAP_TRIGGER_MAX_EVENTS (2 * SYNCAP_TRIGGER_MAX_LINES)

// One edge of a pulse: the lines (bit i: config line i) that switch to level at time_ns together
// (lines with equal phases share one event, i.e. one bulk set).
struct syncap_trigger_event {
  int64_t time_ns;  // scheduled, CLOCK_MONOTONIC
  uint32_t lines;
  int level;  // 1 rising, 0 falling
};

struct syncap_trigger_pulse {
  uint64_t index;   // position in the schedule, 0 for the first pulse: the frame number
  int64_t rise_ns;  // scheduled first rising edge: t_k + the smallest phase
  int64_t fall_ns;  // scheduled last falling edge: t_k + the largest phase + width
  uint64_t missed;  // pulses skipped right before this one
  unsigned flags;   // SYNCAP_TRIGGER_FLAG_*
};

// Counts of the current (or last) run.
struct syncap_trigger_stats {
  uint64_t pulses;  // rising edges driven
  uint64_t late;    // of those, driven beyond the tolerance
  uint64_t missed;  // pulses skipped because their time had passed
};

// A trigger in state IDLE, or NULL with *error set (config violation or no memory).
struct syncap_trigger* syncap_trigger_new(const struct syncap_trigger_config* config,
                                          enum syncap_trigger_error* error);
void syncap_trigger_free(struct syncap_trigger* trigger);

// Starts a run whose pulse 0 rises at start_ns; resets frame numbers and stats.
// SYNCAP_TRIGGER_ERR_ALREADY_RUNNING while a run is on.
enum syncap_trigger_error syncap_trigger_start(struct syncap_trigger* trigger, int64_t start_ns);
// Ends the run. SYNCAP_TRIGGER_ERR_NOT_RUNNING when there is none.
enum syncap_trigger_error syncap_trigger_stop(struct syncap_trigger* trigger);
enum syncap_trigger_state syncap_trigger_state(const struct syncap_trigger* trigger);

// Scheduled time t_k of pulse `index` of the current run (start time 0 before the first run):
// start + floor(index * 1e9 / rate) exactly, without accumulated rounding, for any index whose
// time fits in int64_t (about 292 years). A line with phase p rises at t_k + p.
int64_t syncap_trigger_rise_ns(const struct syncap_trigger* trigger, uint64_t index);
// t_k + width: the falling edge of the lines at phase 0.
int64_t syncap_trigger_fall_ns(const struct syncap_trigger* trigger, uint64_t index);
// First rising edge (t + smallest phase) of the next pulse not yet driven.
int64_t syncap_trigger_next_rise_ns(const struct syncap_trigger* trigger);

// The edge events of pulse `index` in time order (at equal times falling before rising), lines
// with equal phases merged into one event; returns how many (2 to SYNCAP_TRIGGER_MAX_EVENTS). The
// first is always the rising edge of the lines with the smallest phase; all of them lie within
// [t_k, t_k+1], since phase + width <= period.
size_t syncap_trigger_pulse_events(const struct syncap_trigger* trigger, uint64_t index,
                                   struct syncap_trigger_event events[SYNCAP_TRIGGER_MAX_EVENTS]);

// The pulse to drive when the daemon is awake at now_ns: the next pulse, or, when the next
// pulse's successor is already due, the latest due pulse, with the skipped ones counted in
// `missed` and SYNCAP_TRIGGER_FLAG_MISSED set. A count run never skips its last pulse, which is
// flagged SYNCAP_TRIGGER_FLAG_LAST. Changes nothing; SYNCAP_TRIGGER_ERR_NOT_RUNNING outside a run.
enum syncap_trigger_error syncap_trigger_due_pulse(const struct syncap_trigger* trigger,
                                                   int64_t now_ns,
                                                   struct syncap_trigger_pulse* pulse);

// Records that the rising edge of `pulse` (from syncap_trigger_due_pulse) was driven at edge_ns:
// adds SYNCAP_TRIGGER_FLAG_LATE to pulse->flags when beyond the tolerance, updates the stats,
// moves on to the following pulse, and stops the run after its last pulse.
enum syncap_trigger_error syncap_trigger_edge_driven(struct syncap_trigger* trigger,
                                                     struct syncap_trigger_pulse* pulse,
                                                     int64_t edge_ns);

void syncap_trigger_get_stats(const struct syncap_trigger* trigger,
                              struct syncap_trigger_stats* stats);

// Start/stop input lines (rising edges of buttons or a controller's outputs).
enum syncap_trigger_input {
  SYNCAP_TRIGGER_INPUT_START,
  SYNCAP_TRIGGER_INPUT_STOP,
};

enum syncap_trigger_input_action {
  SYNCAP_TRIGGER_INPUT_BOUNCE,   // within debounce_ns of the previous edge of this input: ignored
  SYNCAP_TRIGGER_INPUT_IGNORED,  // start while running, stop while not running
  SYNCAP_TRIGGER_INPUT_STARTED,  // a run began, pulse 0 at start_ns
  SYNCAP_TRIGGER_INPUT_STOPPED,  // the run ended
};

// A rising edge of `input` at edge_ns: debounced per input (an edge counts as the previous one
// unless it was a bounce itself, so a bounce train never outlives debounce_ns after its first
// edge), then syncap_trigger_start(start_ns) or syncap_trigger_stop when the state allows it.
// Edges must come in time order per input.
enum syncap_trigger_input_action syncap_trigger_input_edge(struct syncap_trigger* trigger,
                                                           enum syncap_trigger_input input,
                                                           int64_t edge_ns, int64_t start_ns);

#ifdef __cplusplus
}
#endif
