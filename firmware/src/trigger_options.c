#include "trigger_options.h"

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
  OPT_CHIP,
  OPT_LCM_URL,
  OPT_TRIGGER_ID,
  OPT_START_DELAY_MS,
  OPT_QUIET,
  OPT_HELP,
};

static const struct option long_options[] = {
    {"rate", required_argument, NULL, OPT_RATE},
    {"width-us", required_argument, NULL, OPT_WIDTH_US},
    {"count", required_argument, NULL, OPT_COUNT},
    {"lines", required_argument, NULL, OPT_LINES},
    {"chip", required_argument, NULL, OPT_CHIP},
    {"lcm-url", required_argument, NULL, OPT_LCM_URL},
    {"trigger-id", required_argument, NULL, OPT_TRIGGER_ID},
    {"start-delay-ms", required_argument, NULL, OPT_START_DELAY_MS},
    {"quiet", no_argument, NULL, OPT_QUIET},
    {"help", no_argument, NULL, OPT_HELP},
    {NULL, 0, NULL, 0},
};

void trigger_options_usage(FILE* out) {
  fputs(
      "usage: syncap-trigger [OPTIONS]\n"
      "Drives the camera trigger lines and publishes one syncap_trigger_t per pulse on\n"
      "LCM channel SYNCAP_TRIGGER.\n"
      "  --rate HZ            pulse rate, 0.01 to 1000 (default 30)\n"
      "  --width-us US        pulse high time, shorter than the period (default 1000)\n"
      "  --count N            pulses to send, 0 = until SIGINT/SIGTERM (default 0)\n"
      "  --lines L1,L2,...    GPIO line offsets driven together (default 0)\n"
      "  --chip SPEC          GPIO chip: 'sim' (simulated, in-process) or 'sim:NAME'\n"
      "                       (simulated, shared with other processes: "
      "/dev/shm/syncap-gpiosim-NAME)\n"
      "  --lcm-url URL        LCM provider (default: LCM's, udpm://239.255.76.67:7667?ttl=0)\n"
      "  --trigger-id N       id of this trigger module, 0 to 32767 (default 0)\n"
      "  --start-delay-ms MS  wait before the first pulse so subscribers can start (default 0)\n"
      "  --quiet              no start line and no summary\n"
      "  --help               this text\n",
      out);
}

void trigger_options_reject(const char* option, const char* value, const char* why) {
  fprintf(stderr, "syncap-trigger: invalid %s '%s': %s\n", option, value, why);
  trigger_options_usage(stderr);
}

static void set_defaults(struct trigger_options* options) {
  *options = (struct trigger_options){
      .rate_hz = 30.0,
      .rate_text = "30",
      .width_us = 1000,
      .width_text = "1000",
      .count = 0,
      .lines = {0},
      .num_lines = 1,
      .lines_text = "0",
      .chip = "sim",
      .lcm_url = NULL,
      .trigger_id = 0,
      .start_delay_ms = 0,
      .quiet = false,
  };
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

// Applies one option with its value; false (after printing why) when the value is wrong.
static bool apply_option(int id, const char* value, struct trigger_options* options) {
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
    default:
      break;
  }
  if (why == NULL) return true;
  for (const struct option* o = long_options; o->name != NULL; ++o) {
    if (o->val != id) continue;
    char name[32];
    snprintf(name, sizeof(name), "--%s", o->name);
    trigger_options_reject(name, value, why);
  }
  return false;
}

static enum trigger_options_result reject_syntax(const char* what, const char* text) {
  fprintf(stderr, "syncap-trigger: %s '%s'\n", what, text);
  trigger_options_usage(stderr);
  return TRIGGER_OPTIONS_INVALID;
}

enum trigger_options_result trigger_options_parse(int argc, char** argv,
                                                  struct trigger_options* options) {
  set_defaults(options);
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
    if (id == OPT_QUIET) {
      options->quiet = true;
    } else if (!apply_option(id, optarg, options)) {
      return TRIGGER_OPTIONS_INVALID;
    }
  }
  if (optind < argc) return reject_syntax("unexpected argument", argv[optind]);
  return TRIGGER_OPTIONS_RUN;
}
