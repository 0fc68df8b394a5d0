// Internal: the command line and config file of syncap-trigger.
#pragma once

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "syncap/trigger/gpio.h"

// A value taken from a YAML config file, kept as long as the options that point into it.
struct trigger_config_string {
  struct trigger_config_string* next;
  char text[];
};

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
  char* config_text;        // a 'key = value' file's text, which its values point into
  struct trigger_config_string* config_strings;  // a YAML file's values
};

enum trigger_options_result {
  TRIGGER_OPTIONS_RUN,
  TRIGGER_OPTIONS_HELP,     // --help was printed
  TRIGGER_OPTIONS_INVALID,  // the error and the usage were printed to stderr
};

// Defaults, then the --config file when one is given, then the command line, which wins.
enum trigger_options_result trigger_options_parse(int argc, char** argv,
                                                  struct trigger_options* options);

// Applies the file at path to options. A path ending in .yaml or .yml is YAML
// (trigger_options_load_yaml); any other holds `key = value` lines (keys: the long options without
// their dashes; '#' starts a comment; blank lines are fine; flags take true/false/yes/no/1/0).
// false with a message "PATH:LINE: what is wrong" in error. options keeps the file's text.
bool trigger_options_load_config(const char* path, struct trigger_options* options, char* error,
                                 size_t size);

// Applies a YAML file (docs/guide/rig.md): a flat mapping of `key: value` entries, each key an
// option; or the rig file (a top-level `trigger:`, `host:`, `edges:` or `cameras:`), whose
// top-level scalar entries that are options of syncap-trigger (`lcm-url`) come first and then
// every entry of its `trigger:` section. A list value ([17, 27]) is taken as "17,27". false with
// "PATH:LINE:COLUMN: key 'KEY': what is wrong" in error. trigger_config_yaml.c.
bool trigger_options_load_yaml(const char* path, struct trigger_options* options, char* error,
                               size_t size);

// Whether key is one of the options a config file may set (not help or config).
bool trigger_options_is_key(const char* key);

// Applies one config entry, key a long option's name without dashes; NULL, or why not. The value
// must live as long as options (trigger_options_keep).
const char* trigger_options_apply_key(const char* key, const char* value,
                                      struct trigger_options* options);

// A copy of text[0..length) that lives until trigger_options_free; NULL when out of memory.
const char* trigger_options_keep(struct trigger_options* options, const char* text, size_t length);

// The defaults, without any file or argument.
void trigger_options_defaults(struct trigger_options* options);

// Frees what parsing allocated (the config file's text). Values from the file go with it.
void trigger_options_free(struct trigger_options* options);

void trigger_options_usage(FILE* out);

// Prints "syncap-trigger: invalid OPTION 'VALUE': WHY" and the usage to stderr.
void trigger_options_reject(const char* option, const char* value, const char* why);
