#include "syncap/trigger/trigger.h"

#include <stdbool.h>
#include <stdlib.h>

#include "schedule.h"

struct syncap_trigger {
  struct syncap_trigger_config config;
  uint64_t rate_uhz;
  enum syncap_trigger_state state;
  int64_t start_ns;
  uint64_t next_index;  // the 64-bit frame counter: next pulse not yet driven
  struct syncap_trigger_stats stats;
  // The events of a pulse relative to t_k, sorted (see syncap_trigger_pulse_events).
  struct syncap_trigger_event events[SYNCAP_TRIGGER_MAX_EVENTS];
  size_t num_events;
  int64_t min_phase_ns;
  int64_t max_phase_ns;
  bool input_seen[2];        // per syncap_trigger_input: an edge was accepted before
  int64_t input_last_ns[2];  // and when
};

static void build_events(struct syncap_trigger* trigger);

struct syncap_trigger* syncap_trigger_new(const struct syncap_trigger_config* config,
                                          enum syncap_trigger_error* error) {
  *error = syncap_trigger_config_validate(config);
  if (*error != SYNCAP_TRIGGER_OK) return NULL;
  struct syncap_trigger* trigger = calloc(1, sizeof(*trigger));
  if (trigger == NULL) {
    *error = SYNCAP_TRIGGER_ERR_NO_MEMORY;
    return NULL;
  }
  trigger->config = *config;
  trigger->rate_uhz = syncap_schedule_rate_uhz(config->rate_hz);
  trigger->state = SYNCAP_TRIGGER_IDLE;
  build_events(trigger);
  return trigger;
}

// Falling before rising at equal times: a line that falls never blocks another one's rise.
static bool event_before(const struct syncap_trigger_event* a,
                         const struct syncap_trigger_event* b) {
  if (a->time_ns != b->time_ns) return a->time_ns < b->time_ns;
  return a->level < b->level;
}

// One event per distinct (time, level), in time order; insertion sort (at most 64 events).
static void build_events(struct syncap_trigger* trigger) {
  const struct syncap_trigger_config* config = &trigger->config;
  trigger->min_phase_ns = config->phase_ns[0];
  trigger->max_phase_ns = config->phase_ns[0];
  for (size_t i = 0; i < config->num_lines; ++i) {
    if (config->phase_ns[i] < trigger->min_phase_ns) trigger->min_phase_ns = config->phase_ns[i];
    if (config->phase_ns[i] > trigger->max_phase_ns) trigger->max_phase_ns = config->phase_ns[i];
    for (int level = 1; level >= 0; --level) {
      const int64_t time_ns = config->phase_ns[i] + (level ? 0 : config->pulse_width_ns);
      size_t j = 0;
      while (j < trigger->num_events &&
             (trigger->events[j].time_ns != time_ns || trigger->events[j].level != level)) {
        ++j;
      }
      if (j == trigger->num_events) {
        trigger->events[trigger->num_events++] =
            (struct syncap_trigger_event){.time_ns = time_ns, .lines = 0, .level = level};
      }
      trigger->events[j].lines |= UINT32_C(1) << i;
    }
  }
  for (size_t i = 1; i < trigger->num_events; ++i) {
    const struct syncap_trigger_event event = trigger->events[i];
    size_t j = i;
    while (j > 0 && event_before(&event, &trigger->events[j - 1])) {
      trigger->events[j] = trigger->events[j - 1];
      --j;
    }
    trigger->events[j] = event;
  }
}

size_t syncap_trigger_pulse_events(const struct syncap_trigger* trigger, uint64_t index,
                                   struct syncap_trigger_event events[SYNCAP_TRIGGER_MAX_EVENTS]) {
  const int64_t t_ns = syncap_trigger_rise_ns(trigger, index);
  for (size_t i = 0; i < trigger->num_events; ++i) {
    events[i] = trigger->events[i];
    events[i].time_ns += t_ns;
  }
  return trigger->num_events;
}

void syncap_trigger_free(struct syncap_trigger* trigger) { free(trigger); }

enum syncap_trigger_error syncap_trigger_start(struct syncap_trigger* trigger, int64_t start_ns) {
  if (trigger->state == SYNCAP_TRIGGER_RUNNING) return SYNCAP_TRIGGER_ERR_ALREADY_RUNNING;
  trigger->state = SYNCAP_TRIGGER_RUNNING;
  trigger->start_ns = start_ns;
  trigger->next_index = 0;
  trigger->stats = (struct syncap_trigger_stats){0};
  return SYNCAP_TRIGGER_OK;
}

enum syncap_trigger_error syncap_trigger_stop(struct syncap_trigger* trigger) {
  if (trigger->state != SYNCAP_TRIGGER_RUNNING) return SYNCAP_TRIGGER_ERR_NOT_RUNNING;
  trigger->state = SYNCAP_TRIGGER_STOPPED;
  return SYNCAP_TRIGGER_OK;
}

enum syncap_trigger_state syncap_trigger_state(const struct syncap_trigger* trigger) {
  return trigger->state;
}

int64_t syncap_trigger_rise_ns(const struct syncap_trigger* trigger, uint64_t index) {
  return trigger->start_ns + syncap_schedule_offset_ns(trigger->rate_uhz, index);
}

int64_t syncap_trigger_fall_ns(const struct syncap_trigger* trigger, uint64_t index) {
  return syncap_trigger_rise_ns(trigger, index) + trigger->config.pulse_width_ns;
}

int64_t syncap_trigger_next_rise_ns(const struct syncap_trigger* trigger) {
  return syncap_trigger_rise_ns(trigger, trigger->next_index) + trigger->min_phase_ns;
}

static bool is_count_run(const struct syncap_trigger* trigger) {
  return trigger->config.count != SYNCAP_TRIGGER_FOREVER;
}

// The pulse to drive at now_ns: the next one unless its successor is already due too, in which
// case the whole periods that passed are skipped (frame numbers stay pulse indices).
static uint64_t due_index(const struct syncap_trigger* trigger, int64_t now_ns) {
  uint64_t index = trigger->next_index;
  const int64_t first_ns = now_ns - trigger->min_phase_ns;  // compared with t_k
  if (syncap_trigger_rise_ns(trigger, index + 1) <= first_ns) {
    index = syncap_schedule_index_at(trigger->rate_uhz, first_ns - trigger->start_ns);
  }
  if (is_count_run(trigger) && index >= trigger->config.count) index = trigger->config.count - 1;
  return index;
}

enum syncap_trigger_error syncap_trigger_due_pulse(const struct syncap_trigger* trigger,
                                                   int64_t now_ns,
                                                   struct syncap_trigger_pulse* pulse) {
  if (trigger->state != SYNCAP_TRIGGER_RUNNING) return SYNCAP_TRIGGER_ERR_NOT_RUNNING;
  const uint64_t index = due_index(trigger, now_ns);
  *pulse = (struct syncap_trigger_pulse){
      .index = index,
      .rise_ns = syncap_trigger_rise_ns(trigger, index) + trigger->min_phase_ns,
      .fall_ns = syncap_trigger_fall_ns(trigger, index) + trigger->max_phase_ns,
      .missed = index - trigger->next_index,
  };
  if (pulse->missed > 0) pulse->flags |= SYNCAP_TRIGGER_FLAG_MISSED;
  if (is_count_run(trigger) && index == trigger->config.count - 1) {
    pulse->flags |= SYNCAP_TRIGGER_FLAG_LAST;
  }
  return SYNCAP_TRIGGER_OK;
}

enum syncap_trigger_error syncap_trigger_edge_driven(struct syncap_trigger* trigger,
                                                     struct syncap_trigger_pulse* pulse,
                                                     int64_t edge_ns) {
  if (trigger->state != SYNCAP_TRIGGER_RUNNING) return SYNCAP_TRIGGER_ERR_NOT_RUNNING;
  if (edge_ns - pulse->rise_ns > trigger->config.late_tolerance_ns) {
    pulse->flags |= SYNCAP_TRIGGER_FLAG_LATE;
    ++trigger->stats.late;
  }
  ++trigger->stats.pulses;
  trigger->stats.missed += pulse->missed;
  trigger->next_index = pulse->index + 1;
  if (pulse->flags & SYNCAP_TRIGGER_FLAG_LAST) trigger->state = SYNCAP_TRIGGER_STOPPED;
  return SYNCAP_TRIGGER_OK;
}

void syncap_trigger_get_stats(const struct syncap_trigger* trigger,
                              struct syncap_trigger_stats* stats) {
  *stats = trigger->stats;
}

enum syncap_trigger_input_action syncap_trigger_input_edge(struct syncap_trigger* trigger,
                                                           enum syncap_trigger_input input,
                                                           int64_t edge_ns, int64_t start_ns) {
  const size_t i = input == SYNCAP_TRIGGER_INPUT_START ? 0 : 1;
  if (trigger->input_seen[i] && edge_ns - trigger->input_last_ns[i] < trigger->config.debounce_ns) {
    return SYNCAP_TRIGGER_INPUT_BOUNCE;
  }
  trigger->input_seen[i] = true;
  trigger->input_last_ns[i] = edge_ns;
  if (input == SYNCAP_TRIGGER_INPUT_START) {
    return syncap_trigger_start(trigger, start_ns) == SYNCAP_TRIGGER_OK
               ? SYNCAP_TRIGGER_INPUT_STARTED
               : SYNCAP_TRIGGER_INPUT_IGNORED;
  }
  return syncap_trigger_stop(trigger) == SYNCAP_TRIGGER_OK ? SYNCAP_TRIGGER_INPUT_STOPPED
                                                           : SYNCAP_TRIGGER_INPUT_IGNORED;
}
