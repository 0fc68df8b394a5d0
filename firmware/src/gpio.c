#include "syncap/trigger/gpio.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpio_backend.h"

static const struct syncap_gpio_backend* const backends[] = {&syncap_gpio_sim_backend,
                                                             &syncap_gpio_gpiod_backend};

// The backend whose name is the spec up to an optional ':', with the argument after the ':'.
// "gpiochipN..." and "/..." are libgpiod chips given whole (gpiod_chip_open_lookup's forms).
static const struct syncap_gpio_backend* find_backend(const char* spec, const char** argument) {
  if (strncmp(spec, "gpiochip", 8) == 0 || spec[0] == '/') {
    *argument = spec;
    return &syncap_gpio_gpiod_backend;
  }
  const size_t name_length = strcspn(spec, ":");
  const char* colon = strchr(spec, ':');
  *argument = colon != NULL ? colon + 1 : NULL;
  for (size_t i = 0; i < sizeof(backends) / sizeof(backends[0]); ++i) {
    const char* name = backends[i]->name;
    if (strlen(name) == name_length && strncmp(spec, name, name_length) == 0) return backends[i];
  }
  return NULL;
}

struct syncap_gpio* syncap_gpio_open(const char* spec) {
  const char* argument = NULL;
  const struct syncap_gpio_backend* backend = find_backend(spec, &argument);
  if (backend == NULL) {
    errno = ENODEV;
    return NULL;
  }
  struct syncap_gpio* gpio = calloc(1, sizeof(*gpio));
  if (gpio == NULL) return NULL;
  gpio->backend = backend;
  gpio->state = backend->open(argument);
  if (gpio->state == NULL) {
    const int saved = errno;
    free(gpio);
    errno = saved;
    return NULL;
  }
  return gpio;
}

const char* syncap_gpio_describe_open_error(const char* spec, int error, char* out, size_t size) {
  switch (error) {
    case ENODEV:
      snprintf(out, size,
               "unknown GPIO chip '%s' (use sim, sim:N, sim:NAME, gpiochipN, /dev/gpiochipN or "
               "gpiod:NAME|LABEL|NUMBER)",
               spec);
      break;
    case ENOENT:
      snprintf(out, size,
               "GPIO chip '%s' does not exist (looked up by name, path, label and number)", spec);
      break;
    case EACCES:
    case EPERM:
      snprintf(out, size, "no permission to open GPIO chip '%s' (%s)", spec, strerror(error));
      break;
    default:
      snprintf(out, size, "cannot open GPIO chip '%s': %s", spec, strerror(error));
      break;
  }
  return out;
}

static bool has_duplicates(const unsigned* offsets, size_t num_lines) {
  for (size_t i = 0; i < num_lines; ++i) {
    for (size_t j = i + 1; j < num_lines; ++j) {
      if (offsets[i] == offsets[j]) return true;
    }
  }
  return false;
}

// Checks a request for lines of one direction: EBUSY when that direction already has lines
// (`already`), EINVAL for no lines, too many, a duplicate, or a line the other direction holds.
static int check_new_lines(size_t already, const unsigned* offsets, size_t num_lines,
                           const unsigned* other, size_t num_other) {
  if (already > 0) {
    errno = EBUSY;
    return -1;
  }
  if (num_lines == 0 || num_lines > SYNCAP_GPIO_MAX_LINES || has_duplicates(offsets, num_lines)) {
    errno = EINVAL;
    return -1;
  }
  for (size_t i = 0; i < num_lines; ++i) {
    for (size_t j = 0; j < num_other; ++j) {
      if (offsets[i] == other[j]) {
        errno = EINVAL;
        return -1;
      }
    }
  }
  return 0;
}

int syncap_gpio_request_outputs(struct syncap_gpio* gpio, const unsigned* offsets, size_t num_lines,
                                const char* consumer) {
  if (check_new_lines(gpio->num_lines, offsets, num_lines, gpio->inputs, gpio->num_inputs) < 0) {
    return -1;
  }
  if (gpio->backend->request_outputs(gpio->state, offsets, num_lines, consumer) < 0) return -1;
  memcpy(gpio->offsets, offsets, num_lines * sizeof(offsets[0]));
  gpio->num_lines = num_lines;
  gpio->high = 0;
  return 0;
}

static uint32_t all_lines(const struct syncap_gpio* gpio) {
  return gpio->num_lines == 32 ? UINT32_MAX : (UINT32_C(1) << gpio->num_lines) - 1;
}

int syncap_gpio_set_lines(struct syncap_gpio* gpio, uint32_t mask, int value) {
  if (gpio->num_lines == 0) {
    errno = EPERM;
    return -1;
  }
  if ((mask & ~all_lines(gpio)) != 0) {
    errno = EINVAL;
    return -1;
  }
  value = value != 0;
  const uint32_t change = value ? mask & ~gpio->high : mask & gpio->high;
  if (change == 0) return 0;
  unsigned offsets[SYNCAP_GPIO_MAX_LINES];
  size_t count = 0;
  for (size_t i = 0; i < gpio->num_lines; ++i) {
    if (change & (UINT32_C(1) << i)) offsets[count++] = gpio->offsets[i];
  }
  int64_t time_ns = 0;
  if (gpio->backend->set_all(gpio->state, offsets, count, value, &time_ns) < 0) return -1;
  gpio->high = value ? gpio->high | change : gpio->high & ~change;
  gpio->last_change_ns = time_ns;
  return 0;
}

int syncap_gpio_set_all(struct syncap_gpio* gpio, int value) {
  if (gpio->num_lines == 0) {
    errno = EPERM;
    return -1;
  }
  return syncap_gpio_set_lines(gpio, all_lines(gpio), value);
}

void syncap_gpio_release(struct syncap_gpio* gpio) {
  if (gpio->num_lines == 0) return;
  // Best effort: a line that cannot be driven low now cannot be helped by failing the release.
  (void)syncap_gpio_set_all(gpio, 0);
  gpio->backend->release(gpio->state, gpio->offsets, gpio->num_lines);
  gpio->num_lines = 0;
}

int syncap_gpio_request_inputs(struct syncap_gpio* gpio, const unsigned* offsets, size_t num_lines,
                               const char* consumer) {
  if (check_new_lines(gpio->num_inputs, offsets, num_lines, gpio->offsets, gpio->num_lines) < 0) {
    return -1;
  }
  if (gpio->backend->request_inputs(gpio->state, offsets, num_lines, consumer) < 0) return -1;
  memcpy(gpio->inputs, offsets, num_lines * sizeof(offsets[0]));
  gpio->num_inputs = num_lines;
  return 0;
}

int syncap_gpio_wait_edge(struct syncap_gpio* gpio, int64_t timeout_ns,
                          struct syncap_gpio_event* event) {
  if (gpio->num_inputs == 0) {
    errno = EPERM;
    return -1;
  }
  if (timeout_ns < 0) timeout_ns = 0;
  return gpio->backend->wait_edge(gpio->state, gpio->inputs, gpio->num_inputs, timeout_ns, event);
}

void syncap_gpio_close(struct syncap_gpio* gpio) {
  if (gpio == NULL) return;
  syncap_gpio_release(gpio);
  if (gpio->num_inputs > 0) {
    gpio->backend->release_inputs(gpio->state, gpio->inputs, gpio->num_inputs);
    gpio->num_inputs = 0;
  }
  gpio->backend->close(gpio->state);
  free(gpio);
}

const char* syncap_gpio_backend_name(const struct syncap_gpio* gpio) { return gpio->backend->name; }

int64_t syncap_gpio_last_change_ns(const struct syncap_gpio* gpio) { return gpio->last_change_ns; }
