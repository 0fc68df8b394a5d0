// syncap-trigger: the trigger daemon (trigger_daemon.h) with its options from the command line
// and the config file, in real time and stopped by SIGINT/SIGTERM. See docs/design/trigger.md.
#include <stdint.h>

#include "syncap/trigger/trigger.h"
#include "trigger_daemon.h"
#include "trigger_options.h"

int main(int argc, char** argv) {
  struct trigger_options options;
  const enum trigger_options_result parsed = trigger_options_parse(argc, argv, &options);
  if (parsed != TRIGGER_OPTIONS_RUN) {
    trigger_options_free(&options);
    return parsed == TRIGGER_OPTIONS_HELP ? TRIGGER_DAEMON_OK : TRIGGER_DAEMON_USAGE;
  }
  // Bench: a count run of rate * seconds pulses, without LCM.
  if (options.bench_seconds > 0 && options.rate_hz >= SYNCAP_TRIGGER_MIN_RATE_HZ &&
      options.rate_hz <= SYNCAP_TRIGGER_MAX_RATE_HZ) {
    options.count = (uint64_t)(options.rate_hz * (double)options.bench_seconds);
    if (options.count == 0) options.count = 1;
  }
  const struct trigger_daemon_settings settings = {.realtime = true, .signals = true};
  const int status = trigger_daemon_run(&options, &settings);
  trigger_options_free(&options);
  return status;
}
