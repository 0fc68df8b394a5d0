// Internal: the command line and config file of syncap-trigger.
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
  int64_t phases_us[SYNCAP_GPIO_MAX_LINES];  // per line, in the order of lines
  size_t num_phases;                         // 0: all lines at phase 0
  const char* phases_text;
  int64_t spin_us;  // busy-wait this long before each edge (0: sleep only)
  const char* chip;
  const char* lcm_url;  // NULL: LCM's default provider
  int16_t trigger_id;
  int64_t start_delay_ms;
  int64_t start_line;  // input line offset on the same chip, -1 for none
  int64_t stop_line;   // likewise
  int64_t debounce_us;
  int64_t bench_seconds;  // > 0: timing benchmark instead of a normal run
  bool quiet;
  const char* config_path;  // --config FILE, NULL without
  char* config_text;        // the file's text, which the values from it point into
};

enum trigger_options_result {
  TRIGGER_OPTIONS_RUN,
  TRIGGER_OPTIONS_HELP,     // --help was printed
  TRIGGER_OPTIONS_INVALID,  // the error and the usage were printed to stderr
};

// Defaults, then the --config file when one is given, then the command line, which wins.
enum trigger_options_result trigger_options_parse(int argc, char** argv,
                                                  struct trigger_options* options);

// Applies the `key = value` lines of the file at path to options (keys: the long options without
// their dashes; '#' starts a comment; blank lines are fine; flags take true/false/yes/no/1/0).
// false with a message "PATH:LINE: what is wrong" in error. options keeps the file's text.
bool trigger_options_load_config(const char* path, struct trigger_options* options, char* error,
                                 size_t size);

// The defaults, without any file or argument.
void trigger_options_defaults(struct trigger_options* options);

// Frees what parsing allocated (the config file's text). Values from the file go with it.
void trigger_options_free(struct trigger_options* options);

void trigger_options_usage(FILE* out);

// Prints "syncap-trigger: invalid OPTION 'VALUE': WHY" and the usage to stderr.
void trigger_options_reject(const char* option, const char* value, const char* why);
