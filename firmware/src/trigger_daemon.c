// The trigger daemon (trigger_daemon.h): drives the camera trigger lines on an absolute
// CLOCK_MONOTONIC schedule and publishes one syncap_trigger_t per pulse, and a
// syncap_trigger_status_t heartbeat once a second. Optional start/stop input lines start and stop
// runs. See docs/design/trigger.md. The options become a trigger and lines in trigger_setup.c;
// --bench records its edges in trigger_bench.c.
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
#include "syncap/trigger/trigger.h"
#include "syncap_trigger_status_t.h"
#include "syncap_trigger_t.h"
#include "trigger_bench.h"
#include "trigger_setup.h"

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
  struct trigger_bench bench;  // bench mode: each rising edge's error (errors_ns NULL otherwise)
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
    if (d->bench.errors_ns != NULL) trigger_bench_record(&d->bench, edge_ns - pulse.rise_ns);
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
  if (d->bench.errors_ns != NULL) {
    trigger_bench_print(&d->bench, d->options, d->trigger);
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
  d->trigger = trigger_setup_create(d->options, &status);
  if (d->trigger == NULL) return status;
  d->gpio = trigger_setup_open_lines(d->options, &status);
  if (d->gpio == NULL) return status;
  if (d->options->bench_seconds > 0) {
    // Bench: no LCM.
    if (!trigger_bench_init(&d->bench, d->options->rate_hz, d->options->bench_seconds)) {
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
  trigger_bench_free(&d->bench);
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
