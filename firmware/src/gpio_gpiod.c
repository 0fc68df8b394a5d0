// The libgpiod 1.6 backend: outputs as one bulk request set with gpiod_line_set_value_bulk, inputs
// as one bulk request for both edges, events read with the kernel's timestamps.
#include "gpio_gpiod.h"

#include <errno.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "gpio_backend.h"

const struct syncap_gpiod_ops syncap_gpiod_real_ops = {
    .chip_open_lookup = gpiod_chip_open_lookup,
    .chip_close = gpiod_chip_close,
    .chip_get_lines = gpiod_chip_get_lines,
    .line_request_bulk_output = gpiod_line_request_bulk_output,
    .line_request_bulk_both_edges_events = gpiod_line_request_bulk_both_edges_events,
    .line_set_value_bulk = gpiod_line_set_value_bulk,
    .line_release_bulk = gpiod_line_release_bulk,
    .line_event_wait_bulk = gpiod_line_event_wait_bulk,
    .line_event_read = gpiod_line_event_read,
    .line_offset = gpiod_line_offset,
    .clock_gettime = clock_gettime,
};

static const struct syncap_gpiod_ops* current_ops = &syncap_gpiod_real_ops;

void syncap_gpiod_set_ops(const struct syncap_gpiod_ops* ops) {
  current_ops = ops != NULL ? ops : &syncap_gpiod_real_ops;
}

#define NS_PER_S INT64_C(1000000000)

int64_t syncap_gpiod_event_monotonic_ns(int64_t event_ns, int64_t monotonic_now_ns,
                                        int64_t realtime_now_ns) {
  const int64_t to_monotonic = llabs(event_ns - monotonic_now_ns);
  const int64_t to_realtime = llabs(event_ns - realtime_now_ns);
  if (to_monotonic <= to_realtime) return event_ns;
  return event_ns - (realtime_now_ns - monotonic_now_ns);
}

struct gpiod_state {
  const struct syncap_gpiod_ops* ops;
  struct gpiod_chip* chip;
  struct gpiod_line_bulk outputs;
  unsigned output_offsets[SYNCAP_GPIO_MAX_LINES];  // of the lines in outputs, in order
  int output_values[SYNCAP_GPIO_MAX_LINES];        // their current levels
  size_t num_outputs;
  struct gpiod_line_bulk inputs;
  bool has_outputs;
  bool has_inputs;
};

static int64_t now_ns(const struct gpiod_state* s, clockid_t clock) {
  struct timespec now;
  s->ops->clock_gettime(clock, &now);
  return (int64_t)now.tv_sec * NS_PER_S + now.tv_nsec;
}

static void* gpiod_open(const char* argument) {
  if (argument == NULL || argument[0] == '\0') {
    errno = EINVAL;
    return NULL;
  }
  struct gpiod_state* s = calloc(1, sizeof(*s));
  if (s == NULL) return NULL;
  s->ops = current_ops;
  errno = 0;
  s->chip = s->ops->chip_open_lookup(argument);
  if (s->chip == NULL) {
    const int error = errno != 0 ? errno : ENOENT;
    free(s);
    errno = error;
    return NULL;
  }
  return s;
}

// The lines at offsets into bulk; EINVAL for an offset the chip does not have.
static int get_lines(struct gpiod_state* s, const unsigned* offsets, size_t num_lines,
                     struct gpiod_line_bulk* bulk) {
  unsigned copy[SYNCAP_GPIO_MAX_LINES];
  memcpy(copy, offsets, num_lines * sizeof(offsets[0]));
  gpiod_line_bulk_init(bulk);
  errno = 0;
  if (s->ops->chip_get_lines(s->chip, copy, (unsigned)num_lines, bulk) < 0) {
    if (errno == 0) errno = EINVAL;
    return -1;
  }
  return 0;
}

static int gpiod_request_outputs(void* state, const unsigned* offsets, size_t num_lines,
                                 const char* consumer) {
  struct gpiod_state* s = state;
  if (get_lines(s, offsets, num_lines, &s->outputs) < 0) return -1;
  const int low[SYNCAP_GPIO_MAX_LINES] = {0};
  errno = 0;
  if (s->ops->line_request_bulk_output(&s->outputs, consumer, low) < 0) {
    if (errno == 0) errno = EBUSY;
    return -1;
  }
  memcpy(s->output_offsets, offsets, num_lines * sizeof(offsets[0]));
  memset(s->output_values, 0, sizeof(s->output_values));
  s->num_outputs = num_lines;
  s->has_outputs = true;
  return 0;
}

// One gpiod_line_set_value_bulk for the whole output bulk: the lines at offsets get value, the
// others keep theirs. The edge happens during the ioctl: its time is the middle of the call.
static int gpiod_set_all(void* state, const unsigned* offsets, size_t num_lines, int value,
                         int64_t* time_ns) {
  struct gpiod_state* s = state;
  int values[SYNCAP_GPIO_MAX_LINES];
  memcpy(values, s->output_values, sizeof(values));
  for (size_t i = 0; i < num_lines; ++i) {
    for (size_t j = 0; j < s->num_outputs; ++j) {
      if (s->output_offsets[j] == offsets[i]) values[j] = value;
    }
  }
  const int64_t before_ns = now_ns(s, CLOCK_MONOTONIC);
  if (s->ops->line_set_value_bulk(&s->outputs, values) < 0) return -1;
  memcpy(s->output_values, values, sizeof(values));
  const int64_t after_ns = now_ns(s, CLOCK_MONOTONIC);
  *time_ns = before_ns + (after_ns - before_ns) / 2;
  return 0;
}

static void gpiod_release(void* state, const unsigned* offsets, size_t num_lines) {
  (void)offsets;
  (void)num_lines;
  struct gpiod_state* s = state;
  if (!s->has_outputs) return;
  s->ops->line_release_bulk(&s->outputs);
  s->has_outputs = false;
}

static int gpiod_request_inputs(void* state, const unsigned* offsets, size_t num_lines,
                                const char* consumer) {
  struct gpiod_state* s = state;
  if (get_lines(s, offsets, num_lines, &s->inputs) < 0) return -1;
  errno = 0;
  if (s->ops->line_request_bulk_both_edges_events(&s->inputs, consumer) < 0) {
    if (errno == 0) errno = EBUSY;
    return -1;
  }
  s->has_inputs = true;
  return 0;
}

static int gpiod_wait_edge(void* state, const unsigned* offsets, size_t num_lines,
                           int64_t timeout_ns, struct syncap_gpio_event* event) {
  (void)offsets;
  (void)num_lines;
  struct gpiod_state* s = state;
  const struct timespec timeout = {.tv_sec = timeout_ns / NS_PER_S,
                                   .tv_nsec = timeout_ns % NS_PER_S};
  struct gpiod_line_bulk ready;
  gpiod_line_bulk_init(&ready);
  const int waited = s->ops->line_event_wait_bulk(&s->inputs, &timeout, &ready);
  if (waited <= 0) return waited;
  if (gpiod_line_bulk_num_lines(&ready) == 0) return 0;
  struct gpiod_line* line = gpiod_line_bulk_get_line(&ready, 0);
  struct gpiod_line_event raw;
  if (s->ops->line_event_read(line, &raw) < 0) return -1;
  const int64_t raw_ns = (int64_t)raw.ts.tv_sec * NS_PER_S + raw.ts.tv_nsec;
  *event = (struct syncap_gpio_event){
      .line = s->ops->line_offset(line),
      .rising = raw.event_type == GPIOD_LINE_EVENT_RISING_EDGE,
      .time_ns = syncap_gpiod_event_monotonic_ns(raw_ns, now_ns(s, CLOCK_MONOTONIC),
                                                 now_ns(s, CLOCK_REALTIME)),
  };
  return 1;
}

static void gpiod_release_inputs(void* state, const unsigned* offsets, size_t num_lines) {
  (void)offsets;
  (void)num_lines;
  struct gpiod_state* s = state;
  if (!s->has_inputs) return;
  s->ops->line_release_bulk(&s->inputs);
  s->has_inputs = false;
}

static void gpiod_close(void* state) {
  struct gpiod_state* s = state;
  gpiod_release(s, NULL, 0);
  gpiod_release_inputs(s, NULL, 0);
  s->ops->chip_close(s->chip);
  free(s);
}

const struct syncap_gpio_backend syncap_gpio_gpiod_backend = {
    .name = "gpiod",
    .open = gpiod_open,
    .request_outputs = gpiod_request_outputs,
    .set_all = gpiod_set_all,
    .release = gpiod_release,
    .request_inputs = gpiod_request_inputs,
    .wait_edge = gpiod_wait_edge,
    .release_inputs = gpiod_release_inputs,
    .close = gpiod_close,
};
