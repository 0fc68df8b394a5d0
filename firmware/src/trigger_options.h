// Internal: the command line of syncap-trigger.
#pragma once

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "syncap/trigger/gpio.h"

struct trigger_options {
  double rate_hz;
  const char* rate_text;  // as given, for error messages
  int64_t width_us;
  const char* width_text;
  uint64_t count;  // 0: forever
  unsigned lines[SYNCAP_GPIO_MAX_LINES];
  size_t num_lines;
  const char* lines_text;
  const char* chip;
  const char* lcm_url;  // NULL: LCM's default provider
  int16_t trigger_id;
  int64_t start_delay_ms;
  bool quiet;
};

enum trigger_options_result {
  TRIGGER_OPTIONS_RUN,
  TRIGGER_OPTIONS_HELP,     // --help was printed
  TRIGGER_OPTIONS_INVALID,  // the error and the usage were printed to stderr
};

enum trigger_options_result trigger_options_parse(int argc, char** argv,
                                                  struct trigger_options* options);

void trigger_options_usage(FILE* out);

// Prints "syncap-trigger: invalid OPTION 'VALUE': WHY" and the usage to stderr.
void trigger_options_reject(const char* option, const char* value, const char* why);
