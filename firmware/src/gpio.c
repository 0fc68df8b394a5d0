#include "syncap/trigger/gpio.h"

#include <errno.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "gpio_backend.h"

static const struct syncap_gpio_backend* const backends[] = {&syncap_gpio_sim_backend};

// The backend whose name is the spec up to an optional ':'.
static const struct syncap_gpio_backend* find_backend(const char* spec) {
  const size_t name_length = strcspn(spec, ":");
  for (size_t i = 0; i < sizeof(backends) / sizeof(backends[0]); ++i) {
    const char* name = backends[i]->name;
    if (strlen(name) == name_length && strncmp(spec, name, name_length) == 0) return backends[i];
  }
  return NULL;
}

struct syncap_gpio* syncap_gpio_open(const char* spec) {
  const struct syncap_gpio_backend* backend = find_backend(spec);
  if (backend == NULL) {
    errno = ENODEV;
    return NULL;
  }
  struct syncap_gpio* gpio = calloc(1, sizeof(*gpio));
  if (gpio == NULL) return NULL;
  const char* colon = strchr(spec, ':');
  gpio->backend = backend;
  gpio->state = backend->open(colon != NULL ? colon + 1 : NULL);
  if (gpio->state == NULL) {
    const int saved = errno;
    free(gpio);
    errno = saved;
    return NULL;
  }
  return gpio;
}

static bool has_duplicates(const unsigned* offsets, size_t num_lines) {
  for (size_t i = 0; i < num_lines; ++i) {
    for (size_t j = i + 1; j < num_lines; ++j) {
      if (offsets[i] == offsets[j]) return true;
    }
  }
  return false;
}

int syncap_gpio_request_outputs(struct syncap_gpio* gpio, const unsigned* offsets, size_t num_lines,
                                const char* consumer) {
  if (gpio->num_lines > 0) {
    errno = EBUSY;
    return -1;
  }
  if (num_lines == 0 || num_lines > SYNCAP_GPIO_MAX_LINES || has_duplicates(offsets, num_lines)) {
    errno = EINVAL;
    return -1;
  }
  if (gpio->backend->request_outputs(gpio->state, offsets, num_lines, consumer) < 0) return -1;
  memcpy(gpio->offsets, offsets, num_lines * sizeof(offsets[0]));
  gpio->num_lines = num_lines;
  gpio->value = 0;
  return 0;
}

int syncap_gpio_set_all(struct syncap_gpio* gpio, int value) {
  if (gpio->num_lines == 0) {
    errno = EPERM;
    return -1;
  }
  value = value != 0;
  if (value == gpio->value) return 0;
  int64_t time_ns = 0;
  if (gpio->backend->set_all(gpio->state, gpio->offsets, gpio->num_lines, value, &time_ns) < 0) {
    return -1;
  }
  gpio->value = value;
  gpio->last_change_ns = time_ns;
  return 0;
}

void syncap_gpio_release(struct syncap_gpio* gpio) {
  if (gpio->num_lines == 0) return;
  // Best effort: a line that cannot be driven low now cannot be helped by failing the release.
  (void)syncap_gpio_set_all(gpio, 0);
  gpio->backend->release(gpio->state, gpio->offsets, gpio->num_lines);
  gpio->num_lines = 0;
}

void syncap_gpio_close(struct syncap_gpio* gpio) {
  if (gpio == NULL) return;
  syncap_gpio_release(gpio);
  gpio->backend->close(gpio->state);
  free(gpio);
}

const char* syncap_gpio_backend_name(const struct syncap_gpio* gpio) { return gpio->backend->name; }

int64_t syncap_gpio_last_change_ns(const struct syncap_gpio* gpio) { return gpio->last_change_ns; }
