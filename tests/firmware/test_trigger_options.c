// syncap-trigger's config file and command line: keys, comments, precedence, and errors that name
// the file and the line.
#include "cmocka_main.h"

#include <stdlib.h>
#include <unistd.h>

#include "trigger_options.h"

// Writes text to a new temporary file; its path goes to path.
static void write_config(const char* text, char* path, size_t size) {
  snprintf(path, size, "/tmp/syncap-trigger-test-%ld-XXXXXX", (long)getpid());
  const int fd = mkstemp(path);
  assert_true(fd >= 0);
  const size_t length = strlen(text);
  assert_int_equal(write(fd, text, length), (ssize_t)length);
  close(fd);
}

// Loads text as a config file into options (defaults first); returns whether it loaded, the error
// in error.
static bool load(const char* text, struct trigger_options* options, char* error, size_t size) {
  char path[128];
  write_config(text, path, sizeof(path));
  trigger_options_defaults(options);
  const bool ok = trigger_options_load_config(path, options, error, size);
  // The message names the file: put a stable name in its place for the checks.
  if (!ok) {
    const size_t n = strlen(path);
    assert_memory_equal(error, path, n);
    char rest[512];
    snprintf(rest, sizeof(rest), "trigger.conf%s", error + n);
    snprintf(error, size, "%s", rest);
  }
  unlink(path);
  return ok;
}

static void keys_comments_and_blank_lines(void** state) {
  (void)state;
  struct trigger_options options;
  char error[512] = "";
  const bool ok = load(
      "# the rig's trigger\n"
      "rate = 100\n"
      "\n"
      "   width-us=500   # half a millisecond\n"
      "lines = 0,1,2\n"
      "chip = gpiochip0\n"
      "start-line = 5\n"
      "stop-line = 6\n"
      "debounce-us = 2000\n"
      "trigger-id = 3\n"
      "start-delay-ms = 250\n"
      "lcm-url = udpm://239.255.76.67:7667?ttl=1\n"
      "quiet = yes",
      &options, error, sizeof(error));
  assert_true(ok);
  assert_true(options.rate_hz == 100.0);
  assert_int_equal(options.width_us, 500);
  assert_int_equal(options.num_lines, 3);
  assert_int_equal(options.lines[2], 2);
  assert_string_equal(options.chip, "gpiochip0");
  assert_int_equal(options.start_line, 5);
  assert_int_equal(options.stop_line, 6);
  assert_int_equal(options.debounce_us, 2000);
  assert_int_equal(options.trigger_id, 3);
  assert_int_equal(options.start_delay_ms, 250);
  assert_string_equal(options.lcm_url, "udpm://239.255.76.67:7667?ttl=1");
  assert_true(options.quiet);
  trigger_options_free(&options);
}

static void phases_and_spin_keys(void** state) {
  (void)state;
  struct trigger_options options;
  char error[512] = "";
  assert_true(
      load("lines = 0,1,2\nphases-us = 0, 250,250\nspin-us = 0\n", &options, error, sizeof(error)));
  assert_int_equal(options.num_phases, 3);
  assert_int_equal(options.phases_us[1], 250);
  assert_int_equal(options.phases_us[2], 250);
  assert_int_equal(options.spin_us, 0);
  trigger_options_free(&options);
  trigger_options_defaults(&options);
  assert_int_equal(options.spin_us, 200);
  assert_int_equal(options.num_phases, 0);
  assert_false(load("phases-us = 0,-5\n", &options, error, sizeof(error)));
  assert_string_equal(error,
                      "trigger.conf:1: invalid phases-us '0,-5': each phase must be a whole number "
                      "of microseconds >= 0");
  trigger_options_free(&options);
  assert_false(load("spin-us = 20000\n", &options, error, sizeof(error)));
  trigger_options_free(&options);
}

static void unknown_key_names_file_and_line(void** state) {
  (void)state;
  struct trigger_options options;
  char error[512] = "";
  assert_false(load("# comment\nrate = 30\nrat = 100\n", &options, error, sizeof(error)));
  assert_string_equal(error, "trigger.conf:3: unknown key 'rat'");
  trigger_options_free(&options);
}

static void bad_value_names_file_line_key_and_value(void** state) {
  (void)state;
  struct trigger_options options;
  char error[512] = "";
  assert_false(load("count = 12x\n", &options, error, sizeof(error)));
  assert_string_equal(error, "trigger.conf:1: invalid count '12x': must be a whole number >= 0");
  trigger_options_free(&options);
  assert_false(load("\n\nquiet = maybe\n", &options, error, sizeof(error)));
  assert_string_equal(error, "trigger.conf:3: invalid quiet 'maybe': must be true or false");
  trigger_options_free(&options);
}

static void line_without_equals_or_value_is_an_error(void** state) {
  (void)state;
  struct trigger_options options;
  char error[512] = "";
  assert_false(load("rate 30\n", &options, error, sizeof(error)));
  assert_string_equal(error, "trigger.conf:1: expected 'key = value', got 'rate 30'");
  trigger_options_free(&options);
  assert_false(load("rate =   # nothing\n", &options, error, sizeof(error)));
  assert_string_equal(error, "trigger.conf:1: missing value for 'rate'");
  trigger_options_free(&options);
}

// help and config are command-line only.
static void help_and_config_are_not_keys(void** state) {
  (void)state;
  struct trigger_options options;
  char error[512] = "";
  assert_false(load("config = /etc/other.conf\n", &options, error, sizeof(error)));
  assert_string_equal(error, "trigger.conf:1: unknown key 'config'");
  trigger_options_free(&options);
}

static void missing_file_is_named(void** state) {
  (void)state;
  struct trigger_options options;
  trigger_options_defaults(&options);
  char error[512] = "";
  assert_false(
      trigger_options_load_config("/nonexistent/trigger.conf", &options, error, sizeof(error)));
  assert_string_equal(error, "/nonexistent/trigger.conf: cannot read: No such file or directory");
}

static void command_line_overrides_the_file(void** state) {
  (void)state;
  char path[128];
  write_config("rate = 100\nwidth-us = 500\ncount = 7\n", path, sizeof(path));
  char* argv[] = {"syncap-trigger", "--rate", "50", "--config", path, "--count=9", NULL};
  struct trigger_options options;
  assert_int_equal(trigger_options_parse(6, argv, &options), TRIGGER_OPTIONS_RUN);
  unlink(path);
  assert_true(options.rate_hz == 50.0);  // the command line, though given before --config
  assert_string_equal(options.rate_text, "50");
  assert_int_equal(options.width_us, 500);  // the file
  assert_int_equal(options.count, 9);
  assert_string_equal(options.config_path, path);
  trigger_options_free(&options);
}

static void defaults_without_a_file(void** state) {
  (void)state;
  char* argv[] = {"syncap-trigger", NULL};
  struct trigger_options options;
  assert_int_equal(trigger_options_parse(1, argv, &options), TRIGGER_OPTIONS_RUN);
  assert_true(options.rate_hz == 30.0);
  assert_int_equal(options.start_line, -1);
  assert_int_equal(options.stop_line, -1);
  assert_int_equal(options.debounce_us, 5000);
  assert_int_equal(options.bench_seconds, 0);
  assert_null(options.config_path);
  trigger_options_free(&options);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(keys_comments_and_blank_lines),
    cmocka_unit_test(phases_and_spin_keys),
    cmocka_unit_test(unknown_key_names_file_and_line),
    cmocka_unit_test(bad_value_names_file_line_key_and_value),
    cmocka_unit_test(line_without_equals_or_value_is_an_error),
    cmocka_unit_test(help_and_config_are_not_keys),
    cmocka_unit_test(missing_file_is_named),
    cmocka_unit_test(command_line_overrides_the_file),
    cmocka_unit_test(defaults_without_a_file),
};

SYNCAP_CMOCKA_MAIN(tests)
