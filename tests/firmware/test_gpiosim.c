// The shared simulated GPIO chip (gpiosim.h): names and errors, state shared between mappings and
// processes, runs, and watchers that see every rising edge once, in order, with its exact time,
// from another thread or another process; timeouts; the "sim:NAME" GPIO backend on top of it.
// Every case uses its own chip name (with the pid) and removes it again.
#include "cmocka_main.h"

#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "syncap/trigger/gpio.h"
#include "syncap/trigger/gpiosim.h"

#define EDGES 1000
#define NS_PER_MS INT64_C(1000000)

struct chip_fixture {
  char name[64];
  struct syncap_gpiosim* chip;
};

static int64_t monotonic_ns(void) {
  struct timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  return (int64_t)now.tv_sec * 1000000000 + now.tv_nsec;
}

static void sleep_us(long us) {
  const struct timespec pause = {.tv_sec = us / 1000000, .tv_nsec = (us % 1000000) * 1000};
  nanosleep(&pause, NULL);
}

static int set_up_chip(void** state) {
  static struct chip_fixture fixture;
  static unsigned serial = 0;
  snprintf(fixture.name, sizeof(fixture.name), "test-%ld-%u", (long)getpid(), serial++);
  syncap_gpiosim_unlink(fixture.name);
  fixture.chip = syncap_gpiosim_open(fixture.name, true);
  if (fixture.chip == NULL) return -1;
  *state = &fixture;
  return 0;
}

static int tear_down_chip(void** state) {
  struct chip_fixture* fixture = *state;
  syncap_gpiosim_close(fixture->chip);
  syncap_gpiosim_unlink(fixture->name);
  return 0;
}

// One pulse on line: high (a rising edge, whose time is returned), then low.
static int64_t pulse(struct syncap_gpiosim* chip, unsigned line) {
  int64_t rise_ns = 0;
  assert_int_equal(syncap_gpiosim_set_lines(chip, &line, 1, 1, &rise_ns), 0);
  assert_int_equal(syncap_gpiosim_set_lines(chip, &line, 1, 0, NULL), 0);
  return rise_ns;
}

// The starting point of a watcher that wants the edges from now on.
static struct syncap_gpiosim_rise now_on(struct syncap_gpiosim* chip, unsigned line) {
  struct syncap_gpiosim_line state;
  assert_int_equal(syncap_gpiosim_read_line(chip, line, &state), 0);
  return (struct syncap_gpiosim_rise){state.run, state.count, state.last_rise_ns};
}

static void missing_chip_is_enoent_with_a_message_naming_it(void** state) {
  (void)state;
  char name[64];
  snprintf(name, sizeof(name), "test-%ld-missing", (long)getpid());
  syncap_gpiosim_unlink(name);
  errno = 0;
  assert_null(syncap_gpiosim_open(name, false));
  assert_int_equal(errno, ENOENT);
  char message[256];
  syncap_gpiosim_describe_error(name, ENOENT, message, sizeof(message));
  char expected[256];
  snprintf(expected, sizeof(expected),
           "shared GPIO chip '%s' (/dev/shm/syncap-gpiosim-%s) does not exist", name, name);
  assert_string_equal(message, expected);
  assert_int_equal(syncap_gpiosim_unlink(name), -1);
  assert_int_equal(errno, ENOENT);
}

static void invalid_names_are_einval(void** state) {
  (void)state;
  const char* names[] = {"",
                         ".hidden",
                         "-option",
                         "a/b",
                         "a b",
                         "caf\xc3\xa9",
                         "12345678901234567890123456789012345678901234567890123456789012345"};
  for (size_t i = 0; i < sizeof(names) / sizeof(names[0]); ++i) {
    assert_false(syncap_gpiosim_name_is_valid(names[i]));
    errno = 0;
    assert_null(syncap_gpiosim_open(names[i], true));
    assert_int_equal(errno, EINVAL);
  }
  assert_true(syncap_gpiosim_name_is_valid("cam_0.rig-2"));
  char message[256];
  syncap_gpiosim_describe_error("a/b", EINVAL, message, sizeof(message));
  assert_non_null(strstr(message, "'a/b' is not a valid shared GPIO chip name"));
}

static void a_second_mapping_sees_the_same_lines(void** state) {
  struct chip_fixture* fixture = *state;
  struct syncap_gpiosim* other = syncap_gpiosim_open(fixture->name, false);
  assert_non_null(other);
  assert_string_equal(syncap_gpiosim_name(other), fixture->name);
  const unsigned lines[] = {3, 63};
  assert_int_equal(syncap_gpiosim_claim_lines(fixture->chip, lines, 2), 0);
  int64_t rise_ns = 0;
  assert_int_equal(syncap_gpiosim_set_lines(fixture->chip, lines, 2, 7, &rise_ns), 0);
  for (size_t i = 0; i < 2; ++i) {
    struct syncap_gpiosim_line line;
    assert_int_equal(syncap_gpiosim_read_line(other, lines[i], &line), 0);
    assert_int_equal(line.level, 1);
    assert_int_equal(line.run, 1);
    assert_int_equal(line.count, 1);
    assert_int_equal(line.last_rise_ns, rise_ns);
  }
  struct syncap_gpiosim_line untouched;
  assert_int_equal(syncap_gpiosim_read_line(other, 4, &untouched), 0);
  assert_int_equal(untouched.run, 0);
  assert_int_equal(untouched.count, 0);
  syncap_gpiosim_close(other);
}

static void only_low_to_high_counts_as_a_rising_edge(void** state) {
  struct chip_fixture* fixture = *state;
  const unsigned line = 5;
  assert_int_equal(syncap_gpiosim_set_lines(fixture->chip, &line, 1, 0, NULL), 0);
  assert_int_equal(syncap_gpiosim_set_lines(fixture->chip, &line, 1, 1, NULL), 0);
  assert_int_equal(syncap_gpiosim_set_lines(fixture->chip, &line, 1, 1, NULL), 0);
  assert_int_equal(syncap_gpiosim_set_lines(fixture->chip, &line, 1, 0, NULL), 0);
  struct syncap_gpiosim_line state_now;
  assert_int_equal(syncap_gpiosim_read_line(fixture->chip, line, &state_now), 0);
  assert_int_equal(state_now.count, 1);
  assert_int_equal(state_now.level, 0);
}

static void bad_lines_are_einval(void** state) {
  struct chip_fixture* fixture = *state;
  const unsigned lines[] = {0, SYNCAP_GPIOSIM_NUM_LINES};
  struct syncap_gpiosim_line line;
  struct syncap_gpiosim_rise rise = {0, 0, 0};
  assert_int_equal(syncap_gpiosim_claim_lines(fixture->chip, lines, 2), -1);
  assert_int_equal(errno, EINVAL);
  assert_int_equal(syncap_gpiosim_set_lines(fixture->chip, lines, 2, 1, NULL), -1);
  assert_int_equal(errno, EINVAL);
  assert_int_equal(syncap_gpiosim_read_line(fixture->chip, lines[1], &line), -1);
  assert_int_equal(errno, EINVAL);
  assert_int_equal(syncap_gpiosim_wait_rising(fixture->chip, lines[1], 0, &rise), -1);
  assert_int_equal(errno, EINVAL);
  // Nothing was applied to the good line either.
  assert_int_equal(syncap_gpiosim_read_line(fixture->chip, 0, &line), 0);
  assert_int_equal(line.level, 0);
  assert_int_equal(line.run, 0);
}

static void wait_times_out_without_an_edge(void** state) {
  struct chip_fixture* fixture = *state;
  struct syncap_gpiosim_rise rise = now_on(fixture->chip, 2);
  const int64_t start_ns = monotonic_ns();
  errno = 0;
  assert_int_equal(syncap_gpiosim_wait_rising(fixture->chip, 2, 30 * NS_PER_MS, &rise), -1);
  assert_int_equal(errno, ETIMEDOUT);
  const int64_t waited_ns = monotonic_ns() - start_ns;
  assert_true(waited_ns >= 30 * NS_PER_MS);
  assert_true(waited_ns < 1000 * NS_PER_MS);
  // A zero timeout only looks.
  assert_int_equal(syncap_gpiosim_wait_rising(fixture->chip, 2, 0, &rise), -1);
  assert_int_equal(errno, ETIMEDOUT);
  // An edge on another line does not end the wait for this one.
  pulse(fixture->chip, 3);
  assert_int_equal(syncap_gpiosim_wait_rising(fixture->chip, 2, 0, &rise), -1);
  assert_int_equal(errno, ETIMEDOUT);
}

// Edges driven before the wait are handed out from the history, one by one, with their times.
static void a_late_watcher_gets_each_kept_edge_in_order(void** state) {
  struct chip_fixture* fixture = *state;
  const unsigned line = 9;
  assert_int_equal(syncap_gpiosim_claim_lines(fixture->chip, &line, 1), 0);
  struct syncap_gpiosim_rise rise = now_on(fixture->chip, line);
  int64_t times[100];
  for (size_t i = 0; i < 100; ++i) times[i] = pulse(fixture->chip, line);
  for (uint64_t count = 1; count <= 100; ++count) {
    assert_int_equal(syncap_gpiosim_wait_rising(fixture->chip, line, 0, &rise), 0);
    assert_int_equal(rise.run, 1);
    assert_int_equal(rise.count, count);
    assert_int_equal(rise.time_ns, times[count - 1]);
  }
  assert_int_equal(syncap_gpiosim_wait_rising(fixture->chip, line, 0, &rise), -1);
}

static void a_watcher_too_far_behind_jumps_to_the_oldest_kept_edge(void** state) {
  struct chip_fixture* fixture = *state;
  const unsigned line = 1;
  struct syncap_gpiosim_rise rise = now_on(fixture->chip, line);
  int64_t last_ns = 0;
  for (size_t i = 0; i < SYNCAP_GPIOSIM_HISTORY + 10; ++i) last_ns = pulse(fixture->chip, line);
  assert_int_equal(syncap_gpiosim_wait_rising(fixture->chip, line, 0, &rise), 0);
  assert_int_equal(rise.count, 11);
  struct syncap_gpiosim_line state_now;
  assert_int_equal(syncap_gpiosim_read_line(fixture->chip, line, &state_now), 0);
  assert_int_equal(state_now.count, SYNCAP_GPIOSIM_HISTORY + 10);
  assert_int_equal(state_now.last_rise_ns, last_ns);
}

// A new writer claims the line: its edges are numbered from 1 in a new run, and a watcher that
// followed the old run moves on to the new one.
static void claiming_starts_a_new_run(void** state) {
  struct chip_fixture* fixture = *state;
  const unsigned line = 7;
  assert_int_equal(syncap_gpiosim_claim_lines(fixture->chip, &line, 1), 0);
  struct syncap_gpiosim_rise rise = now_on(fixture->chip, line);
  for (int i = 0; i < 5; ++i) pulse(fixture->chip, line);
  for (int i = 0; i < 5; ++i)
    assert_int_equal(syncap_gpiosim_wait_rising(fixture->chip, line, 0, &rise), 0);
  assert_int_equal(rise.run, 1);
  assert_int_equal(rise.count, 5);
  assert_int_equal(syncap_gpiosim_claim_lines(fixture->chip, &line, 1), 0);
  const int64_t first_ns = pulse(fixture->chip, line);
  assert_int_equal(syncap_gpiosim_wait_rising(fixture->chip, line, 0, &rise), 0);
  assert_int_equal(rise.run, 2);
  assert_int_equal(rise.count, 1);
  assert_int_equal(rise.time_ns, first_ns);
}

struct writer_run {
  struct syncap_gpiosim* chip;
  unsigned line;
  int64_t times[EDGES];
};

// Raises EDGES pulses with irregular gaps, some long enough for the watcher to block, some so
// short that edges pile up while it is busy.
static void* write_edges(void* argument) {
  struct writer_run* run = argument;
  for (size_t i = 0; i < EDGES; ++i) {
    run->times[i] = pulse(run->chip, run->line);
    if (i % 7 == 0) sleep_us((long)(i % 5) * 100);
  }
  return NULL;
}

static void a_watcher_thread_sees_every_edge_with_its_time(void** state) {
  struct chip_fixture* fixture = *state;
  static struct writer_run run;
  run.chip = fixture->chip;
  run.line = 11;
  assert_int_equal(syncap_gpiosim_claim_lines(fixture->chip, &run.line, 1), 0);
  struct syncap_gpiosim_rise rise = now_on(fixture->chip, run.line);
  pthread_t writer;
  assert_int_equal(pthread_create(&writer, NULL, write_edges, &run), 0);
  static struct syncap_gpiosim_rise seen[EDGES];
  size_t count = 0;
  while (count < EDGES &&
         syncap_gpiosim_wait_rising(fixture->chip, run.line, 2000 * NS_PER_MS, &rise) == 0) {
    seen[count++] = rise;
  }
  pthread_join(writer, NULL);
  assert_int_equal(count, EDGES);
  for (size_t i = 0; i < EDGES; ++i) {
    assert_int_equal(seen[i].count, i + 1);
    assert_int_equal(seen[i].time_ns, run.times[i]);
  }
}

// The child watches and reports what it saw through a pipe; the parent drives the edges once the
// child says it is ready.
static void watch_in_child(const char* name, unsigned line, int ready_fd, int report_fd) {
  struct syncap_gpiosim* chip = syncap_gpiosim_open(name, false);
  if (chip == NULL) _exit(10);
  struct syncap_gpiosim_line state;
  if (syncap_gpiosim_read_line(chip, line, &state) < 0) _exit(11);
  struct syncap_gpiosim_rise rise = {state.run, state.count, state.last_rise_ns};
  if (write(ready_fd, "r", 1) != 1) _exit(12);
  for (size_t i = 0; i < EDGES; ++i) {
    if (syncap_gpiosim_wait_rising(chip, line, 2000 * NS_PER_MS, &rise) < 0) _exit(13);
    if (write(report_fd, &rise, sizeof(rise)) != (ssize_t)sizeof(rise)) _exit(14);
  }
  syncap_gpiosim_close(chip);
  _exit(0);
}

static void a_watcher_process_sees_every_edge_with_its_time(void** state) {
  struct chip_fixture* fixture = *state;
  const unsigned line = 12;
  int ready[2];
  int report[2];
  assert_int_equal(pipe(ready), 0);
  assert_int_equal(pipe(report), 0);
  const pid_t child = fork();
  assert_true(child >= 0);
  if (child == 0) watch_in_child(fixture->name, line, ready[1], report[1]);
  close(ready[1]);
  close(report[1]);
  char byte = 0;
  assert_int_equal(read(ready[0], &byte, 1), 1);
  static struct writer_run run;
  run.chip = fixture->chip;
  run.line = line;
  // Reading the reports meanwhile keeps the pipe from filling up and blocking the child.
  pthread_t writer;
  assert_int_equal(pthread_create(&writer, NULL, write_edges, &run), 0);
  static struct syncap_gpiosim_rise seen[EDGES];
  size_t bytes = 0;
  ssize_t got = 0;
  while (bytes < sizeof(seen) &&
         (got = read(report[0], (char*)seen + bytes, sizeof(seen) - bytes)) > 0) {
    bytes += (size_t)got;
  }
  pthread_join(writer, NULL);
  int status = 0;
  waitpid(child, &status, 0);
  close(ready[0]);
  close(report[0]);
  assert_true(WIFEXITED(status));
  assert_int_equal(WEXITSTATUS(status), 0);
  assert_int_equal(bytes, sizeof(seen));
  for (size_t i = 0; i < EDGES; ++i) {
    assert_int_equal(seen[i].count, i + 1);
    assert_int_equal(seen[i].time_ns, run.times[i]);
  }
}

// A watcher killed in the middle of a wait must not keep anyone else from using the chip.
static void a_killed_watcher_blocks_no_one(void** state) {
  struct chip_fixture* fixture = *state;
  const unsigned line = 13;
  const pid_t child = fork();
  assert_true(child >= 0);
  if (child == 0) {
    struct syncap_gpiosim* chip = syncap_gpiosim_open(fixture->name, false);
    struct syncap_gpiosim_rise rise = {UINT64_MAX, 0, 0};
    (void)syncap_gpiosim_wait_rising(chip, line + 1, -1, &rise);
    _exit(0);
  }
  sleep_us(50000);
  kill(child, SIGKILL);
  waitpid(child, NULL, 0);
  // Edges, with this thread waiting for each: with a pthread condition variable the writer's
  // second broadcast after the kill blocked for ever, waiting for the dead waiter to wake (the
  // bench's camera-unplug fault hung the trigger so). The alarm turns such a hang into a failure.
  static struct writer_run run;
  run.chip = fixture->chip;
  run.line = line;
  struct syncap_gpiosim_rise rise = now_on(fixture->chip, line);
  alarm(20);
  pthread_t writer;
  assert_int_equal(pthread_create(&writer, NULL, write_edges, &run), 0);
  size_t count = 0;
  while (count < EDGES &&
         syncap_gpiosim_wait_rising(fixture->chip, line, 2000 * NS_PER_MS, &rise) == 0) {
    ++count;
  }
  pthread_join(writer, NULL);
  alarm(0);
  assert_int_equal(count, EDGES);
  assert_int_equal(rise.time_ns, run.times[EDGES - 1]);
}

// Several processes creating the same chip at once all end up on one chip.
static void racing_creators_share_one_chip(void** state) {
  struct chip_fixture* fixture = *state;
  syncap_gpiosim_close(fixture->chip);  // the fixture's chip goes; the children race to create it
  fixture->chip = NULL;
  assert_int_equal(syncap_gpiosim_unlink(fixture->name), 0);
  pid_t children[6];
  for (size_t i = 0; i < 6; ++i) {
    children[i] = fork();
    assert_true(children[i] >= 0);
    if (children[i] == 0) {
      struct syncap_gpiosim* chip = syncap_gpiosim_open(fixture->name, true);
      const unsigned line = (unsigned)i;
      const bool ok = chip != NULL && syncap_gpiosim_set_lines(chip, &line, 1, 1, NULL) == 0;
      syncap_gpiosim_close(chip);
      _exit(ok ? 0 : 1);
    }
  }
  for (size_t i = 0; i < 6; ++i) {
    int status = 0;
    waitpid(children[i], &status, 0);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  fixture->chip = syncap_gpiosim_open(fixture->name, false);
  assert_non_null(fixture->chip);
  for (unsigned line = 0; line < 6; ++line) {
    struct syncap_gpiosim_line state_now;
    assert_int_equal(syncap_gpiosim_read_line(fixture->chip, line, &state_now), 0);
    assert_int_equal(state_now.count, 1);
  }
}

// "sim:NAME" through the GPIO API: request claims the lines, each set is one instant on the
// shared chip, and the GPIO's change time is the chip's edge time.
static void gpio_sim_name_drives_the_shared_chip(void** state) {
  struct chip_fixture* fixture = *state;
  char spec[80];
  snprintf(spec, sizeof(spec), "sim:%s", fixture->name);
  struct syncap_gpio* gpio = syncap_gpio_open(spec);
  assert_non_null(gpio);
  const unsigned lines[] = {0, 2};
  assert_int_equal(syncap_gpio_request_outputs(gpio, lines, 2, "test"), 0);
  struct syncap_gpiosim_rise rise = now_on(fixture->chip, 2);
  assert_int_equal(rise.run, 1);
  for (int i = 0; i < 3; ++i) {
    assert_int_equal(syncap_gpio_set_all(gpio, 1), 0);
    const int64_t rise_ns = syncap_gpio_last_change_ns(gpio);
    assert_int_equal(syncap_gpio_set_all(gpio, 0), 0);
    assert_int_equal(syncap_gpiosim_wait_rising(fixture->chip, 2, 0, &rise), 0);
    assert_int_equal(rise.count, (uint64_t)i + 1);
    assert_int_equal(rise.time_ns, rise_ns);
  }
  syncap_gpio_close(gpio);
  struct syncap_gpiosim_line line;
  assert_int_equal(syncap_gpiosim_read_line(fixture->chip, 0, &line), 0);
  assert_int_equal(line.level, 0);
  assert_int_equal(line.count, 3);
}

#define CHIP_TEST(test) cmocka_unit_test_setup_teardown(test, set_up_chip, tear_down_chip)

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(missing_chip_is_enoent_with_a_message_naming_it),
    cmocka_unit_test(invalid_names_are_einval),
    CHIP_TEST(a_second_mapping_sees_the_same_lines),
    CHIP_TEST(only_low_to_high_counts_as_a_rising_edge),
    CHIP_TEST(bad_lines_are_einval),
    CHIP_TEST(wait_times_out_without_an_edge),
    CHIP_TEST(a_late_watcher_gets_each_kept_edge_in_order),
    CHIP_TEST(a_watcher_too_far_behind_jumps_to_the_oldest_kept_edge),
    CHIP_TEST(claiming_starts_a_new_run),
    CHIP_TEST(a_watcher_thread_sees_every_edge_with_its_time),
    CHIP_TEST(a_watcher_process_sees_every_edge_with_its_time),
    CHIP_TEST(a_killed_watcher_blocks_no_one),
    CHIP_TEST(racing_creators_share_one_chip),
    CHIP_TEST(gpio_sim_name_drives_the_shared_chip),
};

SYNCAP_CMOCKA_MAIN(tests)
