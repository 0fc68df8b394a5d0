// Internal: what a GPIO backend provides. gpio.c does the bookkeeping common to all backends
// (argument checks, requested lines, current level), so a backend only touches its hardware.
#pragma once

#include <stddef.h>
#include <stdint.h>

#include "syncap/trigger/gpio.h"

struct syncap_gpio_backend {
  const char* name;
  // New backend state for the spec's argument (the text after "name:", or NULL); NULL + errno.
  void* (*open)(const char* argument);
  int (*request_outputs)(void* state, const unsigned* offsets, size_t num_lines,
                         const char* consumer);
  // Drives the lines at offsets (a subset of the requested ones, none already at value) to value
  // at one instant; stores the CLOCK_MONOTONIC time the lines switched at.
  int (*set_all)(void* state, const unsigned* offsets, size_t num_lines, int value,
                 int64_t* time_ns);
  // Called with the lines already driven low.
  void (*release)(void* state, const unsigned* offsets, size_t num_lines);
  // Input lines reporting edges; wait_edge: 1 edge, 0 timeout, -1 error (see gpio.h).
  int (*request_inputs)(void* state, const unsigned* offsets, size_t num_lines,
                        const char* consumer);
  int (*wait_edge)(void* state, const unsigned* offsets, size_t num_lines, int64_t timeout_ns,
                   struct syncap_gpio_event* event);
  void (*release_inputs)(void* state, const unsigned* offsets, size_t num_lines);
  void (*close)(void* state);
};

extern const struct syncap_gpio_backend syncap_gpio_sim_backend;
extern const struct syncap_gpio_backend syncap_gpio_gpiod_backend;

struct syncap_gpio {
  const struct syncap_gpio_backend* backend;
  void* state;
  unsigned offsets[SYNCAP_GPIO_MAX_LINES];
  size_t num_lines;        // 0 while no lines are requested
  uint32_t high;           // bit i: requested line i is high
  int64_t last_change_ns;  // when the backend last switched them, 0 before that
  unsigned inputs[SYNCAP_GPIO_MAX_LINES];
  size_t num_inputs;  // 0 while no input lines are requested
};
