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
      "rate-hz = 100\n"
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
  assert_false(load("# comment\nrate-hz = 30\nrat = 100\n", &options, error, sizeof(error)));
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
  assert_false(load("rate-hz 30\n", &options, error, sizeof(error)));
  assert_string_equal(error, "trigger.conf:1: expected 'key = value', got 'rate-hz 30'");
  trigger_options_free(&options);
  assert_false(load("rate-hz =   # nothing\n", &options, error, sizeof(error)));
  assert_string_equal(error, "trigger.conf:1: missing value for 'rate-hz'");
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
  write_config("rate-hz = 100\nwidth-us = 500\ncount = 7\n", path, sizeof(path));
  char* argv[] = {"syncap-trigger", "--rate-hz", "50", "--config", path, "--count=9", NULL};
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

// --rate and the key rate, the old names of --rate-hz, still set the rate.
static void old_rate_name_still_sets_the_rate(void** state) {
  (void)state;
  struct trigger_options options;
  char error[512] = "";
  assert_true(load("rate = 100\n", &options, error, sizeof(error)));
  assert_true(options.rate_hz == 100.0);
  trigger_options_free(&options);
  char* argv[] = {"syncap-trigger", "--rate", "50", NULL};
  assert_int_equal(trigger_options_parse(3, argv, &options), TRIGGER_OPTIONS_RUN);
  assert_true(options.rate_hz == 50.0);
  trigger_options_free(&options);
}

// Writes text to DIR/name in a new temporary folder; its path goes to path. The folder is left
// for remove_yaml.
static void write_named(const char* text, const char* name, char* path, size_t size) {
  char folder[] = "/tmp/syncap-trigger-yaml-XXXXXX";
  assert_non_null(mkdtemp(folder));
  snprintf(path, size, "%s/%s", folder, name);
  FILE* file = fopen(path, "w");
  assert_non_null(file);
  fputs(text, file);
  fclose(file);
}

static void remove_named(const char* path) {
  unlink(path);
  char folder[256];
  snprintf(folder, sizeof(folder), "%s", path);
  *strrchr(folder, '/') = '\0';
  rmdir(folder);
}

// Loads text as DIR/trigger.yaml; the error with "trigger.yaml" for the path.
static bool load_yaml(const char* text, struct trigger_options* options, char* error, size_t size) {
  char path[256];
  write_named(text, "trigger.yaml", path, sizeof(path));
  trigger_options_defaults(options);
  const bool ok = trigger_options_load_config(path, options, error, size);
  if (!ok) {
    const char* rest = error + strlen(path);
    char copy[512];
    snprintf(copy, sizeof(copy), "trigger.yaml%s", rest);
    snprintf(error, size, "%s", copy);
  }
  remove_named(path);
  return ok;
}

static void yaml_file_of_options(void** state) {
  (void)state;
  struct trigger_options options;
  char error[512] = "";
  assert_true(
      load_yaml("# the trigger\nrate-hz: 100\nwidth-us: 500\nlines: [0, 1, 2]\n"
                "phases-us: 0,250,250\nchip: gpiochip0\nquiet: true\n",
                &options, error, sizeof(error)));
  assert_true(options.rate_hz == 100.0);
  assert_int_equal(options.width_us, 500);
  assert_int_equal(options.num_lines, 3);
  assert_int_equal(options.lines[2], 2);
  assert_string_equal(options.lines_text, "0,1,2");
  assert_int_equal(options.phases_us[1], 250);
  assert_string_equal(options.chip, "gpiochip0");
  assert_true(options.quiet);
  trigger_options_free(&options);
}

static void yaml_errors_name_file_line_column_and_key(void** state) {
  (void)state;
  struct trigger_options options;
  char error[512] = "";
  assert_false(load_yaml("rate-hz: 30\nrat: 100\n", &options, error, sizeof(error)));
  assert_string_equal(error, "trigger.yaml:2:1: key 'rat': not an option of syncap-trigger");
  trigger_options_free(&options);
  assert_false(load_yaml("rate-hz: 30\ncount:   12x\n", &options, error, sizeof(error)));
  assert_string_equal(error, "trigger.yaml:2:10: key 'count': '12x' must be a whole number >= 0");
  trigger_options_free(&options);
  assert_false(load_yaml("lines: {a: 1}\n", &options, error, sizeof(error)));
  assert_string_equal(error, "trigger.yaml:1:8: key 'lines': is not a single value or a list");
  trigger_options_free(&options);
  assert_false(load_yaml("width-us:\n", &options, error, sizeof(error)));
  assert_string_equal(error, "trigger.yaml:1:10: key 'width-us': missing value");
  trigger_options_free(&options);
  assert_false(load_yaml("rate-hz: [30\n", &options, error, sizeof(error)));
  assert_memory_equal(error, "trigger.yaml:2:1: not YAML: ", 27);
  trigger_options_free(&options);
}

// The rig file: the shared lcm-url, the trigger: section; the other programs' parts passed over.
static void rig_file_gives_the_trigger_its_section(void** state) {
  (void)state;
  struct trigger_options options;
  char error[512] = "";
  assert_true(
      load_yaml("calibration: /etc/syncap/cameras.json\n"
                "lcm-url: udpm://239.255.76.67:7667?ttl=1\n"
                "trigger:\n  chip: gpiochip0\n  lines: 17,27\n  rate-hz: 60\n"
                "host:\n  hull: true\n"
                "edges:\n  threshold: 200\n"
                "cameras:\n  - {camera-id: 0, board: a}\n",
                &options, error, sizeof(error)));
  assert_string_equal(options.lcm_url, "udpm://239.255.76.67:7667?ttl=1");
  assert_string_equal(options.chip, "gpiochip0");
  assert_int_equal(options.num_lines, 2);
  assert_int_equal(options.lines[1], 27);
  assert_true(options.rate_hz == 60.0);
  trigger_options_free(&options);
  assert_false(load_yaml("host:\n  hull: true\ntrigger:\n  chip: sim\n  hull: true\n", &options,
                         error, sizeof(error)));
  assert_string_equal(error, "trigger.yaml:5:3: key 'hull': not an option of syncap-trigger");
  trigger_options_free(&options);
}

// The rig example the guide shows (docs/examples/rig-8cam.yaml) parses as the trigger's.
static void shipped_rig_example_parses(void** state) {
  (void)state;
  struct trigger_options options;
  trigger_options_defaults(&options);
  char error[512] = "";
  const bool ok = trigger_options_load_config(SYNCAP_SOURCE_DIR "/docs/examples/rig-8cam.yaml",
                                              &options, error, sizeof(error));
  if (!ok) fail_msg("%s", error);
  assert_string_equal(options.chip, "gpiochip0");
  assert_int_equal(options.num_lines, 4);
  assert_true(options.rate_hz == 30.0);
  assert_string_equal(options.lcm_url, "udpm://239.255.76.67:7667?ttl=1");
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
    cmocka_unit_test(old_rate_name_still_sets_the_rate),
    cmocka_unit_test(yaml_file_of_options),
    cmocka_unit_test(yaml_errors_name_file_line_column_and_key),
    cmocka_unit_test(rig_file_gives_the_trigger_its_section),
    cmocka_unit_test(shipped_rig_example_parses),
    cmocka_unit_test(defaults_without_a_file),
};

SYNCAP_CMOCKA_MAIN(tests)
