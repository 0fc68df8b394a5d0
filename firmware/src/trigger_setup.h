// Internal to syncap-trigger: the trigger core and the GPIO lines its options ask for.
#pragma once

#include "syncap/trigger/gpio.h"
#include "syncap/trigger/trigger.h"
#include "trigger_options.h"

// The pulse schedule for the options, or NULL after printing why on stderr (*status: a
// trigger_daemon_status, usage for options the core refuses, runtime when out of memory).
struct syncap_trigger* trigger_setup_create(const struct trigger_options* options, int* status);

// The chip with the output lines (and the start/stop input lines) requested, or NULL after
// printing why (*status: usage for a chip or lines that do not exist, runtime otherwise).
struct syncap_gpio* trigger_setup_open_lines(const struct trigger_options* options, int* status);
