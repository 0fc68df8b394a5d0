// Internal: the libgpiod 1.6 backend ("gpiochipN", "/dev/gpiochipN", "gpiod:NAME|LABEL|NUMBER").
// Every libgpiod call goes through a table of function pointers, the real libgpiod by default, so
// that tests can put a fake in its place (no GPIO chip needed) and script its results.
#pragma once

#include <gpiod.h>
#include <stdint.h>
#include <time.h>

struct syncap_gpiod_ops {
  struct gpiod_chip* (*chip_open_lookup)(const char* descr);
  void (*chip_close)(struct gpiod_chip* chip);
  int (*chip_get_lines)(struct gpiod_chip* chip, unsigned int* offsets, unsigned int num_offsets,
                        struct gpiod_line_bulk* bulk);
  int (*line_request_bulk_output)(struct gpiod_line_bulk* bulk, const char* consumer,
                                  const int* default_vals);
  int (*line_request_bulk_both_edges_events)(struct gpiod_line_bulk* bulk, const char* consumer);
  int (*line_set_value_bulk)(struct gpiod_line_bulk* bulk, const int* values);
  void (*line_release_bulk)(struct gpiod_line_bulk* bulk);
  int (*line_event_wait_bulk)(struct gpiod_line_bulk* bulk, const struct timespec* timeout,
                              struct gpiod_line_bulk* event_bulk);
  int (*line_event_read)(struct gpiod_line* line, struct gpiod_line_event* event);
  unsigned int (*line_offset)(struct gpiod_line* line);
  int (*clock_gettime)(clockid_t clock, struct timespec* now);
};

// The real libgpiod.
extern const struct syncap_gpiod_ops syncap_gpiod_real_ops;

// Chips opened from now on use ops (NULL: the real libgpiod again). For tests.
void syncap_gpiod_set_ops(const struct syncap_gpiod_ops* ops);

// An edge event's timestamp as CLOCK_MONOTONIC ns. Linux >= 5.7 stamps GPIO v1 line events with
// CLOCK_MONOTONIC (ktime_get_ns), older kernels with CLOCK_REALTIME, and libgpiod 1.6 passes the
// kernel's value through without saying which (gpiod.h: "best estimate of time of event
// occurrence"). So a timestamp nearer to realtime_now_ns than to monotonic_now_ns is converted
// by the current offset between the two clocks.
int64_t syncap_gpiod_event_monotonic_ns(int64_t event_ns, int64_t monotonic_now_ns,
                                        int64_t realtime_now_ns);
