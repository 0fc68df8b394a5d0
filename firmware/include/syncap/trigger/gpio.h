// Output lines of a GPIO chip, driven together: a tiny API after libgpiod's chip/line-bulk model.
// A backend spec picks the chip: "sim" (in-process simulation) and "sim:NAME" (the simulated chip
// shared with other processes, gpiosim.h) are the ones in this build, see gpio_sim.h; a libgpiod
// backend ("gpiochip0", "/dev/gpiochip0") slots in behind the same calls.
// Functions returning int give 0, or -1 with errno set.
#pragma once

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SYNCAP_GPIO_MAX_LINES 32

// An open chip and, once requested, its output lines.
struct syncap_gpio;

// Opens the chip named by spec, or returns NULL with errno: ENODEV for a backend this build does
// not have, EINVAL for a malformed spec, ENOMEM.
struct syncap_gpio* syncap_gpio_open(const char* spec);

// Requests lines `offsets` (distinct, 1..SYNCAP_GPIO_MAX_LINES of them) as outputs driven low.
// EBUSY when lines are already requested, EINVAL for bad offsets.
int syncap_gpio_request_outputs(struct syncap_gpio* gpio, const unsigned* offsets, size_t num_lines,
                                const char* consumer);

// Drives every requested line to value (0 low, anything else high) at once. EPERM when no lines
// are requested.
int syncap_gpio_set_all(struct syncap_gpio* gpio, int value);

// Drives the requested lines low and gives them back; the chip stays open. No-op without lines.
void syncap_gpio_release(struct syncap_gpio* gpio);

// Releases the lines (so they are left low) and closes the chip. NULL is allowed.
void syncap_gpio_close(struct syncap_gpio* gpio);

// CLOCK_MONOTONIC time at which the last syncap_gpio_set_all that changed the level switched the
// lines, as the backend saw it (so that it equals the time a shared chip's watchers see); 0 before
// the first change.
int64_t syncap_gpio_last_change_ns(const struct syncap_gpio* gpio);

// The backend's name, e.g. "sim".
const char* syncap_gpio_backend_name(const struct syncap_gpio* gpio);

#ifdef __cplusplus
}
#endif
