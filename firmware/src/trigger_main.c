// syncap-trigger: drives the camera trigger lines on an absolute CLOCK_MONOTONIC schedule and
// publishes one syncap_trigger_t per pulse. See firmware/README.md.
#include <errno.h>
#include <inttypes.h>
#include <lcm/lcm.h>
#include <sched.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>

#include "syncap/trigger/gpio.h"
#include "syncap/trigger/gpiosim.h"
#include "syncap/trigger/trigger.h"
#include "syncap_trigger_t.h"
#include "trigger_options.h"

// Same name as syncap::proto::kTriggerChannel (proto/include/syncap/proto/channels.hpp).
#define TRIGGER_CHANNEL "SYNCAP_TRIGGER"
#define NS_PER_S INT64_C(1000000000)
#define NS_PER_MS INT64_C(1000000)
// A signal landing between the stop check and clock_nanosleep is only seen when the sleep ends,
// so long sleeps are cut into slices of this length to bound how late a stop can be noticed.
#define STOP_CHECK_NS (50 * NS_PER_MS)
#define RT_PRIORITY 80

_Static_assert(SYNCAP_TRIGGER_FLAG_LATE == SYNCAP_TRIGGER_T_FLAG_LATE, "flag bits differ");
_Static_assert(SYNCAP_TRIGGER_FLAG_MISSED == SYNCAP_TRIGGER_T_FLAG_MISSED, "flag bits differ");
_Static_assert(SYNCAP_TRIGGER_FLAG_LAST == SYNCAP_TRIGGER_T_FLAG_LAST, "flag bits differ");

enum exit_status { STATUS_OK = 0, STATUS_RUNTIME_ERROR = 1, STATUS_USAGE = 2 };

struct daemon {
  const struct trigger_options* options;
  struct syncap_trigger* trigger;
  struct syncap_gpio* gpio;
  lcm_t* lcm;
  bool publish_warned;
};

static volatile sig_atomic_t stop_requested = 0;

static void request_stop(int signal_number) {
  (void)signal_number;
  stop_requested = 1;
}

static void install_signal_handlers(void) {
  struct sigaction action;
  memset(&action, 0, sizeof(action));
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, NULL);
  sigaction(SIGTERM, &action, NULL);
}

static int64_t clock_ns(clockid_t clock) {
  struct timespec now;
  clock_gettime(clock, &now);
  return (int64_t)now.tv_sec * NS_PER_S + now.tv_nsec;
}

// Sleeps until deadline_ns on CLOCK_MONOTONIC. When stoppable, returns false as soon as a stop
// is requested; otherwise sleeps through signals.
static bool sleep_until(int64_t deadline_ns, bool stoppable) {
  for (;;) {
    if (stoppable && stop_requested) return false;
    const int64_t now_ns = clock_ns(CLOCK_MONOTONIC);
    if (now_ns >= deadline_ns) return true;
    int64_t wake_ns = deadline_ns;
    if (stoppable && deadline_ns - now_ns > STOP_CHECK_NS) wake_ns = now_ns + STOP_CHECK_NS;
    const struct timespec wake = {.tv_sec = wake_ns / NS_PER_S, .tv_nsec = wake_ns % NS_PER_S};
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, NULL);  // EINTR: the loop re-checks
  }
}

// SCHED_FIFO and locked memory keep wake-up latency low; without them the trigger still runs,
// only with more jitter, so a refusal is one warning, not an error.
static void enter_realtime(void) {
  const struct sched_param param = {.sched_priority = RT_PRIORITY};
  const int sched_error = sched_setscheduler(0, SCHED_FIFO, &param) == 0 ? 0 : errno;
  const int lock_error = mlockall(MCL_CURRENT | MCL_FUTURE) == 0 ? 0 : errno;
  if (sched_error == 0 && lock_error == 0) return;
  fprintf(stderr,
          "syncap-trigger: warning: running without real-time guarantees (SCHED_FIFO: %s; "
          "mlockall: %s), pulse timing may jitter\n",
          sched_error ? strerror(sched_error) : "ok", lock_error ? strerror(lock_error) : "ok");
}

static void publish_pulse(struct daemon* d, const struct syncap_trigger_pulse* pulse,
                          int64_t edge_ns, int64_t realtime_ns) {
  const syncap_trigger_t message = {
      .frame_number = (int64_t)pulse->index,
      .monotonic_ns = edge_ns,
      .realtime_ns = realtime_ns,
      .rate_hz = d->options->rate_hz,
      .pulse_width_us = (int32_t)d->options->width_us,
      .trigger_id = d->options->trigger_id,
      .flags = (int8_t)pulse->flags,
  };
  if (syncap_trigger_t_publish(d->lcm, TRIGGER_CHANNEL, &message) != 0 && !d->publish_warned) {
    fprintf(stderr, "syncap-trigger: warning: publishing on %s failed (reported once)\n",
            TRIGGER_CHANNEL);
    d->publish_warned = true;
  }
}

static bool set_lines(struct daemon* d, int value) {
  if (syncap_gpio_set_all(d->gpio, value) == 0) return true;
  fprintf(stderr, "syncap-trigger: driving the lines %s failed: %s\n", value ? "high" : "low",
          strerror(errno));
  return false;
}

// One pulse: raise, publish, hold for the width, lower. A pulse once published keeps its full
// width even when a stop arrives meanwhile, so cameras never see a cut-short exposure pulse.
static bool drive_pulse(struct daemon* d) {
  struct syncap_trigger_pulse pulse;
  const int64_t now_ns = clock_ns(CLOCK_MONOTONIC);
  if (syncap_trigger_due_pulse(d->trigger, now_ns, &pulse) != SYNCAP_TRIGGER_OK) return true;
  if (!set_lines(d, 1)) return false;
  // The backend's own edge time: on a shared chip it is exactly the time its watchers see.
  const int64_t edge_ns = syncap_gpio_last_change_ns(d->gpio);
  const int64_t realtime_ns = clock_ns(CLOCK_REALTIME);
  syncap_trigger_edge_driven(d->trigger, &pulse, edge_ns);
  publish_pulse(d, &pulse, edge_ns, realtime_ns);
  sleep_until(pulse.fall_ns, false);
  return set_lines(d, 0);
}

static bool run_pulses(struct daemon* d) {
  const int64_t start_ns = clock_ns(CLOCK_MONOTONIC) + d->options->start_delay_ms * NS_PER_MS;
  syncap_trigger_start(d->trigger, start_ns);
  bool ok = true;
  while (ok && syncap_trigger_state(d->trigger) == SYNCAP_TRIGGER_RUNNING) {
    if (!sleep_until(syncap_trigger_next_rise_ns(d->trigger), true)) break;
    ok = drive_pulse(d);
  }
  if (syncap_trigger_state(d->trigger) == SYNCAP_TRIGGER_RUNNING) syncap_trigger_stop(d->trigger);
  return ok;
}

static const char* option_of(enum syncap_trigger_error error, const struct trigger_options* o,
                             const char** value) {
  switch (error) {
    case SYNCAP_TRIGGER_ERR_RATE_NOT_FINITE:
    case SYNCAP_TRIGGER_ERR_RATE_TOO_LOW:
    case SYNCAP_TRIGGER_ERR_RATE_TOO_HIGH:
      *value = o->rate_text;
      return "--rate";
    case SYNCAP_TRIGGER_ERR_WIDTH_NOT_POSITIVE:
    case SYNCAP_TRIGGER_ERR_WIDTH_NOT_BELOW_PERIOD:
      *value = o->width_text;
      return "--width-us";
    default:
      *value = o->lines_text;
      return "--lines";
  }
}

// The trigger for the options, or NULL after printing why (*status says usage or runtime).
static struct syncap_trigger* create_trigger(const struct trigger_options* options, int* status) {
  struct syncap_trigger_config config;
  syncap_trigger_config_init(&config);
  config.rate_hz = options->rate_hz;
  config.pulse_width_ns = options->width_us * 1000;
  config.count = options->count;
  config.num_lines = options->num_lines;  // phases stay 0: all lines switch together
  enum syncap_trigger_error error = SYNCAP_TRIGGER_OK;
  struct syncap_trigger* trigger = syncap_trigger_new(&config, &error);
  if (trigger != NULL) return trigger;
  if (error == SYNCAP_TRIGGER_ERR_NO_MEMORY) {
    *status = STATUS_RUNTIME_ERROR;
    fprintf(stderr, "syncap-trigger: %s\n", syncap_trigger_strerror(error));
  } else {
    *status = STATUS_USAGE;
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

// The chip with the lines requested, or NULL after printing why (*status says usage or runtime).
static struct syncap_gpio* open_lines(const struct trigger_options* options, int* status) {
  struct syncap_gpio* gpio = syncap_gpio_open(options->chip);
  if (gpio == NULL) {
    *status = errno == ENODEV || errno == EINVAL ? STATUS_USAGE : STATUS_RUNTIME_ERROR;
    if (errno == ENODEV) {
      trigger_options_reject("--chip", options->chip,
                             "unknown chip (this build has sim, sim:N and sim:NAME)");
    } else if (errno == EINVAL) {
      trigger_options_reject("--chip", options->chip,
                             "sim:N needs 1 to 1000000 edges, sim:NAME a name of A-Z a-z 0-9 . _ - "
                             "(at most 64, not starting with . or -)");
    } else if (is_shared_sim(options->chip)) {
      char why[256];
      fprintf(stderr, "syncap-trigger: cannot open chip '%s': %s\n", options->chip,
              syncap_gpiosim_describe_error(options->chip + 4, errno, why, sizeof(why)));
    } else {
      fprintf(stderr, "syncap-trigger: cannot open chip '%s': %s\n", options->chip,
              strerror(errno));
    }
    return NULL;
  }
  if (syncap_gpio_request_outputs(gpio, options->lines, options->num_lines, "syncap-trigger") < 0) {
    *status = errno == EINVAL ? STATUS_USAGE : STATUS_RUNTIME_ERROR;
    fprintf(stderr, "syncap-trigger: cannot request lines %s on chip '%s': %s\n",
            options->lines_text, options->chip, strerror(errno));
    syncap_gpio_close(gpio);
    return NULL;
  }
  return gpio;
}

static void print_start(const struct trigger_options* o) {
  char count[32] = "forever";
  if (o->count > 0) snprintf(count, sizeof(count), "%" PRIu64 " pulses", o->count);
  printf("syncap-trigger: %g Hz, %" PRId64 " us pulses, %s, lines %s on chip %s, first in %" PRId64
         " ms\n",
         o->rate_hz, o->width_us, count, o->lines_text, o->chip, o->start_delay_ms);
  fflush(stdout);
}

static void print_summary(const struct syncap_trigger* trigger) {
  struct syncap_trigger_stats stats;
  syncap_trigger_get_stats(trigger, &stats);
  printf("syncap-trigger: pulses=%" PRIu64 " late=%" PRIu64 " missed=%" PRIu64 "\n", stats.pulses,
         stats.late, stats.missed);
}

static int run_daemon(struct daemon* d) {
  install_signal_handlers();
  enter_realtime();
  if (!d->options->quiet) print_start(d->options);
  const bool ok = run_pulses(d);
  if (!d->options->quiet) print_summary(d->trigger);
  return ok ? STATUS_OK : STATUS_RUNTIME_ERROR;
}

// Creates the trigger, the lines and LCM; STATUS_OK, or the exit status after printing why.
static int set_up(struct daemon* d) {
  int status = STATUS_OK;
  d->trigger = create_trigger(d->options, &status);
  if (d->trigger == NULL) return status;
  d->gpio = open_lines(d->options, &status);
  if (d->gpio == NULL) return status;
  d->lcm = lcm_create(d->options->lcm_url);
  if (d->lcm == NULL) {
    fprintf(stderr, "syncap-trigger: cannot create LCM for '%s'\n",
            d->options->lcm_url ? d->options->lcm_url : "(default)");
    return STATUS_RUNTIME_ERROR;
  }
  return STATUS_OK;
}

static void tear_down(struct daemon* d) {
  syncap_gpio_close(d->gpio);  // leaves every line low
  if (d->lcm != NULL) lcm_destroy(d->lcm);
  syncap_trigger_free(d->trigger);
}

int main(int argc, char** argv) {
  struct trigger_options options;
  switch (trigger_options_parse(argc, argv, &options)) {
    case TRIGGER_OPTIONS_HELP:
      return STATUS_OK;
    case TRIGGER_OPTIONS_INVALID:
      return STATUS_USAGE;
    case TRIGGER_OPTIONS_RUN:
      break;
  }
  struct daemon d = {.options = &options};
  int status = set_up(&d);
  if (status == STATUS_OK) status = run_daemon(&d);
  tear_down(&d);
  return status;
}
