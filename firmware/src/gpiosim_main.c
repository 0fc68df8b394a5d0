// syncap-gpiosim: looks at, watches and removes the shared simulated GPIO chips (gpiosim.h), so
// that a person can see what syncap-trigger --chip sim:NAME drives. See docs/design/trigger.md.
#include <errno.h>
#include <inttypes.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "syncap/trigger/gpiosim.h"

#define WATCH_SLICE_NS INT64_C(100000000)  // how often watch checks for SIGINT/SIGTERM

enum exit_status { STATUS_OK = 0, STATUS_FAILURE = 1, STATUS_USAGE = 2 };

static volatile sig_atomic_t stop_requested = 0;

static void request_stop(int signal_number) {
  (void)signal_number;
  stop_requested = 1;
}

static void usage(FILE* out) {
  fputs(
      "usage: syncap-gpiosim COMMAND NAME [ARGS]\n"
      "The simulated GPIO chips shared between processes (/dev/shm/syncap-gpiosim-NAME).\n"
      "  create NAME               create the chip (every line low) unless it exists\n"
      "  show NAME                 print each line ever claimed: level, run, rising edges\n"
      "  watch NAME LINE [COUNT]   print LINE's rising edges as they come, from now on;\n"
      "                            stop after COUNT edges (default: on SIGINT/SIGTERM)\n"
      "  rm NAME                   remove the chip\n",
      out);
}

static int report_open_error(const char* name, int error) {
  char why[256];
  fprintf(stderr, "syncap-gpiosim: %s\n",
          syncap_gpiosim_describe_error(name, error, why, sizeof(why)));
  return error == EINVAL ? STATUS_USAGE : STATUS_FAILURE;
}

static bool parse_unsigned(const char* text, uint64_t max, uint64_t* value) {
  char* end = NULL;
  errno = 0;
  const unsigned long long parsed = strtoull(text, &end, 10);
  if (errno != 0 || end == text || *end != '\0' || text[0] == '-' || parsed > max) return false;
  *value = parsed;
  return true;
}

static int show(struct syncap_gpiosim* chip) {
  printf("chip %s: line level run rising_edges last_rise_ns\n", syncap_gpiosim_name(chip));
  for (unsigned line = 0; line < SYNCAP_GPIOSIM_NUM_LINES; ++line) {
    struct syncap_gpiosim_line state;
    if (syncap_gpiosim_read_line(chip, line, &state) < 0) return STATUS_FAILURE;
    if (state.run == 0) continue;
    printf("%u %d %" PRIu64 " %" PRIu64 " %" PRId64 "\n", line, state.level, state.run, state.count,
           state.last_rise_ns);
  }
  return STATUS_OK;
}

static int watch(struct syncap_gpiosim* chip, unsigned line, uint64_t count) {
  signal(SIGINT, request_stop);
  signal(SIGTERM, request_stop);
  struct syncap_gpiosim_line state;
  if (syncap_gpiosim_read_line(chip, line, &state) < 0) return STATUS_FAILURE;
  struct syncap_gpiosim_rise rise = {state.run, state.count, state.last_rise_ns};
  for (uint64_t seen = 0; !stop_requested && (count == 0 || seen < count);) {
    if (syncap_gpiosim_wait_rising(chip, line, WATCH_SLICE_NS, &rise) < 0) {
      if (errno == ETIMEDOUT) continue;
      perror("syncap-gpiosim: waiting for an edge");
      return STATUS_FAILURE;
    }
    printf("line %u run %" PRIu64 " edge %" PRIu64 " at %" PRId64 " ns\n", line, rise.run,
           rise.count, rise.time_ns);
    fflush(stdout);
    ++seen;
  }
  return STATUS_OK;
}

// Runs create, show or watch, which need the chip open ("create" creates it when missing).
static int run_on_chip(const char* command, const char* name, int argc, char** argv) {
  uint64_t line = 0;
  uint64_t count = 0;
  const bool is_watch = strcmp(command, "watch") == 0;
  if (is_watch &&
      (argc < 1 || argc > 2 || !parse_unsigned(argv[0], SYNCAP_GPIOSIM_NUM_LINES - 1, &line) ||
       (argc == 2 && !parse_unsigned(argv[1], UINT64_MAX, &count)))) {
    fprintf(stderr, "syncap-gpiosim: watch needs LINE (0 to %d) and an optional COUNT\n",
            SYNCAP_GPIOSIM_NUM_LINES - 1);
    return STATUS_USAGE;
  }
  if (!is_watch && argc != 0) {
    fprintf(stderr, "syncap-gpiosim: unexpected argument '%s'\n", argv[0]);
    return STATUS_USAGE;
  }
  struct syncap_gpiosim* chip = syncap_gpiosim_open(name, strcmp(command, "create") == 0);
  if (chip == NULL) return report_open_error(name, errno);
  int status = STATUS_OK;
  if (strcmp(command, "show") == 0) status = show(chip);
  if (is_watch) status = watch(chip, (unsigned)line, count);
  syncap_gpiosim_close(chip);
  return status;
}

int main(int argc, char** argv) {
  if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
    usage(stdout);
    return STATUS_OK;
  }
  // It takes no options: one given is named, as every program names an unknown option.
  for (int i = 1; i < argc; ++i) {
    if (argv[i][0] == '-' && argv[i][1] != '\0') {
      fprintf(stderr, "syncap-gpiosim: unknown option '%s'\n", argv[i]);
      usage(stderr);
      return STATUS_USAGE;
    }
  }
  if (argc < 3) {
    usage(stderr);
    return STATUS_USAGE;
  }
  const char* command = argv[1];
  const char* name = argv[2];
  if (strcmp(command, "rm") == 0) {
    if (argc != 3) {
      usage(stderr);
      return STATUS_USAGE;
    }
    return syncap_gpiosim_unlink(name) == 0 ? STATUS_OK : report_open_error(name, errno);
  }
  if (strcmp(command, "create") != 0 && strcmp(command, "show") != 0 &&
      strcmp(command, "watch") != 0) {
    fprintf(stderr, "syncap-gpiosim: unknown command '%s'\n", command);
    usage(stderr);
    return STATUS_USAGE;
  }
  return run_on_chip(command, name, argc - 3, argv + 3);
}
