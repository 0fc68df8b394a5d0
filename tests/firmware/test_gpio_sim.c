// The GPIO API on the "sim" backend: specs, line requests, edge recording, release, the ring.
#include "cmocka_main.h"

#include <errno.h>

#include "syncap/trigger/gpio.h"
#include "syncap/trigger/gpio_sim.h"

static struct syncap_gpio* open_sim_with_lines(const char* spec, const unsigned* offsets,
                                               size_t num_lines) {
  struct syncap_gpio* gpio = syncap_gpio_open(spec);
  assert_non_null(gpio);
  assert_int_equal(syncap_gpio_request_outputs(gpio, offsets, num_lines, "test"), 0);
  return gpio;
}

static void unknown_backend_is_enodev(void** state) {
  (void)state;
  errno = 0;
  assert_null(syncap_gpio_open("flash"));  // neither sim nor gpiochipN, a path or gpiod:
  assert_int_equal(errno, ENODEV);
  assert_null(syncap_gpio_open("simulator"));
  assert_int_equal(errno, ENODEV);
}

static void malformed_sim_spec_is_einval(void** state) {
  (void)state;
  // "sim:abc" would name a shared chip; names with '/' or a leading '-' are not valid ones.
  const char* specs[] = {"sim:", "sim:0", "sim:a/b", "sim:-4", "sim:1000001", "sim:.x"};
  for (size_t i = 0; i < sizeof(specs) / sizeof(specs[0]); ++i) {
    errno = 0;
    assert_null(syncap_gpio_open(specs[i]));
    assert_int_equal(errno, EINVAL);
  }
}

static void sim_backend_is_named_sim(void** state) {
  (void)state;
  struct syncap_gpio* gpio = syncap_gpio_open("sim:16");
  assert_non_null(gpio);
  assert_string_equal(syncap_gpio_backend_name(gpio), "sim");
  syncap_gpio_close(gpio);
}

static void request_rejects_bad_line_sets(void** state) {
  (void)state;
  struct syncap_gpio* gpio = syncap_gpio_open("sim");
  const unsigned duplicates[] = {3, 4, 3};
  const unsigned beyond_chip[] = {SYNCAP_GPIO_SIM_NUM_LINES};
  unsigned too_many[SYNCAP_GPIO_MAX_LINES + 1];
  for (unsigned i = 0; i < SYNCAP_GPIO_MAX_LINES + 1; ++i) too_many[i] = i;
  assert_int_equal(syncap_gpio_request_outputs(gpio, duplicates, 0, "test"), -1);
  assert_int_equal(errno, EINVAL);
  assert_int_equal(syncap_gpio_request_outputs(gpio, duplicates, 3, "test"), -1);
  assert_int_equal(errno, EINVAL);
  assert_int_equal(syncap_gpio_request_outputs(gpio, beyond_chip, 1, "test"), -1);
  assert_int_equal(errno, EINVAL);
  assert_int_equal(syncap_gpio_request_outputs(gpio, too_many, SYNCAP_GPIO_MAX_LINES + 1, "t"), -1);
  assert_int_equal(errno, EINVAL);
  syncap_gpio_close(gpio);
}

static void second_request_is_ebusy(void** state) {
  (void)state;
  const unsigned lines[] = {1};
  struct syncap_gpio* gpio = open_sim_with_lines("sim", lines, 1);
  assert_int_equal(syncap_gpio_request_outputs(gpio, lines, 1, "test"), -1);
  assert_int_equal(errno, EBUSY);
  syncap_gpio_close(gpio);
}

static void set_without_lines_is_eperm(void** state) {
  (void)state;
  struct syncap_gpio* gpio = syncap_gpio_open("sim");
  assert_int_equal(syncap_gpio_set_all(gpio, 1), -1);
  assert_int_equal(errno, EPERM);
  syncap_gpio_close(gpio);
}

// All lines switch at one instant, in request order; each set is one edge per line.
static void set_all_records_an_edge_per_line(void** state) {
  (void)state;
  const unsigned lines[] = {7, 2, 40};
  struct syncap_gpio* gpio = open_sim_with_lines("sim", lines, 3);
  assert_int_equal(syncap_gpio_set_all(gpio, 1), 0);
  assert_int_equal(syncap_gpio_set_all(gpio, 0), 0);
  struct syncap_gpio_edge edges[8];
  assert_int_equal(syncap_gpio_sim_edges(gpio, edges, 8), 6);
  for (size_t i = 0; i < 6; ++i) {
    assert_int_equal(edges[i].line, lines[i % 3]);
    assert_int_equal(edges[i].value, i < 3 ? 1 : 0);
    assert_int_equal(edges[i].time_ns, edges[i - i % 3].time_ns);
  }
  assert_true(edges[3].time_ns >= edges[0].time_ns);
  assert_int_equal(syncap_gpio_sim_dropped(gpio), 0);
  syncap_gpio_close(gpio);
}

// A mask switches only its lines, in one instant; lines already at the level are left alone.
static void set_lines_switches_only_the_masked_lines(void** state) {
  (void)state;
  const unsigned lines[] = {7, 2, 40};
  struct syncap_gpio* gpio = open_sim_with_lines("sim", lines, 3);
  assert_int_equal(syncap_gpio_set_lines(gpio, 0x5, 1), 0);  // 7 and 40
  assert_int_equal(syncap_gpio_set_lines(gpio, 0x3, 1), 0);  // 2 only: 7 is high already
  assert_int_equal(syncap_gpio_set_all(gpio, 0), 0);
  assert_int_equal(syncap_gpio_set_lines(gpio, 0x8, 1), -1);  // no 4th line
  assert_int_equal(errno, EINVAL);
  struct syncap_gpio_edge edges[8];
  assert_int_equal(syncap_gpio_sim_edges(gpio, edges, 8), 6);
  assert_int_equal(edges[0].line, 7);
  assert_int_equal(edges[1].line, 40);
  assert_int_equal(edges[1].time_ns, edges[0].time_ns);
  assert_int_equal(edges[2].line, 2);
  assert_int_equal(edges[2].value, 1);
  for (size_t i = 3; i < 6; ++i) {
    assert_int_equal(edges[i].line, lines[i - 3]);
    assert_int_equal(edges[i].value, 0);
  }
  syncap_gpio_close(gpio);
}

static void same_level_again_records_nothing(void** state) {
  (void)state;
  const unsigned lines[] = {0};
  struct syncap_gpio* gpio = open_sim_with_lines("sim", lines, 1);
  assert_int_equal(syncap_gpio_set_all(gpio, 0), 0);  // lines start low
  assert_int_equal(syncap_gpio_set_all(gpio, 5), 0);  // any non-zero value is high
  assert_int_equal(syncap_gpio_set_all(gpio, 1), 0);
  struct syncap_gpio_edge edges[4];
  assert_int_equal(syncap_gpio_sim_edges(gpio, edges, 4), 1);
  assert_int_equal(edges[0].value, 1);
  syncap_gpio_close(gpio);
}

static void release_leaves_lines_low(void** state) {
  (void)state;
  const unsigned lines[] = {3, 4};
  struct syncap_gpio* gpio = open_sim_with_lines("sim", lines, 2);
  assert_int_equal(syncap_gpio_set_all(gpio, 1), 0);
  syncap_gpio_release(gpio);
  struct syncap_gpio_edge edges[8];
  assert_int_equal(syncap_gpio_sim_edges(gpio, edges, 8), 4);
  assert_int_equal(edges[2].value, 0);
  assert_int_equal(edges[3].value, 0);
  // Released lines can be requested again, and a release without lines does nothing.
  assert_int_equal(syncap_gpio_request_outputs(gpio, lines, 2, "test"), 0);
  syncap_gpio_release(gpio);
  syncap_gpio_release(gpio);
  assert_int_equal(syncap_gpio_sim_edges(gpio, edges, 8), 4);
  syncap_gpio_close(gpio);
}

static void full_ring_drops_the_oldest(void** state) {
  (void)state;
  const unsigned lines[] = {9};
  struct syncap_gpio* gpio = open_sim_with_lines("sim:4", lines, 1);
  for (int i = 0; i < 6; ++i) assert_int_equal(syncap_gpio_set_all(gpio, i % 2 == 0), 0);
  struct syncap_gpio_edge edges[8];
  assert_int_equal(syncap_gpio_sim_edges(gpio, edges, 8), 4);
  assert_int_equal(syncap_gpio_sim_dropped(gpio), 2);
  for (size_t i = 0; i < 4; ++i) assert_int_equal(edges[i].value, i % 2 == 0);
  assert_int_equal(syncap_gpio_sim_edges(gpio, edges, 2), 2);  // bounded by max
  syncap_gpio_close(gpio);
}

static void close_accepts_null(void** state) {
  (void)state;
  syncap_gpio_close(NULL);
}

static const struct CMUnitTest tests[] = {
    cmocka_unit_test(unknown_backend_is_enodev),
    cmocka_unit_test(malformed_sim_spec_is_einval),
    cmocka_unit_test(sim_backend_is_named_sim),
    cmocka_unit_test(request_rejects_bad_line_sets),
    cmocka_unit_test(second_request_is_ebusy),
    cmocka_unit_test(set_without_lines_is_eperm),
    cmocka_unit_test(set_all_records_an_edge_per_line),
    cmocka_unit_test(set_lines_switches_only_the_masked_lines),
    cmocka_unit_test(same_level_again_records_nothing),
    cmocka_unit_test(release_leaves_lines_low),
    cmocka_unit_test(full_ring_drops_the_oldest),
    cmocka_unit_test(close_accepts_null),
};

SYNCAP_CMOCKA_MAIN(tests)
