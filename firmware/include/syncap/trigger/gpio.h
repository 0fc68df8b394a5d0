// Lines of a GPIO chip: outputs driven together, inputs reporting edges. A tiny API after
// libgpiod's chip/line-bulk model. A backend spec picks the chip:
//   "sim", "sim:N", "sim:NAME"   the simulated chips, see gpio_sim.h;
//   "gpiochipN", "/dev/PATH",    a real chip through libgpiod 1.6 (gpiod_chip_open_lookup: by
//   "gpiod:NAME|LABEL|NUMBER"    name, path, label or number), see src/gpio_gpiod.h.
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

// An edge seen on an input line.
struct syncap_gpio_event {
  unsigned line;    // line offset
  int rising;       // 1 rising edge, 0 falling edge
  int64_t time_ns;  // CLOCK_MONOTONIC time of the edge (the kernel's timestamp on real chips)
};

// Opens the chip named by spec, or returns NULL with errno: ENODEV for a spec no backend takes,
// EINVAL for a malformed spec, ENOENT for a chip that does not exist, ENOMEM.
struct syncap_gpio* syncap_gpio_open(const char* spec);

// A sentence naming the chip and what is wrong, for an errno from syncap_gpio_open, e.g.
// "GPIO chip 'gpiochip7' does not exist (looked up by name, path, label and number)". Returns out.
const char* syncap_gpio_describe_open_error(const char* spec, int error, char* out, size_t size);

// Requests lines `offsets` (distinct, 1..SYNCAP_GPIO_MAX_LINES of them) as outputs driven low.
// EBUSY when lines are already requested, EINVAL for bad offsets.
int syncap_gpio_request_outputs(struct syncap_gpio* gpio, const unsigned* offsets, size_t num_lines,
                                const char* consumer);

// Drives every requested line to value (0 low, anything else high) at once. EPERM when no lines
// are requested.
int syncap_gpio_set_all(struct syncap_gpio* gpio, int value);

// Drives the requested lines selected by mask (bit i: the i-th offset of the request) to value
// at once, in one backend call (one bulk set); lines already at that level are left alone. EPERM
// when no lines are requested, EINVAL for a bit beyond the requested lines.
int syncap_gpio_set_lines(struct syncap_gpio* gpio, uint32_t mask, int value);

// Drives the requested lines low and gives them back; the chip stays open. No-op without lines.
void syncap_gpio_release(struct syncap_gpio* gpio);

// Requests lines `offsets` (distinct, 1..SYNCAP_GPIO_MAX_LINES, none of them an output) as inputs
// reporting both edges. EBUSY when inputs are already requested, EINVAL for bad offsets.
int syncap_gpio_request_inputs(struct syncap_gpio* gpio, const unsigned* offsets, size_t num_lines,
                               const char* consumer);

// Waits up to timeout_ns (>= 0) for the next edge on an input line: 1 with *event filled in, 0
// when none came in time, -1 with errno (EPERM without input lines). May run in another thread
// than the output calls; only one thread may wait. The in-process "sim" chip never has edges on
// its inputs; "sim:NAME" reports the rising edges other processes drive on the shared chip.
int syncap_gpio_wait_edge(struct syncap_gpio* gpio, int64_t timeout_ns,
                          struct syncap_gpio_event* event);

// Releases the lines (outputs left low, inputs too) and closes the chip. NULL is allowed.
void syncap_gpio_close(struct syncap_gpio* gpio);

// CLOCK_MONOTONIC time at which the last syncap_gpio_set_all/_set_lines that changed a level
// switched the lines, as the backend saw it (so that it equals the time a shared chip's watchers
// see); 0 before the first change.
int64_t syncap_gpio_last_change_ns(const struct syncap_gpio* gpio);

// The backend's name: "sim" or "gpiod".
const char* syncap_gpio_backend_name(const struct syncap_gpio* gpio);

#ifdef __cplusplus
}
#endif
