// syncap-trigger as a process: exit status 2 with a message for wrong arguments, a clean exit 0
// with a summary at the end of a count run and on SIGINT/SIGTERM. LCM goes to memq:// (in-process),
// so these need no network.
#include "cmocka_main.h"

#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>

#include "child_process.h"

#ifndef SYNCAP_TRIGGER_EXE
#error "SYNCAP_TRIGGER_EXE must be the path of syncap-trigger"
#endif

struct run_result {
  int status;  // wait status, -1 on timeout
  char output[8192];
};

// Runs syncap-trigger with args; after signal_after_ms (when >= 0) sends it signal_number.
static void run_trigger(char* const* args, int signal_after_ms, int signal_number,
                        struct run_result* result) {
  char* argv[32] = {SYNCAP_TRIGGER_EXE};
  for (size_t i = 0; args[i] != NULL && i + 2 < 32; ++i) argv[i + 1] = args[i];
  FILE* output = tmpfile();
  assert_non_null(output);
  const pid_t pid = child_spawn(argv, fileno(output));
  assert_true(pid > 0);
  if (signal_after_ms >= 0) {
    const struct timespec delay = {signal_after_ms / 1000, (signal_after_ms % 1000) * 1000000L};
    nanosleep(&delay, NULL);
    kill(pid, signal_number);
  }
  result->status = child_wait(pid, 10000);
  rewind(output);
  const size_t length = fread(result->output, 1, sizeof(result->output) - 1, output);
  result->output[length] = '\0';
  fclose(output);
}

static void assert_exit_status(const struct run_result* result, int expected) {
  if (!WIFEXITED(result->status) || WEXITSTATUS(result->status) != expected) {
    print_error("status 0x%x, output:\n%s\n", (unsigned)result->status, result->output);
  }
  assert_true(WIFEXITED(result->status));
  assert_int_equal(WEXITSTATUS(result->status), expected);
}

static void assert_output_has(const struct run_result* result, const char* text) {
  if (strstr(result->output, text) == NULL) {
    print_error("'%s' not in output:\n%s\n", text, result->output);
    fail();
  }
}

static void unknown_option_exits_2_naming_it(void** state) {
  (void)state;
  static struct run_result result;
  run_trigger((char*[]){"--frobnicate", NULL}, -1, 0, &result);
  assert_exit_status(&result, 2);
  assert_output_has(&result, "'--frobnicate'");
  assert_output_has(&result, "usage:");
}

static void rate_out_of_range_exits_2_naming_it(void** state) {
  (void)state;
  static struct run_result result;
  run_trigger((char*[]){"--rate", "1000.1", NULL}, -1, 0, &result);
  assert_exit_status(&result, 2);
  assert_output_has(&result, "--rate '1000.1'");
}

static void malformed_count_exits_2_naming_it(void** state) {
  (void)state;
  static struct run_result result;
  run_trigger((char*[]){"--count", "12x", NULL}, -1, 0, &result);
  assert_exit_status(&result, 2);
  assert_output_has(&result, "--count '12x'");
}

static void chip_other_than_sim_exits_2(void** state) {
  (void)state;
  static struct run_result result;
  run_trigger((char*[]){"--chip", "gpiochip0", NULL}, -1, 0, &result);
  assert_exit_status(&result, 2);
  assert_output_has(&result, "--chip 'gpiochip0'");
}

static void help_exits_0(void** state) {
  (void)state;
  static struct run_result result;
  run_trigger((char*[]){"--help", NULL}, -1, 0, &result);
  assert_exit_status(&result, 0);
  assert_output_has(&result, "--start-delay-ms");
}

static void count_run_ends_with_a_summary(void** state) {
  (void)state;
  static struct run_result result;
  run_trigger((char*[]){"--count", "5", "--rate", "50", "--lcm-url", "memq://", NULL}, -1, 0,
              &result);
  assert_exit_status(&result, 0);
  assert_output_has(&result, "pulses=5 ");
}

static void quiet_run_prints_no_summary(void** state) {
  (void)state;
  static struct run_result result;
  run_trigger((char*[]){"--count", "2", "--rate", "500", "--quiet", "--lcm-url", "memq://", NULL},
              -1, 0, &result);
  assert_exit_status(&result, 0);
  assert_null(strstr(result.output, "pulses="));
}

// Slow rate and a start delay: the signal arrives while the daemon sleeps.
static void sigterm_stops_cleanly_with_status_0(void** state) {
  (void)state;
  static struct run_result result;
  run_trigger((char*[]){"--rate", "0.01", "--lcm-url", "memq://", NULL}, 300, SIGTERM, &result);
  assert_exit_status(&result, 0);
  assert_output_has(&result, "pulses=1 ");
}

static void sigint_stops_cleanly_with_status_0(void** state) {
  (void)state;
  static struct run_result result;
  run_trigger((char*[]){"--start-delay-ms", "100000", "--lcm-url", "memq://", NULL}, 300, SIGINT,
              &result);
  assert_exit_status(&result, 0);
  assert_output_has(&result, "pulses=0 ");
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(unknown_option_exits_2_naming_it),
    cmocka_unit_test(rate_out_of_range_exits_2_naming_it),
    cmocka_unit_test(malformed_count_exits_2_naming_it),
    cmocka_unit_test(chip_other_than_sim_exits_2),
    cmocka_unit_test(help_exits_0),
    cmocka_unit_test(count_run_ends_with_a_summary),
    cmocka_unit_test(quiet_run_prints_no_summary),
    cmocka_unit_test(sigterm_stops_cleanly_with_status_0),
    cmocka_unit_test(sigint_stops_cleanly_with_status_0),
};

SYNCAP_CMOCKA_MAIN(tests)
