// The "sim" backend: records edges instead of driving pins, for tests and dry runs; with a chip
// name it also drives the shared chip of that name (gpiosim.h), which other processes watch.
#include "syncap/trigger/gpio_sim.h"

#include <errno.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "gpio_backend.h"
#include "syncap/trigger/gpiosim.h"

_Static_assert(SYNCAP_GPIO_SIM_NUM_LINES == SYNCAP_GPIOSIM_NUM_LINES, "both chips have 64 lines");

struct sim_chip {
  struct syncap_gpio_edge* ring;
  size_t capacity;
  size_t head;   // index of the oldest edge
  size_t count;  // edges held
  uint64_t dropped;
  struct syncap_gpiosim* shared;  // NULL for the in-process chip
  // Per input line of the shared chip: the last rising edge handed out.
  struct syncap_gpiosim_rise seen[SYNCAP_GPIO_SIM_NUM_LINES];
};

static bool is_decimal(const char* text) {
  return text[0] != '\0' && strspn(text, "0123456789") == strlen(text);
}

// "N" -> N edges of ring, 1..SYNCAP_GPIO_SIM_MAX_EDGES; 0 when out of range.
static size_t parse_capacity(const char* argument) {
  errno = 0;
  const unsigned long long value = strtoull(argument, NULL, 10);
  if (errno != 0 || value < 1 || value > SYNCAP_GPIO_SIM_MAX_EDGES) return 0;
  return (size_t)value;
}

static struct sim_chip* new_chip(size_t capacity) {
  struct sim_chip* chip = calloc(1, sizeof(*chip));
  if (chip == NULL) return NULL;
  chip->ring = calloc(capacity, sizeof(chip->ring[0]));
  if (chip->ring == NULL) {
    free(chip);
    errno = ENOMEM;
    return NULL;
  }
  chip->capacity = capacity;
  return chip;
}

static void sim_close(void* state) {
  struct sim_chip* chip = state;
  syncap_gpiosim_close(chip->shared);
  free(chip->ring);
  free(chip);
}

// NULL -> in-process chip with the default ring; "N" -> ring of N edges; anything else names the
// shared chip, created when missing.
static void* sim_open(const char* argument) {
  const bool shared = argument != NULL && !is_decimal(argument);
  size_t capacity = SYNCAP_GPIO_SIM_DEFAULT_EDGES;
  if (argument != NULL && !shared) capacity = parse_capacity(argument);
  if (capacity == 0 || (shared && !syncap_gpiosim_name_is_valid(argument))) {
    errno = EINVAL;
    return NULL;
  }
  struct sim_chip* chip = new_chip(capacity);
  if (chip == NULL || !shared) return chip;
  chip->shared = syncap_gpiosim_open(argument, true);
  if (chip->shared == NULL) {
    const int error = errno;
    sim_close(chip);
    errno = error;
    return NULL;
  }
  return chip;
}

// EINVAL for an offset beyond the simulated chip's lines.
static int check_offsets(const unsigned* offsets, size_t num_lines) {
  for (size_t i = 0; i < num_lines; ++i) {
    if (offsets[i] >= SYNCAP_GPIO_SIM_NUM_LINES) {
      errno = EINVAL;
      return -1;
    }
  }
  return 0;
}

// A shared chip's lines start a new run, so that watchers number this writer's edges from 1.
static int sim_request_outputs(void* state, const unsigned* offsets, size_t num_lines,
                               const char* consumer) {
  (void)consumer;
  struct sim_chip* chip = state;
  if (check_offsets(offsets, num_lines) < 0) return -1;
  if (chip->shared == NULL) return 0;
  return syncap_gpiosim_claim_lines(chip->shared, offsets, num_lines);
}

static void record_edge(struct sim_chip* chip, struct syncap_gpio_edge edge) {
  if (chip->count == chip->capacity) {
    chip->head = (chip->head + 1) % chip->capacity;
    --chip->count;
    ++chip->dropped;
  }
  chip->ring[(chip->head + chip->count) % chip->capacity] = edge;
  ++chip->count;
}

static int64_t monotonic_ns(void) {
  struct timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  return (int64_t)now.tv_sec * 1000000000 + now.tv_nsec;
}

static int sim_set_all(void* state, const unsigned* offsets, size_t num_lines, int value,
                       int64_t* time_ns) {
  struct sim_chip* chip = state;
  if (chip->shared != NULL) {
    // The shared chip takes the time under its lock, so watchers see exactly this edge time.
    if (syncap_gpiosim_set_lines(chip->shared, offsets, num_lines, value, time_ns) < 0) return -1;
  } else {
    *time_ns = monotonic_ns();  // all lines switch at one instant, as in a bulk set
  }
  for (size_t i = 0; i < num_lines; ++i) {
    record_edge(chip, (struct syncap_gpio_edge){offsets[i], value, *time_ns});
  }
  return 0;
}

static void sim_release(void* state, const unsigned* offsets, size_t num_lines) {
  (void)state;
  (void)offsets;
  (void)num_lines;
}

// Inputs: edges from now on. Only the shared chip has anyone to drive them.
static int sim_request_inputs(void* state, const unsigned* offsets, size_t num_lines,
                              const char* consumer) {
  (void)consumer;
  struct sim_chip* chip = state;
  if (check_offsets(offsets, num_lines) < 0) return -1;
  if (chip->shared == NULL) return 0;
  for (size_t i = 0; i < num_lines; ++i) {
    struct syncap_gpiosim_line line;
    if (syncap_gpiosim_read_line(chip->shared, offsets[i], &line) < 0) return -1;
    chip->seen[offsets[i]] = (struct syncap_gpiosim_rise){line.run, line.count, line.last_rise_ns};
  }
  return 0;
}

static void sleep_ns(int64_t ns) {
  const struct timespec delay = {.tv_sec = ns / 1000000000, .tv_nsec = ns % 1000000000};
  nanosleep(&delay, NULL);
}

// The shared chip wakes watchers per line; with several input lines this polls each one every
// millisecond, which is plenty for start/stop buttons.
#define SIM_INPUT_POLL_NS 1000000

static int sim_wait_edge(void* state, const unsigned* offsets, size_t num_lines, int64_t timeout_ns,
                         struct syncap_gpio_event* event) {
  struct sim_chip* chip = state;
  if (chip->shared == NULL) {
    sleep_ns(timeout_ns);
    return 0;
  }
  const int64_t deadline_ns = monotonic_ns() + timeout_ns;
  for (;;) {
    for (size_t i = 0; i < num_lines; ++i) {
      struct syncap_gpiosim_rise rise = chip->seen[offsets[i]];
      if (syncap_gpiosim_wait_rising(chip->shared, offsets[i], 0, &rise) == 0) {
        chip->seen[offsets[i]] = rise;
        *event = (struct syncap_gpio_event){offsets[i], 1, rise.time_ns};
        return 1;
      }
      if (errno != ETIMEDOUT) return -1;
    }
    const int64_t left_ns = deadline_ns - monotonic_ns();
    if (left_ns <= 0) return 0;
    sleep_ns(left_ns < SIM_INPUT_POLL_NS ? left_ns : SIM_INPUT_POLL_NS);
  }
}

const struct syncap_gpio_backend syncap_gpio_sim_backend = {
    .name = "sim",
    .open = sim_open,
    .request_outputs = sim_request_outputs,
    .set_all = sim_set_all,
    .release = sim_release,
    .request_inputs = sim_request_inputs,
    .wait_edge = sim_wait_edge,
    .release_inputs = sim_release,
    .close = sim_close,
};

static const struct sim_chip* sim_chip_of(const struct syncap_gpio* gpio) {
  return gpio->backend == &syncap_gpio_sim_backend ? gpio->state : NULL;
}

size_t syncap_gpio_sim_edges(const struct syncap_gpio* gpio, struct syncap_gpio_edge* out,
                             size_t max) {
  const struct sim_chip* chip = sim_chip_of(gpio);
  if (chip == NULL) return 0;
  const size_t n = chip->count < max ? chip->count : max;
  for (size_t i = 0; i < n; ++i) out[i] = chip->ring[(chip->head + i) % chip->capacity];
  return n;
}

uint64_t syncap_gpio_sim_dropped(const struct syncap_gpio* gpio) {
  const struct sim_chip* chip = sim_chip_of(gpio);
  return chip != NULL ? chip->dropped : 0;
}
