// The trigger daemon, the whole of syncap-trigger but its option parsing: from the options it
// creates the pulse schedule, claims the GPIO lines and opens LCM, then drives the lines and
// publishes every pulse's trigger_t and the heartbeats until its count is done or a stop is
// requested (a signal, or trigger_daemon_request_stop). A library so that tests run it in
// process (tests/firmware/test_trigger_daemon.c); syncap-trigger's main is a thin wrapper.
#ifndef SYNCAP_TRIGGER_DAEMON_H
#define SYNCAP_TRIGGER_DAEMON_H

#include <stdbool.h>

#include "trigger_options.h"

#ifdef __cplusplus
extern "C" {
#endif

// The exit statuses of syncap-trigger.
enum trigger_daemon_status {
  TRIGGER_DAEMON_OK = 0,
  TRIGGER_DAEMON_RUNTIME_ERROR = 1,  // a failure while running (GPIO), or LCM that cannot open
  TRIGGER_DAEMON_USAGE = 2,          // options the trigger or the chip refuse (named on stderr)
};

struct trigger_daemon_settings {
  bool realtime;  // SCHED_FIFO and locked memory (a refusal is one warning)
  bool signals;   // SIGINT and SIGTERM request a stop
};

// Runs the daemon to its end; prints the start line and the summary unless options->quiet, and
// why it stopped on stderr. Returns a trigger_daemon_status.
int trigger_daemon_run(const struct trigger_options* options,
                       const struct trigger_daemon_settings* settings);

// Asks a running daemon to stop at its next check (within 50 ms); safe from a signal handler.
void trigger_daemon_request_stop(void);

#ifdef __cplusplus
}
#endif

#endif
