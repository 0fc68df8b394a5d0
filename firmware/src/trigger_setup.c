// From syncap-trigger's options to its pulse schedule and its claimed GPIO lines
// (trigger_setup.h), every refusal named by the option or the chip it comes from.
#include "trigger_setup.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "syncap/trigger/gpiosim.h"
#include "trigger_daemon.h"

static const char* option_of(enum syncap_trigger_error error, const struct trigger_options* o,
                             const char** value) {
  switch (error) {
    case SYNCAP_TRIGGER_ERR_RATE_NOT_FINITE:
    case SYNCAP_TRIGGER_ERR_RATE_TOO_LOW:
    case SYNCAP_TRIGGER_ERR_RATE_TOO_HIGH:
      *value = o->rate_text;
      return "--rate-hz";
    case SYNCAP_TRIGGER_ERR_WIDTH_NOT_POSITIVE:
    case SYNCAP_TRIGGER_ERR_WIDTH_NOT_BELOW_PERIOD:
      *value = o->width_text;
      return "--width-us";
    case SYNCAP_TRIGGER_ERR_PHASE_NEGATIVE:
    case SYNCAP_TRIGGER_ERR_PHASE_NOT_BELOW_PERIOD:
    case SYNCAP_TRIGGER_ERR_PHASE_PLUS_WIDTH_BEYOND_PERIOD:
      *value = o->phases_text;
      return "--phases-us";
    case SYNCAP_TRIGGER_ERR_DEBOUNCE_NEGATIVE:
      *value = "(negative)";
      return "--debounce-us";
    default:
      *value = o->lines_text;
      return "--lines";
  }
}

struct syncap_trigger* trigger_setup_create(const struct trigger_options* options, int* status) {
  struct syncap_trigger_config config;
  syncap_trigger_config_init(&config);
  config.rate_hz = options->rate_hz;
  config.pulse_width_ns = options->width_us * 1000;
  config.count = options->count;
  config.num_lines = options->num_lines;
  if (options->num_phases != 0 && options->num_phases != options->num_lines) {
    *status = TRIGGER_DAEMON_USAGE;
    char why[96];
    snprintf(why, sizeof(why), "needs one phase per line (%zu lines, %zu phases)",
             options->num_lines, options->num_phases);
    trigger_options_reject("--phases-us", options->phases_text, why);
    return NULL;
  }
  for (size_t i = 0; i < options->num_phases; ++i)
    config.phase_ns[i] = options->phases_us[i] * 1000;
  config.debounce_ns = options->debounce_us * 1000;
  enum syncap_trigger_error error = SYNCAP_TRIGGER_OK;
  struct syncap_trigger* trigger = syncap_trigger_new(&config, &error);
  if (trigger != NULL) return trigger;
  if (error == SYNCAP_TRIGGER_ERR_NO_MEMORY) {
    *status = TRIGGER_DAEMON_RUNTIME_ERROR;
    fprintf(stderr, "syncap-trigger: %s\n", syncap_trigger_strerror(error));
  } else {
    *status = TRIGGER_DAEMON_USAGE;
    const char* value = NULL;
    const char* option = option_of(error, options, &value);
    trigger_options_reject(option, value, syncap_trigger_strerror(error));
  }
  return NULL;
}

// "sim:NAME" (a name, not a ring size): the chip shared with other processes.
static bool is_shared_sim(const char* chip) {
  return strncmp(chip, "sim:", 4) == 0 && strspn(chip + 4, "0123456789") != strlen(chip + 4);
}

static void describe_chip_error(const char* chip, int error, char* why, size_t size) {
  if (is_shared_sim(chip)) {
    syncap_gpiosim_describe_error(chip + 4, error, why, size);
  } else if (error == EINVAL && strncmp(chip, "sim", 3) == 0) {
    snprintf(why, size,
             "sim:N needs 1 to 1000000 edges, sim:NAME a name of A-Z a-z 0-9 . _ - (at most 64, "
             "not starting with . or -)");
  } else {
    syncap_gpio_describe_open_error(chip, error, why, size);
  }
}

// Why a line request failed, naming the lines and the chip.
static void report_request_error(const struct trigger_options* o, const char* what,
                                 const char* lines, int error, int* status) {
  *status = error == EINVAL ? TRIGGER_DAEMON_USAGE : TRIGGER_DAEMON_RUNTIME_ERROR;
  if (error == EBUSY) {
    fprintf(stderr,
            "syncap-trigger: %s %s on chip '%s' are busy (requested by another program; see "
            "gpioinfo)\n",
            what, lines, o->chip);
  } else if (error == EINVAL) {
    fprintf(stderr,
            "syncap-trigger: cannot request %s %s on chip '%s': the chip has no such line, or a "
            "line is used twice\n",
            what, lines, o->chip);
  } else {
    fprintf(stderr, "syncap-trigger: cannot request %s %s on chip '%s': %s\n", what, lines, o->chip,
            strerror(error));
  }
}

static bool request_inputs(struct syncap_gpio* gpio, const struct trigger_options* o, int* status) {
  unsigned offsets[2];
  size_t count = 0;
  if (o->start_line >= 0) offsets[count++] = (unsigned)o->start_line;
  if (o->stop_line >= 0) offsets[count++] = (unsigned)o->stop_line;
  if (count == 0) return true;
  if (count == 2 && offsets[0] == offsets[1]) {
    *status = TRIGGER_DAEMON_USAGE;
    fprintf(stderr, "syncap-trigger: --start-line and --stop-line must be different lines\n");
    return false;
  }
  if (syncap_gpio_request_inputs(gpio, offsets, count, "syncap-trigger") == 0) return true;
  char lines[32];
  if (count == 1) {
    snprintf(lines, sizeof(lines), "%u", offsets[0]);
  } else {
    snprintf(lines, sizeof(lines), "%u,%u", offsets[0], offsets[1]);
  }
  report_request_error(o, "input lines", lines, errno, status);
  return false;
}

struct syncap_gpio* trigger_setup_open_lines(const struct trigger_options* options, int* status) {
  struct syncap_gpio* gpio = syncap_gpio_open(options->chip);
  if (gpio == NULL) {
    const int error = errno;
    char why[320];
    describe_chip_error(options->chip, error, why, sizeof(why));
    if (error == ENODEV || error == EINVAL || error == ENOENT) {
      *status = TRIGGER_DAEMON_USAGE;
      trigger_options_reject("--chip", options->chip, why);
    } else {
      *status = TRIGGER_DAEMON_RUNTIME_ERROR;
      fprintf(stderr, "syncap-trigger: %s\n", why);
    }
    return NULL;
  }
  if (syncap_gpio_request_outputs(gpio, options->lines, options->num_lines, "syncap-trigger") < 0) {
    report_request_error(options, "lines", options->lines_text, errno, status);
    syncap_gpio_close(gpio);
    return NULL;
  }
  if (!request_inputs(gpio, options, status)) {
    syncap_gpio_close(gpio);
    return NULL;
  }
  return gpio;
}
