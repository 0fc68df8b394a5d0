// The "sim" GPIO backend: a chip with SYNCAP_GPIO_SIM_NUM_LINES lines that records every edge in a
// bounded ring (default SYNCAP_GPIO_SIM_DEFAULT_EDGES; spec "sim:N" for N edges). When the ring is
// full the oldest edge is dropped and counted.
//   "sim", "sim:N"  in-process only;
//   "sim:NAME"      (NAME not all digits, see gpiosim.h) also drives the shared chip NAME, created
//                   when missing, so that other processes can watch the lines: requesting lines
//                   starts a new run on them (rising-edge counts from 1), every set is one instant
//                   on the shared chip, and syncap_gpio_last_change_ns() is the time its watchers
//                   see. A bad NAME is EINVAL; a chip that cannot be opened keeps shm's errno.
#pragma once

#include <stddef.h>
#include <stdint.h>

#include "syncap/trigger/gpio.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SYNCAP_GPIO_SIM_NUM_LINES 64
#define SYNCAP_GPIO_SIM_DEFAULT_EDGES 4096
#define SYNCAP_GPIO_SIM_MAX_EDGES 1000000

struct syncap_gpio_edge {
  unsigned line;    // line offset
  int value;        // level after the edge: 1 rising, 0 falling
  int64_t time_ns;  // CLOCK_MONOTONIC when it was driven
};

// Copies up to max recorded edges, oldest first, into out and returns how many. Returns 0 for a
// chip of another backend.
size_t syncap_gpio_sim_edges(const struct syncap_gpio* gpio, struct syncap_gpio_edge* out,
                             size_t max);

// Edges dropped because the ring was full.
uint64_t syncap_gpio_sim_dropped(const struct syncap_gpio* gpio);

#ifdef __cplusplus
}
#endif
