#include "trigger_options.h"

#include <ctype.h>
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum option_id {
  OPT_RATE = 1000,
  OPT_WIDTH_US,
  OPT_COUNT,
  OPT_LINES,
  OPT_PHASES_US,
  OPT_SPIN_US,
  OPT_CHIP,
  OPT_LCM_URL,
  OPT_TRIGGER_ID,
  OPT_START_DELAY_MS,
  OPT_START_LINE,
  OPT_STOP_LINE,
  OPT_DEBOUNCE_US,
  OPT_BENCH,
  OPT_CONFIG,
  OPT_QUIET,
  OPT_HELP,
  OPT_RATE_OLD,  // --rate, the old name of --rate-hz
};

static const struct option long_options[] = {
    {"rate-hz", required_argument, NULL, OPT_RATE},
    {"width-us", required_argument, NULL, OPT_WIDTH_US},
    {"count", required_argument, NULL, OPT_COUNT},
    {"lines", required_argument, NULL, OPT_LINES},
    {"phases-us", required_argument, NULL, OPT_PHASES_US},
    {"spin-us", required_argument, NULL, OPT_SPIN_US},
    {"chip", required_argument, NULL, OPT_CHIP},
    {"lcm-url", required_argument, NULL, OPT_LCM_URL},
    {"trigger-id", required_argument, NULL, OPT_TRIGGER_ID},
    {"start-delay-ms", required_argument, NULL, OPT_START_DELAY_MS},
    {"start-line", required_argument, NULL, OPT_START_LINE},
    {"stop-line", required_argument, NULL, OPT_STOP_LINE},
    {"debounce-us", required_argument, NULL, OPT_DEBOUNCE_US},
    {"bench", required_argument, NULL, OPT_BENCH},
    {"config", required_argument, NULL, OPT_CONFIG},
    {"quiet", no_argument, NULL, OPT_QUIET},
    {"help", no_argument, NULL, OPT_HELP},
    {"rate", required_argument, NULL, OPT_RATE_OLD},
    {NULL, 0, NULL, 0},
};

void trigger_options_usage(FILE* out) {
  fputs(
      "usage: syncap-trigger [OPTIONS]\n"
      "Drives the camera trigger lines and publishes one syncap_trigger_t per pulse on\n"
      "LCM channel SYNCAP_TRIGGER.\n"
      "  --rate-hz HZ         pulse rate, 0.01 to 1000 (default 30)\n"
      "  --width-us US        pulse high time, shorter than the period (default 1000)\n"
      "  --count N            pulses to send, 0 = until SIGINT/SIGTERM (default 0)\n"
      "  --lines L1,L2,...    GPIO line offsets (default 0)\n"
      "  --phases-us P1,P2,.. delay of each line's pulse after the scheduled time, one per\n"
      "                       line; phase + width <= period (default: all 0, together)\n"
      "  --spin-us US         sleep until US before each edge, then busy-wait to it; costs\n"
      "                       about US * edges per second of CPU, 0 = sleep only (default 200)\n"
      "  --chip SPEC          GPIO chip: 'sim' (simulated, in-process), 'sim:NAME'\n"
      "                       (simulated, shared with other processes: "
      "/dev/shm/syncap-gpiosim-NAME),\n"
      "                       or a real one through libgpiod: gpiochipN, /dev/gpiochipN,\n"
      "                       gpiod:LABEL (default sim)\n"
      "  --lcm-url URL        LCM provider (default: LCM's, udpm://239.255.76.67:7667?ttl=0)\n"
      "  --trigger-id N       id of this trigger module, 0 to 32767 (default 0)\n"
      "  --start-delay-ms MS  wait before the first pulse so subscribers can start (default 0)\n"
      "  --start-line N       input line on the same chip: a rising edge starts a run\n"
      "                       (without it the run starts at once)\n"
      "  --stop-line N        input line on the same chip: a rising edge stops the run\n"
      "  --debounce-us US     ignore input edges this close to the previous one (default 5000)\n"
      "  --config FILE        options from a file, keys as these options without dashes:\n"
      "                       FILE.yaml (or .yml) a flat YAML file or the rig file's\n"
      "                       trigger: section, any other 'key = value' lines; the\n"
      "                       command line overrides the file\n"
      "  --bench SECONDS      timing benchmark on the chip (no LCM): prints the rising edges'\n"
      "                       error against the schedule, p50/p99/max in us\n"
      "  --quiet              no start line and no summary\n"
      "  --help               this text\n",
      out);
}

void trigger_options_reject(const char* option, const char* value, const char* why) {
  fprintf(stderr, "syncap-trigger: invalid %s '%s': %s\n", option, value, why);
  trigger_options_usage(stderr);
}

void trigger_options_defaults(struct trigger_options* options) {
  *options = (struct trigger_options){
      .rate_hz = 30.0,
      .rate_text = "30",
      .width_us = 1000,
      .width_text = "1000",
      .count = 0,
      .lines = {0},
      .num_lines = 1,
      .lines_text = "0",
      .num_phases = 0,
      .phases_text = "",
      .spin_us = 200,
      .chip = "sim",
      .lcm_url = NULL,
      .trigger_id = 0,
      .start_delay_ms = 0,
      .start_line = -1,
      .stop_line = -1,
      .debounce_us = 5000,
      .bench_seconds = 0,
      .quiet = false,
      .config_path = NULL,
      .config_text = NULL,
      .config_strings = NULL,
  };
}

void trigger_options_free(struct trigger_options* options) {
  free(options->config_text);
  options->config_text = NULL;
  while (options->config_strings != NULL) {
    struct trigger_config_string* next = options->config_strings->next;
    free(options->config_strings);
    options->config_strings = next;
  }
}

const char* trigger_options_keep(struct trigger_options* options, const char* text, size_t length) {
  struct trigger_config_string* kept = malloc(sizeof(*kept) + length + 1);
  if (kept == NULL) return NULL;
  memcpy(kept->text, text, length);
  kept->text[length] = '\0';
  kept->next = options->config_strings;
  options->config_strings = kept;
  return kept->text;
}

// Whole-string decimal integer in [min, max].
static bool parse_integer(const char* text, int64_t min, int64_t max, int64_t* value) {
  char* end = NULL;
  errno = 0;
  const long long parsed = strtoll(text, &end, 10);
  if (errno != 0 || end == text || *end != '\0' || parsed < min || parsed > max) return false;
  *value = parsed;
  return true;
}

static bool parse_count(const char* text, uint64_t* value) {
  char* end = NULL;
  errno = 0;
  const unsigned long long parsed = strtoull(text, &end, 10);
  // strtoull accepts "-1" as a huge number; a count is never negative.
  if (errno != 0 || end == text || *end != '\0' || strchr(text, '-') != NULL) return false;
  *value = parsed;
  return true;
}

static bool parse_rate(const char* text, double* value) {
  char* end = NULL;
  errno = 0;
  const double parsed = strtod(text, &end);
  if (errno != 0 || end == text || *end != '\0' || !isfinite(parsed)) return false;
  *value = parsed;
  return true;
}

// "L1,L2,..." -> distinct offsets; returns NULL or why the list is wrong.
static const char* parse_lines(const char* text, struct trigger_options* options) {
  char buffer[256];
  if (strlen(text) >= sizeof(buffer)) return "list too long";
  strcpy(buffer, text);
  options->num_lines = 0;
  char* saveptr = NULL;
  for (char* item = strtok_r(buffer, ",", &saveptr); item != NULL;
       item = strtok_r(NULL, ",", &saveptr)) {
    int64_t offset = 0;
    if (!parse_integer(item, 0, 65535, &offset)) return "each line must be an offset 0..65535";
    if (options->num_lines == SYNCAP_GPIO_MAX_LINES) return "at most 32 lines";
    for (size_t i = 0; i < options->num_lines; ++i) {
      if (options->lines[i] == (unsigned)offset) return "a line is listed twice";
    }
    options->lines[options->num_lines++] = (unsigned)offset;
  }
  if (options->num_lines == 0) return "at least one line is needed";
  return NULL;
}

// "P1,P2,..." -> phases in us, each 0..1e8 (the longest period); NULL or why it is wrong.
static const char* parse_phases(const char* text, struct trigger_options* options) {
  char buffer[512];
  if (strlen(text) >= sizeof(buffer)) return "list too long";
  strcpy(buffer, text);
  options->num_phases = 0;
  char* saveptr = NULL;
  for (char* item = strtok_r(buffer, ",", &saveptr); item != NULL;
       item = strtok_r(NULL, ",", &saveptr)) {
    int64_t phase = 0;
    if (!parse_integer(item, 0, 100000000, &phase)) {
      return "each phase must be a whole number of microseconds >= 0";
    }
    if (options->num_phases == SYNCAP_GPIO_MAX_LINES) return "at most 32 phases";
    options->phases_us[options->num_phases++] = phase;
  }
  if (options->num_phases == 0) return "at least one phase is needed";
  return NULL;
}

static bool parse_flag(const char* text, bool* value) {
  static const char* const yes[] = {"true", "yes", "1", "on"};
  static const char* const no[] = {"false", "no", "0", "off"};
  for (size_t i = 0; i < 4; ++i) {
    if (strcmp(text, yes[i]) == 0) *value = true;
    if (strcmp(text, no[i]) == 0) *value = false;
    if (strcmp(text, yes[i]) == 0 || strcmp(text, no[i]) == 0) return true;
  }
  return false;
}

// Applies one option with its value; NULL, or why the value is wrong.
static const char* apply_option(int id, const char* value, struct trigger_options* options) {
  int64_t integer = 0;
  const char* why = NULL;
  switch (id) {
    case OPT_RATE:
      options->rate_text = value;
      if (!parse_rate(value, &options->rate_hz)) why = "not a number";
      break;
    case OPT_WIDTH_US:
      options->width_text = value;
      if (!parse_integer(value, 1, INT32_MAX, &options->width_us)) {
        why = "must be a whole number of microseconds > 0";
      }
      break;
    case OPT_COUNT:
      if (!parse_count(value, &options->count)) why = "must be a whole number >= 0";
      break;
    case OPT_LINES:
      options->lines_text = value;
      why = parse_lines(value, options);
      break;
    case OPT_PHASES_US:
      options->phases_text = value;
      why = parse_phases(value, options);
      break;
    case OPT_SPIN_US:
      if (!parse_integer(value, 0, 10000, &options->spin_us)) {
        why = "must be a whole number of microseconds, 0 to 10000";
      }
      break;
    case OPT_CHIP:
      options->chip = value;
      break;
    case OPT_LCM_URL:
      options->lcm_url = value;
      break;
    case OPT_TRIGGER_ID:
      if (!parse_integer(value, 0, INT16_MAX, &integer)) why = "must be 0 to 32767";
      options->trigger_id = (int16_t)integer;
      break;
    case OPT_START_DELAY_MS:
      if (!parse_integer(value, 0, INT32_MAX, &options->start_delay_ms)) {
        why = "must be a whole number of milliseconds >= 0";
      }
      break;
    case OPT_START_LINE:
      if (!parse_integer(value, 0, 65535, &options->start_line)) why = "must be an offset 0..65535";
      break;
    case OPT_STOP_LINE:
      if (!parse_integer(value, 0, 65535, &options->stop_line)) why = "must be an offset 0..65535";
      break;
    case OPT_DEBOUNCE_US:
      if (!parse_integer(value, 0, 10000000, &options->debounce_us)) {
        why = "must be a whole number of microseconds, 0 to 10000000";
      }
      break;
    case OPT_BENCH:
      if (!parse_integer(value, 1, 3600, &options->bench_seconds)) {
        why = "must be a whole number of seconds, 1 to 3600";
      }
      break;
    case OPT_QUIET:
      if (!parse_flag(value, &options->quiet)) why = "must be true or false";
      break;
    default:
      break;
  }
  return why;
}

static const char* option_name(int id) {
  for (const struct option* o = long_options; o->name != NULL; ++o) {
    if (o->val == id) return o->name;
  }
  return "?";
}

// The option an old name stands for, after a one-line notice on stderr (docs/reference/cli.md,
// "Old names"); any other id as it is.
static int current_option(int id, bool as_key) {
  if (id != OPT_RATE_OLD) return id;
  fprintf(stderr, as_key ? "syncap-trigger: key 'rate' is deprecated, use 'rate-hz'\n"
                         : "syncap-trigger: --rate is deprecated, use --rate-hz\n");
  return OPT_RATE;
}

// The option id of a config key (a long option's name), or 0.
static int option_of_key(const char* key) {
  for (const struct option* o = long_options; o->name != NULL; ++o) {
    if (o->val != OPT_HELP && o->val != OPT_CONFIG && strcmp(o->name, key) == 0) return o->val;
  }
  return 0;
}

bool trigger_options_is_key(const char* key) { return option_of_key(key) != 0; }

const char* trigger_options_apply_key(const char* key, const char* value,
                                      struct trigger_options* options) {
  const int id = option_of_key(key);
  if (id == 0) return "not an option of syncap-trigger";
  return apply_option(current_option(id, true), value, options);
}

static bool has_suffix(const char* text, const char* suffix) {
  const size_t n = strlen(text);
  const size_t m = strlen(suffix);
  return n >= m && strcmp(text + n - m, suffix) == 0;
}

static char* trim(char* text) {
  while (isspace((unsigned char)*text)) ++text;
  size_t length = strlen(text);
  while (length > 0 && isspace((unsigned char)text[length - 1])) text[--length] = '\0';
  return text;
}

static char* read_file(const char* path) {
  FILE* file = fopen(path, "r");
  if (file == NULL) return NULL;
  size_t size = 0;
  size_t capacity = 4096;
  char* text = malloc(capacity);
  while (text != NULL) {
    size += fread(text + size, 1, capacity - size - 1, file);
    if (ferror(file) || size < capacity - 1) break;
    capacity *= 2;
    char* bigger = realloc(text, capacity);
    if (bigger == NULL) free(text);
    text = bigger;
  }
  const bool failed = text == NULL || ferror(file);
  const int error = errno;
  fclose(file);
  if (failed) {
    free(text);
    errno = error != 0 ? error : ENOMEM;
    return NULL;
  }
  text[size] = '\0';
  return text;
}

bool trigger_options_load_config(const char* path, struct trigger_options* options, char* error,
                                 size_t size) {
  if (has_suffix(path, ".yaml") || has_suffix(path, ".yml")) {
    return trigger_options_load_yaml(path, options, error, size);
  }
  char* text = read_file(path);
  if (text == NULL) {
    snprintf(error, size, "%s: cannot read: %s", path, strerror(errno));
    return false;
  }
  free(options->config_text);
  options->config_text = text;
  unsigned number = 0;
  char* next = NULL;
  // strtok_r would skip empty lines and so miscount: split by hand.
  for (char* line = text; line != NULL; line = next) {
    ++number;
    char* end = strchr(line, '\n');
    next = end != NULL ? end + 1 : NULL;
    if (end != NULL) *end = '\0';
    char* hash = strchr(line, '#');
    if (hash != NULL) *hash = '\0';
    char* content = trim(line);
    if (content[0] == '\0') continue;
    char* equals = strchr(content, '=');
    if (equals == NULL) {
      snprintf(error, size, "%s:%u: expected 'key = value', got '%s'", path, number, content);
      return false;
    }
    *equals = '\0';
    const char* key = trim(content);
    const char* value = trim(equals + 1);
    const int id = option_of_key(key);
    if (id == 0) {
      snprintf(error, size, "%s:%u: unknown key '%s'", path, number, key);
      return false;
    }
    if (value[0] == '\0') {
      snprintf(error, size, "%s:%u: missing value for '%s'", path, number, key);
      return false;
    }
    const char* why = apply_option(current_option(id, true), value, options);
    if (why != NULL) {
      snprintf(error, size, "%s:%u: invalid %s '%s': %s", path, number, key, value, why);
      return false;
    }
  }
  return true;
}

// The FILE of --config FILE or --config=FILE, the last one given; NULL without.
static const char* find_config(int argc, char** argv) {
  const char* path = NULL;
  for (int i = 1; i < argc; ++i) {
    if (strcmp(argv[i], "--") == 0) break;
    if (strcmp(argv[i], "--config") == 0 && i + 1 < argc) path = argv[++i];
    if (strncmp(argv[i], "--config=", 9) == 0) path = argv[i] + 9;
  }
  return path;
}

static enum trigger_options_result reject_syntax(const char* what, const char* text) {
  fprintf(stderr, "syncap-trigger: %s '%s'\n", what, text);
  trigger_options_usage(stderr);
  return TRIGGER_OPTIONS_INVALID;
}

enum trigger_options_result trigger_options_parse(int argc, char** argv,
                                                  struct trigger_options* options) {
  trigger_options_defaults(options);
  options->config_path = find_config(argc, argv);
  if (options->config_path != NULL) {
    char error[512];
    if (!trigger_options_load_config(options->config_path, options, error, sizeof(error))) {
      fprintf(stderr, "syncap-trigger: %s\n", error);
      return TRIGGER_OPTIONS_INVALID;
    }
  }
  opterr = 0;  // we print our own messages, naming the option
  optind = 1;
  int id = 0;
  while ((id = getopt_long(argc, argv, ":h", long_options, NULL)) != -1) {
    if (id == '?') return reject_syntax("unknown option", argv[optind - 1]);
    if (id == ':') return reject_syntax("missing value for option", argv[optind - 1]);
    if (id == 'h' || id == OPT_HELP) {
      trigger_options_usage(stdout);
      return TRIGGER_OPTIONS_HELP;
    }
    if (id == OPT_CONFIG) continue;  // read first, above
    id = current_option(id, false);
    if (id == OPT_QUIET) {
      options->quiet = true;
      continue;
    }
    const char* why = apply_option(id, optarg, options);
    if (why != NULL) {
      char name[32];
      snprintf(name, sizeof(name), "--%s", option_name(id));
      trigger_options_reject(name, optarg, why);
      return TRIGGER_OPTIONS_INVALID;
    }
  }
  if (optind < argc) return reject_syntax("unexpected argument", argv[optind]);
  return TRIGGER_OPTIONS_RUN;
}
