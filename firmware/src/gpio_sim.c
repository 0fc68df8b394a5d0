// The "sim" backend: records edges instead of driving pins, for tests and dry runs.
#include "syncap/trigger/gpio_sim.h"

#include <errno.h>
#include <stdlib.h>
#include <time.h>

#include "gpio_backend.h"

struct sim_chip {
  struct syncap_gpio_edge* ring;
  size_t capacity;
  size_t head;   // index of the oldest edge
  size_t count;  // edges held
  uint64_t dropped;
};

// "N" -> N edges of ring, 1..SYNCAP_GPIO_SIM_MAX_EDGES; 0 when malformed.
static size_t parse_capacity(const char* argument) {
  if (argument == NULL) return SYNCAP_GPIO_SIM_DEFAULT_EDGES;
  char* end = NULL;
  errno = 0;
  const unsigned long long value = strtoull(argument, &end, 10);
  if (errno != 0 || end == argument || *end != '\0' || argument[0] == '-') return 0;
  if (value < 1 || value > SYNCAP_GPIO_SIM_MAX_EDGES) return 0;
  return (size_t)value;
}

static void* sim_open(const char* argument) {
  const size_t capacity = parse_capacity(argument);
  if (capacity == 0) {
    errno = EINVAL;
    return NULL;
  }
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

static int sim_request_outputs(void* state, const unsigned* offsets, size_t num_lines,
                               const char* consumer) {
  (void)state;
  (void)consumer;
  for (size_t i = 0; i < num_lines; ++i) {
    if (offsets[i] >= SYNCAP_GPIO_SIM_NUM_LINES) {
      errno = EINVAL;
      return -1;
    }
  }
  return 0;
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

static int sim_set_all(void* state, const unsigned* offsets, size_t num_lines, int value) {
  const int64_t time_ns = monotonic_ns();  // all lines switch at one instant, as in a bulk set
  for (size_t i = 0; i < num_lines; ++i) {
    record_edge(state, (struct syncap_gpio_edge){offsets[i], value, time_ns});
  }
  return 0;
}

static void sim_release(void* state, const unsigned* offsets, size_t num_lines) {
  (void)state;
  (void)offsets;
  (void)num_lines;
}

static void sim_close(void* state) {
  struct sim_chip* chip = state;
  free(chip->ring);
  free(chip);
}

const struct syncap_gpio_backend syncap_gpio_sim_backend = {
    .name = "sim",
    .open = sim_open,
    .request_outputs = sim_request_outputs,
    .set_all = sim_set_all,
    .release = sim_release,
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
