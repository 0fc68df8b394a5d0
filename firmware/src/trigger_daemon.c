// The trigger daemon (trigger_daemon.h): drives the camera trigger lines on an absolute
// CLOCK_MONOTONIC schedule and publishes one syncap_trigger_t per pulse, and a
// syncap_trigger_status_t heartbeat once a second. Optional start/stop input lines start and stop
// runs. See docs/design/trigger.md.
#include "trigger_daemon.h"

#include <errno.h>
#include <inttypes.h>
#include <lcm/lcm.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>

#include "syncap/proto/channels.h"
#include "syncap/trigger/gpio.h"
#include "syncap/trigger/gpiosim.h"
#include "syncap/trigger/trigger.h"
#include "syncap_trigger_status_t.h"
#include "syncap_trigger_t.h"

#define STATUS_PERIOD_NS NS_PER_S
// A heartbeat is not sent when the next rising edge is closer than this, so it never delays one.
#define STATUS_GUARD_NS (2 * NS_PER_MS)
// With input lines, how often the main loop looks at the edges the input thread queued.
#define INPUT_CHECK_NS (5 * NS_PER_MS)
#define INPUT_QUEUE 64
#define NS_PER_S INT64_C(1000000000)
#define NS_PER_MS INT64_C(1000000)
// A signal landing between the stop check and clock_nanosleep is only seen when the sleep ends,
// so long sleeps are cut into slices of this length to bound how late a stop can be noticed.
#define STOP_CHECK_NS (50 * NS_PER_MS)
#define RT_PRIORITY 80

_Static_assert(SYNCAP_TRIGGER_FLAG_LATE == SYNCAP_TRIGGER_T_FLAG_LATE, "flag bits differ");
_Static_assert(SYNCAP_TRIGGER_FLAG_MISSED == SYNCAP_TRIGGER_T_FLAG_MISSED, "flag bits differ");
_Static_assert(SYNCAP_TRIGGER_FLAG_LAST == SYNCAP_TRIGGER_T_FLAG_LAST, "flag bits differ");

enum exit_status {
  STATUS_OK = TRIGGER_DAEMON_OK,
  STATUS_RUNTIME_ERROR = TRIGGER_DAEMON_RUNTIME_ERROR,
  STATUS_USAGE = TRIGGER_DAEMON_USAGE
};

// Rising edges of the input lines, from the input thread to the main loop.
struct input_queue {
  pthread_mutex_t lock;
  struct syncap_gpio_event events[INPUT_QUEUE];
  size_t count;
  int error;  // errno of a failed wait, which ends the input thread
};

struct daemon {
  const struct trigger_options* options;
  struct syncap_trigger* trigger;
  struct syncap_gpio* gpio;
  lcm_t* lcm;  // NULL in bench mode
  bool publish_warned;
  bool status_warned;
  int64_t next_status_ns;
  int64_t last_frame_number;  // -1 before the first pulse of a run
  bool has_inputs;
  struct input_queue inputs;
  pthread_t input_thread;
  atomic_bool input_quit;
  int64_t* bench_errors_ns;  // bench mode: each rising edge's error against its schedule
  size_t bench_count;
  size_t bench_capacity;
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

static void sleep_to(int64_t wake_ns) {
  const struct timespec wake = {.tv_sec = wake_ns / NS_PER_S, .tv_nsec = wake_ns % NS_PER_S};
  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, NULL);  // EINTR: the caller re-checks
}

// Hybrid wait for an edge: clock_nanosleep until spin_ns before edge_ns (the wake-up latency
// falls into that margin), then busy-wait on clock_gettime until edge_ns. Costs up to spin_ns of
// CPU per edge. Returns early only when a signal interrupts the sleep.
static void sleep_to_edge(int64_t edge_ns, int64_t spin_ns) {
  if (spin_ns <= 0) {
    sleep_to(edge_ns);
    return;
  }
  if (clock_ns(CLOCK_MONOTONIC) < edge_ns - spin_ns) {
    sleep_to(edge_ns - spin_ns);
    if (clock_ns(CLOCK_MONOTONIC) < edge_ns - spin_ns) return;  // a signal: the caller re-checks
  }
  while (clock_ns(CLOCK_MONOTONIC) < edge_ns) {
  }
}

// Sleeps through signals until deadline_ns (a later edge of a pulse).
static void sleep_until(int64_t deadline_ns, int64_t spin_ns) {
  while (clock_ns(CLOCK_MONOTONIC) < deadline_ns) sleep_to_edge(deadline_ns, spin_ns);
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

static int8_t status_state(const struct daemon* d) {
  switch (syncap_trigger_state(d->trigger)) {
    case SYNCAP_TRIGGER_IDLE:
      return SYNCAP_TRIGGER_STATUS_T_STATE_IDLE;
    case SYNCAP_TRIGGER_RUNNING:
      return SYNCAP_TRIGGER_STATUS_T_STATE_RUNNING;
    case SYNCAP_TRIGGER_STOPPED:
      break;
  }
  return SYNCAP_TRIGGER_STATUS_T_STATE_STOPPED;
}

static void publish_status(struct daemon* d, int8_t state, const char* text) {
  if (d->lcm == NULL) return;
  struct syncap_trigger_stats stats;
  syncap_trigger_get_stats(d->trigger, &stats);
  char message[SYNCAP_TRIGGER_STATUS_T_MAX_MESSAGE + 1];
  snprintf(message, sizeof(message), "%s", text);  // cut to MAX_MESSAGE
  const syncap_trigger_status_t status = {
      .trigger_id = d->options->trigger_id,
      .state = state,
      .monotonic_ns = clock_ns(CLOCK_MONOTONIC),
      .realtime_ns = clock_ns(CLOCK_REALTIME),
      .pulses = (int64_t)stats.pulses,
      .late = (int64_t)stats.late,
      .missed = (int64_t)stats.missed,
      .last_frame_number = d->last_frame_number,
      .rate_hz = d->options->rate_hz,
      .message = message,
  };
  if (syncap_trigger_status_t_publish(d->lcm, SYNCAP_CHANNEL_TRIGGER_STATUS, &status) != 0 &&
      !d->status_warned) {
    fprintf(stderr, "syncap-trigger: warning: publishing on %s failed (reported once)\n",
            SYNCAP_CHANNEL_TRIGGER_STATUS);
    d->status_warned = true;
  }
}

// The heartbeat, when due and not too close to the next edge (deadline_ns, or 0 for none).
static void heartbeat(struct daemon* d, int64_t now_ns, int64_t deadline_ns) {
  if (now_ns < d->next_status_ns) return;
  if (deadline_ns != 0 && deadline_ns - now_ns < STATUS_GUARD_NS) return;
  publish_status(d, status_state(d), "");
  d->next_status_ns = now_ns + STATUS_PERIOD_NS;
}

static void* input_thread_main(void* argument) {
  struct daemon* d = argument;
  while (!atomic_load(&d->input_quit)) {
    struct syncap_gpio_event event;
    const int got = syncap_gpio_wait_edge(d->gpio, 100 * NS_PER_MS, &event);
    if (got == 0 || (got == 1 && !event.rising)) continue;
    pthread_mutex_lock(&d->inputs.lock);
    if (got < 0) {
      d->inputs.error = errno;
    } else if (d->inputs.count < INPUT_QUEUE) {
      d->inputs.events[d->inputs.count++] = event;
    }
    pthread_mutex_unlock(&d->inputs.lock);
    if (got < 0) break;
  }
  return NULL;
}

// Feeds the queued input edges to the trigger core (debounce, start, stop). false when the input
// thread failed.
static bool handle_inputs(struct daemon* d) {
  if (!d->has_inputs) return true;
  struct syncap_gpio_event events[INPUT_QUEUE];
  pthread_mutex_lock(&d->inputs.lock);
  const size_t count = d->inputs.count;
  const int error = d->inputs.error;
  memcpy(events, d->inputs.events, count * sizeof(events[0]));
  d->inputs.count = 0;
  pthread_mutex_unlock(&d->inputs.lock);
  for (size_t i = 0; i < count; ++i) {
    const bool is_start =
        d->options->start_line >= 0 && events[i].line == (unsigned)d->options->start_line;
    const int64_t start_ns = clock_ns(CLOCK_MONOTONIC) + d->options->start_delay_ms * NS_PER_MS;
    const enum syncap_trigger_input_action action = syncap_trigger_input_edge(
        d->trigger, is_start ? SYNCAP_TRIGGER_INPUT_START : SYNCAP_TRIGGER_INPUT_STOP,
        events[i].time_ns, start_ns);
    if (action == SYNCAP_TRIGGER_INPUT_STARTED) d->last_frame_number = -1;
    if (action == SYNCAP_TRIGGER_INPUT_STARTED || action == SYNCAP_TRIGGER_INPUT_STOPPED) {
      // A stop ends the run after the last pulse already driven (published without LAST, since
      // nobody knew then): the STOPPED heartbeat sent now carries it as last_frame_number.
      if (!d->options->quiet && is_start) {
        printf("syncap-trigger: started by line %u\n", events[i].line);
      } else if (!d->options->quiet) {
        printf("syncap-trigger: stopped by line %u after frame %" PRId64 "\n", events[i].line,
               d->last_frame_number);
      }
      fflush(stdout);
      d->next_status_ns = 0;  // announce the change at once
    }
  }
  if (error == 0) return true;
  fprintf(stderr, "syncap-trigger: waiting for input edges failed: %s\n", strerror(error));
  return false;
}

enum wait_result { WAIT_REACHED, WAIT_SIGNAL, WAIT_CHANGED, WAIT_FAILED };

// Sleeps until deadline_ns in slices, looking at signals, input edges and the heartbeat between
// them. WAIT_CHANGED when an input changed the run state.
static enum wait_result wait_until(struct daemon* d, int64_t deadline_ns) {
  const enum syncap_trigger_state state = syncap_trigger_state(d->trigger);
  const int64_t slice_ns = d->has_inputs ? INPUT_CHECK_NS : STOP_CHECK_NS;
  for (;;) {
    if (stop_requested) return WAIT_SIGNAL;
    if (!handle_inputs(d)) return WAIT_FAILED;
    if (syncap_trigger_state(d->trigger) != state) return WAIT_CHANGED;
    const int64_t now_ns = clock_ns(CLOCK_MONOTONIC);
    if (now_ns >= deadline_ns) return WAIT_REACHED;
    heartbeat(d, now_ns, deadline_ns);
    int64_t wake_ns = deadline_ns;
    if (deadline_ns - now_ns > slice_ns) wake_ns = now_ns + slice_ns;
    if (d->next_status_ns > now_ns && d->next_status_ns < wake_ns) wake_ns = d->next_status_ns;
    if (wake_ns == deadline_ns) {
      sleep_to_edge(deadline_ns, d->options->spin_us * 1000);
    } else {
      sleep_to(wake_ns);
    }
  }
}

static void bench_record(struct daemon* d, int64_t error_ns) {
  if (d->bench_count == d->bench_capacity) return;
  d->bench_errors_ns[d->bench_count++] = error_ns;
}

static void publish_pulse(struct daemon* d, const struct syncap_trigger_pulse* pulse,
                          int64_t edge_ns, int64_t realtime_ns) {
  if (d->lcm == NULL) return;
  const syncap_trigger_t message = {
      .frame_number = (int64_t)pulse->index,
      .monotonic_ns = edge_ns,
      .realtime_ns = realtime_ns,
      .rate_hz = d->options->rate_hz,
      .pulse_width_us = (int32_t)d->options->width_us,
      .trigger_id = d->options->trigger_id,
      .flags = (int8_t)pulse->flags,
  };
  if (syncap_trigger_t_publish(d->lcm, SYNCAP_CHANNEL_TRIGGER, &message) != 0 &&
      !d->publish_warned) {
    fprintf(stderr, "syncap-trigger: warning: publishing on %s failed (reported once)\n",
            SYNCAP_CHANNEL_TRIGGER);
    d->publish_warned = true;
  }
}

static bool set_lines(struct daemon* d, uint32_t lines, int value) {
  if (syncap_gpio_set_lines(d->gpio, lines, value) == 0) return true;
  fprintf(stderr, "syncap-trigger: driving the lines %s failed: %s\n", value ? "high" : "low",
          strerror(errno));
  return false;
}

// One pulse: its edge events in time order (syncap_trigger_pulse_events), each line rising at its
// phase and falling a width later. The first event is the rising edge of the lines with the
// smallest phase: the message is published right after it, with that edge's time. A pulse once
// published is driven to its end even when a stop arrives meanwhile, so cameras never see a
// cut-short exposure pulse.
static bool drive_pulse(struct daemon* d) {
  struct syncap_trigger_pulse pulse;
  const int64_t now_ns = clock_ns(CLOCK_MONOTONIC);
  if (syncap_trigger_due_pulse(d->trigger, now_ns, &pulse) != SYNCAP_TRIGGER_OK) return true;
  struct syncap_trigger_event events[SYNCAP_TRIGGER_MAX_EVENTS];
  const size_t count = syncap_trigger_pulse_events(d->trigger, pulse.index, events);
  const int64_t spin_ns = d->options->spin_us * 1000;
  for (size_t i = 0; i < count; ++i) {
    if (i > 0) sleep_until(events[i].time_ns, spin_ns);
    if (!set_lines(d, events[i].lines, events[i].level)) return false;
    if (i > 0) continue;
    // The backend's own edge time: on a shared chip it is exactly the time its watchers see.
    const int64_t edge_ns = syncap_gpio_last_change_ns(d->gpio);
    const int64_t realtime_ns = clock_ns(CLOCK_REALTIME);
    syncap_trigger_edge_driven(d->trigger, &pulse, edge_ns);
    d->last_frame_number = (int64_t)pulse.index;
    if (d->bench_errors_ns != NULL) bench_record(d, edge_ns - pulse.rise_ns);
    publish_pulse(d, &pulse, edge_ns, realtime_ns);
  }
  return true;
}

// Runs until a signal, a failure, or (without a start line) the end of the first run. With a
// start line, each run waits for its start edge, and the daemon waits for the next one after.
static bool run_pulses(struct daemon* d) {
  const bool has_start_line = d->options->start_line >= 0;
  if (!has_start_line) {
    syncap_trigger_start(d->trigger,
                         clock_ns(CLOCK_MONOTONIC) + d->options->start_delay_ms * NS_PER_MS);
  }
  for (;;) {
    const bool running = syncap_trigger_state(d->trigger) == SYNCAP_TRIGGER_RUNNING;
    if (!running && !has_start_line) break;
    // Not running: wait for a start edge in slices (the deadline is never reached).
    const int64_t deadline_ns =
        running ? syncap_trigger_next_rise_ns(d->trigger) : clock_ns(CLOCK_MONOTONIC) + NS_PER_S;
    const enum wait_result waited = wait_until(d, deadline_ns);
    if (waited == WAIT_SIGNAL) break;
    if (waited == WAIT_FAILED) return false;
    if (waited == WAIT_CHANGED || !running) continue;
    if (!drive_pulse(d)) return false;
  }
  if (syncap_trigger_state(d->trigger) == SYNCAP_TRIGGER_RUNNING) syncap_trigger_stop(d->trigger);
  return true;
}

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

// The trigger for the options, or NULL after printing why (*status says usage or runtime).
static struct syncap_trigger* create_trigger(const struct trigger_options* options, int* status) {
  struct syncap_trigger_config config;
  syncap_trigger_config_init(&config);
  config.rate_hz = options->rate_hz;
  config.pulse_width_ns = options->width_us * 1000;
  config.count = options->count;
  config.num_lines = options->num_lines;
  if (options->num_phases != 0 && options->num_phases != options->num_lines) {
    *status = STATUS_USAGE;
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
  *status = error == EINVAL ? STATUS_USAGE : STATUS_RUNTIME_ERROR;
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
    *status = STATUS_USAGE;
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

// The chip with the lines requested, or NULL after printing why (*status says usage or runtime).
static struct syncap_gpio* open_lines(const struct trigger_options* options, int* status) {
  struct syncap_gpio* gpio = syncap_gpio_open(options->chip);
  if (gpio == NULL) {
    const int error = errno;
    char why[320];
    describe_chip_error(options->chip, error, why, sizeof(why));
    if (error == ENODEV || error == EINVAL || error == ENOENT) {
      *status = STATUS_USAGE;
      trigger_options_reject("--chip", options->chip, why);
    } else {
      *status = STATUS_RUNTIME_ERROR;
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

static int compare_ns(const void* a, const void* b) {
  const int64_t x = *(const int64_t*)a;
  const int64_t y = *(const int64_t*)b;
  return (x > y) - (x < y);
}

// Nearest-rank percentile of sorted values.
static int64_t percentile(const int64_t* sorted, size_t count, double p) {
  size_t rank = (size_t)(p / 100.0 * (double)count + 0.999999);
  if (rank < 1) rank = 1;
  if (rank > count) rank = count;
  return sorted[rank - 1];
}

static void print_bench(struct daemon* d) {
  struct syncap_trigger_stats stats;
  syncap_trigger_get_stats(d->trigger, &stats);
  if (d->bench_count == 0) {
    printf("syncap-trigger: bench: no pulses\n");
    return;
  }
  qsort(d->bench_errors_ns, d->bench_count, sizeof(int64_t), compare_ns);
  printf(
      "syncap-trigger: bench %g Hz, %zu edges on chip %s: rising-edge error p50 %.1f us, "
      "p99 %.1f us, max %.1f us (late=%" PRIu64 " missed=%" PRIu64 ")\n",
      d->options->rate_hz, d->bench_count, d->options->chip,
      (double)percentile(d->bench_errors_ns, d->bench_count, 50.0) / 1000.0,
      (double)percentile(d->bench_errors_ns, d->bench_count, 99.0) / 1000.0,
      (double)d->bench_errors_ns[d->bench_count - 1] / 1000.0, stats.late, stats.missed);
}

static bool start_input_thread(struct daemon* d) {
  if (d->options->start_line < 0 && d->options->stop_line < 0) return true;
  pthread_mutex_init(&d->inputs.lock, NULL);
  atomic_store(&d->input_quit, false);
  const int error = pthread_create(&d->input_thread, NULL, input_thread_main, d);
  if (error != 0) {
    fprintf(stderr, "syncap-trigger: cannot start the input thread: %s\n", strerror(error));
    pthread_mutex_destroy(&d->inputs.lock);
    return false;
  }
  d->has_inputs = true;
  return true;
}

static void stop_input_thread(struct daemon* d) {
  if (!d->has_inputs) return;
  atomic_store(&d->input_quit, true);
  pthread_join(d->input_thread, NULL);
  pthread_mutex_destroy(&d->inputs.lock);
  d->has_inputs = false;
}

static int run_daemon(struct daemon* d, const struct trigger_daemon_settings* settings) {
  if (settings->signals) install_signal_handlers();
  // Before enter_realtime: the input thread keeps ordinary scheduling (the kernel stamps edges).
  if (!start_input_thread(d)) return STATUS_RUNTIME_ERROR;
  if (settings->realtime) enter_realtime();
  if (!d->options->quiet) print_start(d->options);
  d->last_frame_number = -1;
  const bool ok = run_pulses(d);
  stop_input_thread(d);
  if (d->bench_errors_ns != NULL) {
    print_bench(d);
  } else if (!d->options->quiet) {
    print_summary(d->trigger);
  }
  // The final heartbeat: STOPPED, or ERROR after a failure.
  publish_status(d,
                 ok ? SYNCAP_TRIGGER_STATUS_T_STATE_STOPPED : SYNCAP_TRIGGER_STATUS_T_STATE_ERROR,
                 ok ? "exiting" : "runtime failure (GPIO), see the daemon's log");
  return ok ? STATUS_OK : STATUS_RUNTIME_ERROR;
}

// Creates the trigger, the lines and LCM; STATUS_OK, or the exit status after printing why.
static int set_up(struct daemon* d) {
  int status = STATUS_OK;
  d->trigger = create_trigger(d->options, &status);
  if (d->trigger == NULL) return status;
  d->gpio = open_lines(d->options, &status);
  if (d->gpio == NULL) return status;
  if (d->options->bench_seconds > 0) {
    // Bench: no LCM; room for every pulse of the run (count = rate * seconds).
    d->bench_capacity = (size_t)(d->options->rate_hz * (double)d->options->bench_seconds) + 1;
    d->bench_errors_ns = calloc(d->bench_capacity, sizeof(int64_t));
    if (d->bench_errors_ns == NULL) {
      fprintf(stderr, "syncap-trigger: out of memory\n");
      return STATUS_RUNTIME_ERROR;
    }
    return STATUS_OK;
  }
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
  free(d->bench_errors_ns);
}

void trigger_daemon_request_stop(void) { stop_requested = 1; }

int trigger_daemon_run(const struct trigger_options* options,
                       const struct trigger_daemon_settings* settings) {
  stop_requested = 0;
  struct daemon d = {.options = options};
  int status = set_up(&d);
  if (status == STATUS_OK) status = run_daemon(&d, settings);
  tear_down(&d);
  return status;
}
