// The trigger daemon in process (firmware/src/trigger_daemon.h): a count run on a private
// simulated chip publishes one trigger_t per pulse (frame numbers 0..N-1, the rate, the last
// flagged) and the heartbeats, into an LCM log (LCM's file provider), and returns 0; a chip that
// does not exist is refused, named, before any pulse.
#include "cmocka_main.h"

#include <lcm/eventlog.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "syncap/proto/channels.h"
#include "syncap_trigger_t.h"
#include "trigger_daemon.h"

static const struct trigger_daemon_settings kInProcess = {.realtime = false, .signals = false};

static enum trigger_options_result parse(char** args, struct trigger_options* options) {
  char* argv[32] = {"syncap-trigger"};
  int argc = 1;
  for (; args[argc - 1] != NULL && argc < 31; ++argc) argv[argc] = args[argc - 1];
  return trigger_options_parse(argc, argv, options);
}

struct published {
  int triggers;
  int statuses;
  int64_t frames[16];
  int8_t last_flags;
  double rate_hz;
};

static void read_log(const char* path, struct published* p) {
  memset(p, 0, sizeof *p);
  lcm_eventlog_t* log = lcm_eventlog_create(path, "r");
  assert_non_null(log);
  for (lcm_eventlog_event_t* e; (e = lcm_eventlog_read_next_event(log)) != NULL;
       lcm_eventlog_free_event(e)) {
    if (strcmp(e->channel, SYNCAP_CHANNEL_TRIGGER_STATUS) == 0) ++p->statuses;
    if (strcmp(e->channel, SYNCAP_CHANNEL_TRIGGER) != 0) continue;
    syncap_trigger_t t;
    assert_true(syncap_trigger_t_decode(e->data, 0, e->datalen, &t) >= 0);
    if (p->triggers < 16) p->frames[p->triggers] = t.frame_number;
    p->last_flags = t.flags;
    p->rate_hz = t.rate_hz;
    ++p->triggers;
    syncap_trigger_t_decode_cleanup(&t);
  }
  lcm_eventlog_destroy(log);
}

static void a_count_run_publishes_every_pulse_and_ends_with_the_last(void** state) {
  (void)state;
  char path[] = "/tmp/syncap-trigger-daemon-XXXXXX";
  const int fd = mkstemp(path);
  assert_true(fd >= 0);
  close(fd);
  char url[128];
  snprintf(url, sizeof url, "file://%s?mode=w", path);
  struct trigger_options options;
  assert_int_equal(parse((char*[]){"--chip", "sim", "--lines", "0,1", "--rate-hz", "200", "--count",
                                   "5", "--width-us", "100", "--start-delay-ms", "0", "--lcm-url",
                                   url, "--quiet", NULL},
                         &options),
                   TRIGGER_OPTIONS_RUN);
  assert_int_equal(trigger_daemon_run(&options, &kInProcess), TRIGGER_DAEMON_OK);
  trigger_options_free(&options);
  struct published p;
  read_log(path, &p);
  unlink(path);
  assert_int_equal(p.triggers, 5);
  for (int i = 0; i < 5; ++i) assert_int_equal(p.frames[i], i);
  assert_true(p.last_flags & SYNCAP_TRIGGER_T_FLAG_LAST);
  assert_true(p.rate_hz == 200.0);
  assert_true(p.statuses >= 1);  // the final heartbeat at least
}

static void a_chip_that_does_not_exist_is_refused_before_any_pulse(void** state) {
  (void)state;
  struct trigger_options options;
  assert_int_equal(parse((char*[]){"--chip", "/dev/gpiochip-none", "--lines", "0", "--count", "3",
                                   "--lcm-url", "memq://", "--quiet", NULL},
                         &options),
                   TRIGGER_OPTIONS_RUN);
  assert_int_not_equal(trigger_daemon_run(&options, &kInProcess), TRIGGER_DAEMON_OK);
  trigger_options_free(&options);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_count_run_publishes_every_pulse_and_ends_with_the_last),
    cmocka_unit_test(a_chip_that_does_not_exist_is_refused_before_any_pulse),
};

SYNCAP_CMOCKA_MAIN(tests)
