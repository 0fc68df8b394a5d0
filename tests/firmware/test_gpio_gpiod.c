// The libgpiod backend against a fake libgpiod: which calls it makes, in which order, with which
// arguments, and how it reports scripted failures (missing chip, busy line, bad offset). No GPIO
// chip is needed.
#include "cmocka_main.h"

#include <errno.h>
#include <stdbool.h>

#include "gpio_gpiod.h"
#include "syncap/trigger/gpio.h"

#define FAKE_NUM_LINES 8
#define NS_PER_S INT64_C(1000000000)

// The fake chip and lines: libgpiod's types are opaque, so any distinct addresses will do.
static char fake_chip_storage;
static char fake_line_storage[FAKE_NUM_LINES];
#define FAKE_CHIP ((struct gpiod_chip*)(void*)&fake_chip_storage)

static struct fake {
  char calls[64][40];  // names of the calls, in order
  size_t num_calls;
  char looked_up[64];
  bool busy;  // requests fail with EBUSY
  unsigned requested[FAKE_NUM_LINES];
  size_t num_requested;
  char consumer[32];
  int default_vals[FAKE_NUM_LINES];
  int values[FAKE_NUM_LINES];  // last values set
  int sets;                    // set_value_bulk calls
  int wait_result;             // line_event_wait_bulk: 1 with event_line ready, 0 timeout
  unsigned event_line;
  struct gpiod_line_event event;
  int64_t monotonic_now_ns;
  int64_t realtime_now_ns;
} fake;

static void record(const char* name) {
  if (fake.num_calls < 64) snprintf(fake.calls[fake.num_calls++], 40, "%s", name);
}

static struct gpiod_line* fake_line(unsigned offset) {
  return (struct gpiod_line*)(void*)&fake_line_storage[offset];
}

static unsigned int fake_line_offset(struct gpiod_line* line) {
  return (unsigned)((char*)(void*)line - fake_line_storage);
}

static struct gpiod_chip* fake_open_lookup(const char* descr) {
  record("chip_open_lookup");
  snprintf(fake.looked_up, sizeof(fake.looked_up), "%s", descr);
  if (strcmp(descr, "gpiochip0") == 0 || strcmp(descr, "/dev/gpiochip0") == 0 ||
      strcmp(descr, "trigger-board") == 0) {
    return FAKE_CHIP;
  }
  errno = ENOENT;
  return NULL;
}

static void fake_chip_close(struct gpiod_chip* chip) {
  assert_ptr_equal(chip, FAKE_CHIP);
  record("chip_close");
}

static int fake_get_lines(struct gpiod_chip* chip, unsigned int* offsets, unsigned int num,
                          struct gpiod_line_bulk* bulk) {
  record("chip_get_lines");
  assert_ptr_equal(chip, FAKE_CHIP);
  gpiod_line_bulk_init(bulk);
  for (unsigned i = 0; i < num; ++i) {
    if (offsets[i] >= FAKE_NUM_LINES) {
      errno = EINVAL;
      return -1;
    }
    gpiod_line_bulk_add(bulk, fake_line(offsets[i]));
  }
  return 0;
}

static void remember_request(struct gpiod_line_bulk* bulk, const char* consumer) {
  fake.num_requested = gpiod_line_bulk_num_lines(bulk);
  for (size_t i = 0; i < fake.num_requested; ++i) {
    fake.requested[i] = fake_line_offset(gpiod_line_bulk_get_line(bulk, (unsigned)i));
  }
  snprintf(fake.consumer, sizeof(fake.consumer), "%s", consumer);
}

static int fake_request_output(struct gpiod_line_bulk* bulk, const char* consumer,
                               const int* default_vals) {
  record("line_request_bulk_output");
  if (fake.busy) {
    errno = EBUSY;
    return -1;
  }
  remember_request(bulk, consumer);
  for (size_t i = 0; i < fake.num_requested; ++i) fake.default_vals[i] = default_vals[i];
  return 0;
}

static int fake_request_edges(struct gpiod_line_bulk* bulk, const char* consumer) {
  record("line_request_bulk_both_edges_events");
  if (fake.busy) {
    errno = EBUSY;
    return -1;
  }
  remember_request(bulk, consumer);
  return 0;
}

static int fake_set_value_bulk(struct gpiod_line_bulk* bulk, const int* values) {
  record("line_set_value_bulk");
  ++fake.sets;
  for (unsigned i = 0; i < gpiod_line_bulk_num_lines(bulk); ++i) fake.values[i] = values[i];
  return 0;
}

static void fake_release_bulk(struct gpiod_line_bulk* bulk) {
  (void)bulk;
  record("line_release_bulk");
}

static int fake_event_wait_bulk(struct gpiod_line_bulk* bulk, const struct timespec* timeout,
                                struct gpiod_line_bulk* event_bulk) {
  (void)bulk;
  (void)timeout;
  record("line_event_wait_bulk");
  if (fake.wait_result == 1) gpiod_line_bulk_add(event_bulk, fake_line(fake.event_line));
  return fake.wait_result;
}

static int fake_event_read(struct gpiod_line* line, struct gpiod_line_event* event) {
  record("line_event_read");
  assert_ptr_equal(line, fake_line(fake.event_line));
  *event = fake.event;
  return 0;
}

static int fake_clock_gettime(clockid_t clock, struct timespec* now) {
  const int64_t ns = clock == CLOCK_REALTIME ? fake.realtime_now_ns : fake.monotonic_now_ns;
  *now = (struct timespec){.tv_sec = ns / NS_PER_S, .tv_nsec = ns % NS_PER_S};
  return 0;
}

static const struct syncap_gpiod_ops fake_ops = {
    .chip_open_lookup = fake_open_lookup,
    .chip_close = fake_chip_close,
    .chip_get_lines = fake_get_lines,
    .line_request_bulk_output = fake_request_output,
    .line_request_bulk_both_edges_events = fake_request_edges,
    .line_set_value_bulk = fake_set_value_bulk,
    .line_release_bulk = fake_release_bulk,
    .line_event_wait_bulk = fake_event_wait_bulk,
    .line_event_read = fake_event_read,
    .line_offset = fake_line_offset,
    .clock_gettime = fake_clock_gettime,
};

static int set_up(void** state) {
  (void)state;
  memset(&fake, 0, sizeof(fake));
  fake.monotonic_now_ns = 1000 * NS_PER_S;
  fake.realtime_now_ns = INT64_C(1795000000) * NS_PER_S;
  syncap_gpiod_set_ops(&fake_ops);
  return 0;
}

static int tear_down(void** state) {
  (void)state;
  syncap_gpiod_set_ops(NULL);
  return 0;
}

static bool called(const char* name) {
  for (size_t i = 0; i < fake.num_calls; ++i) {
    if (strcmp(fake.calls[i], name) == 0) return true;
  }
  return false;
}

static struct syncap_gpio* open_with_outputs(const unsigned* offsets, size_t num_lines) {
  struct syncap_gpio* gpio = syncap_gpio_open("gpiochip0");
  assert_non_null(gpio);
  assert_int_equal(syncap_gpio_request_outputs(gpio, offsets, num_lines, "syncap-trigger"), 0);
  return gpio;
}

static void opens_by_name_path_and_label(void** state) {
  (void)state;
  const char* specs[] = {"gpiochip0", "/dev/gpiochip0", "gpiod:trigger-board"};
  const char* looked_up[] = {"gpiochip0", "/dev/gpiochip0", "trigger-board"};
  for (size_t i = 0; i < 3; ++i) {
    struct syncap_gpio* gpio = syncap_gpio_open(specs[i]);
    assert_non_null(gpio);
    assert_string_equal(fake.looked_up, looked_up[i]);
    assert_string_equal(syncap_gpio_backend_name(gpio), "gpiod");
    syncap_gpio_close(gpio);
    assert_true(called("chip_close"));
  }
}

static void missing_chip_is_enoent_with_a_message_naming_it(void** state) {
  (void)state;
  errno = 0;
  assert_null(syncap_gpio_open("gpiochip7"));
  assert_int_equal(errno, ENOENT);
  char why[256];
  syncap_gpio_describe_open_error("gpiochip7", ENOENT, why, sizeof(why));
  assert_non_null(strstr(why, "'gpiochip7'"));
  assert_non_null(strstr(why, "does not exist"));
}

static void outputs_are_requested_low_for_the_consumer(void** state) {
  (void)state;
  const unsigned offsets[] = {3, 1, 6};
  struct syncap_gpio* gpio = open_with_outputs(offsets, 3);
  assert_int_equal(fake.num_requested, 3);
  for (size_t i = 0; i < 3; ++i) {
    assert_int_equal(fake.requested[i], offsets[i]);
    assert_int_equal(fake.default_vals[i], 0);
  }
  assert_string_equal(fake.consumer, "syncap-trigger");
  syncap_gpio_close(gpio);
}

static void set_all_drives_every_line_in_one_call(void** state) {
  (void)state;
  const unsigned offsets[] = {0, 2, 4, 7};
  struct syncap_gpio* gpio = open_with_outputs(offsets, 4);
  fake.monotonic_now_ns = 5 * NS_PER_S;
  assert_int_equal(syncap_gpio_set_all(gpio, 1), 0);
  assert_int_equal(fake.sets, 1);
  for (size_t i = 0; i < 4; ++i) assert_int_equal(fake.values[i], 1);
  assert_int_equal(syncap_gpio_last_change_ns(gpio), 5 * NS_PER_S);
  assert_int_equal(syncap_gpio_set_all(gpio, 1), 0);  // no change: no call
  assert_int_equal(fake.sets, 1);
  assert_int_equal(syncap_gpio_set_all(gpio, 0), 0);
  assert_int_equal(fake.sets, 2);
  for (size_t i = 0; i < 4; ++i) assert_int_equal(fake.values[i], 0);
  syncap_gpio_close(gpio);
}

static void close_drives_low_then_releases_then_closes(void** state) {
  (void)state;
  const unsigned offsets[] = {1, 2};
  struct syncap_gpio* gpio = open_with_outputs(offsets, 2);
  assert_int_equal(syncap_gpio_set_all(gpio, 1), 0);
  const size_t before = fake.num_calls;
  syncap_gpio_close(gpio);
  assert_int_equal(fake.num_calls, before + 3);
  assert_string_equal(fake.calls[before], "line_set_value_bulk");
  assert_int_equal(fake.values[0], 0);
  assert_int_equal(fake.values[1], 0);
  assert_string_equal(fake.calls[before + 1], "line_release_bulk");
  assert_string_equal(fake.calls[before + 2], "chip_close");
}

static void busy_line_is_ebusy(void** state) {
  (void)state;
  struct syncap_gpio* gpio = syncap_gpio_open("gpiochip0");
  fake.busy = true;
  const unsigned offsets[] = {0};
  errno = 0;
  assert_int_equal(syncap_gpio_request_outputs(gpio, offsets, 1, "syncap-trigger"), -1);
  assert_int_equal(errno, EBUSY);
  errno = 0;
  assert_int_equal(syncap_gpio_request_inputs(gpio, offsets, 1, "syncap-trigger"), -1);
  assert_int_equal(errno, EBUSY);
  // Nothing was requested, so nothing is released or driven.
  syncap_gpio_close(gpio);
  assert_false(called("line_release_bulk"));
  assert_false(called("line_set_value_bulk"));
}

static void offset_beyond_the_chip_is_einval(void** state) {
  (void)state;
  struct syncap_gpio* gpio = syncap_gpio_open("gpiochip0");
  const unsigned offsets[] = {2, FAKE_NUM_LINES};
  errno = 0;
  assert_int_equal(syncap_gpio_request_outputs(gpio, offsets, 2, "syncap-trigger"), -1);
  assert_int_equal(errno, EINVAL);
  assert_false(called("line_request_bulk_output"));
  syncap_gpio_close(gpio);
}

static void input_edges_carry_the_kernels_monotonic_timestamp(void** state) {
  (void)state;
  const unsigned outputs[] = {0};
  struct syncap_gpio* gpio = open_with_outputs(outputs, 1);
  const unsigned inputs[] = {5, 6};
  assert_int_equal(syncap_gpio_request_inputs(gpio, inputs, 2, "syncap-trigger"), 0);
  assert_true(called("line_request_bulk_both_edges_events"));
  fake.wait_result = 1;
  fake.event_line = 6;
  fake.event =
      (struct gpiod_line_event){.ts = {999, 250}, .event_type = GPIOD_LINE_EVENT_RISING_EDGE};
  struct syncap_gpio_event event;
  assert_int_equal(syncap_gpio_wait_edge(gpio, NS_PER_S, &event), 1);
  assert_int_equal(event.line, 6);
  assert_int_equal(event.rising, 1);
  assert_int_equal(event.time_ns, 999 * NS_PER_S + 250);
  fake.event.event_type = GPIOD_LINE_EVENT_FALLING_EDGE;
  assert_int_equal(syncap_gpio_wait_edge(gpio, NS_PER_S, &event), 1);
  assert_int_equal(event.rising, 0);
  fake.wait_result = 0;
  assert_int_equal(syncap_gpio_wait_edge(gpio, 1000, &event), 0);
  syncap_gpio_close(gpio);
}

// Kernels before 5.7 stamp line events with CLOCK_REALTIME.
static void realtime_event_timestamps_are_converted(void** state) {
  (void)state;
  const int64_t mono = 1000 * NS_PER_S;
  const int64_t real = INT64_C(1795000000) * NS_PER_S;
  assert_int_equal(syncap_gpiod_event_monotonic_ns(mono - 5000, mono, real), mono - 5000);
  assert_int_equal(syncap_gpiod_event_monotonic_ns(real - 5000, mono, real), mono - 5000);

  struct syncap_gpio* gpio = syncap_gpio_open("gpiochip0");
  const unsigned inputs[] = {4};
  assert_int_equal(syncap_gpio_request_inputs(gpio, inputs, 1, "syncap-trigger"), 0);
  fake.wait_result = 1;
  fake.event_line = 4;
  fake.event = (struct gpiod_line_event){.ts = {INT64_C(1795000000) - 1, 0},
                                         .event_type = GPIOD_LINE_EVENT_RISING_EDGE};
  struct syncap_gpio_event event;
  assert_int_equal(syncap_gpio_wait_edge(gpio, NS_PER_S, &event), 1);
  assert_int_equal(event.time_ns, 999 * NS_PER_S);
  syncap_gpio_close(gpio);
}

static void inputs_and_outputs_may_not_share_a_line(void** state) {
  (void)state;
  const unsigned offsets[] = {3};
  struct syncap_gpio* gpio = open_with_outputs(offsets, 1);
  errno = 0;
  assert_int_equal(syncap_gpio_request_inputs(gpio, offsets, 1, "syncap-trigger"), -1);
  assert_int_equal(errno, EINVAL);
  syncap_gpio_close(gpio);
}

#define CASE(name) cmocka_unit_test_setup_teardown(name, set_up, tear_down)

static const struct CMUnitTest tests[] = {
    CASE(opens_by_name_path_and_label),
    CASE(missing_chip_is_enoent_with_a_message_naming_it),
    CASE(outputs_are_requested_low_for_the_consumer),
    CASE(set_all_drives_every_line_in_one_call),
    CASE(close_drives_low_then_releases_then_closes),
    CASE(busy_line_is_ebusy),
    CASE(offset_beyond_the_chip_is_einval),
    CASE(input_edges_carry_the_kernels_monotonic_timestamp),
    CASE(realtime_event_timestamps_are_converted),
    CASE(inputs_and_outputs_may_not_share_a_line),
};

SYNCAP_CMOCKA_MAIN(tests)
