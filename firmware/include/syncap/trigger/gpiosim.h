// A simulated GPIO chip shared between processes: the trigger drives its lines, fake cameras (or
// any other process) watch them. The chip is the POSIX shared-memory object
// /dev/shm/syncap-gpiosim-NAME holding, per line, the level, the run (bumped each time a writer
// claims the line) and within the run a 64-bit rising-edge counter with the CLOCK_MONOTONIC times
// of the last SYNCAP_GPIOSIM_HISTORY rising edges. A process-shared robust mutex and a condition
// variable on CLOCK_MONOTONIC let a watcher block until a line's next rising edge.
//
// Writer:  open(name, true); claim_lines(lines); set_lines(lines, 1); set_lines(lines, 0); ...
// Watcher: open(name, true); read_line(line) as the starting point; wait_rising(...) in a loop,
//          which hands out every rising edge once, in order, with its count and time.
//
// Functions returning int give 0, or -1 with errno set. Every call is thread-safe.
#pragma once

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SYNCAP_GPIOSIM_NUM_LINES 64
// Rising-edge times kept per line: a watcher up to this many edges behind still sees each one.
#define SYNCAP_GPIOSIM_HISTORY 256
// Longest chip name; names use A-Z a-z 0-9 . _ - and start with none of . -
#define SYNCAP_GPIOSIM_NAME_MAX 64
// Enough for the shared-memory path of any valid name, with its NUL.
#define SYNCAP_GPIOSIM_PATH_MAX (sizeof("/dev/shm/syncap-gpiosim-") + SYNCAP_GPIOSIM_NAME_MAX)

// An open shared chip (a mapping of it in this process).
struct syncap_gpiosim;

// A line as it is now.
struct syncap_gpiosim_line {
  int level;             // 0 low, 1 high
  uint64_t run;          // 0 until a writer first claims the line
  uint64_t count;        // rising edges in this run
  int64_t last_rise_ns;  // CLOCK_MONOTONIC of the latest rising edge; 0 when count is 0
};

// One rising edge: the `count`-th of run `run`, driven at time_ns (CLOCK_MONOTONIC).
struct syncap_gpiosim_rise {
  uint64_t run;
  uint64_t count;
  int64_t time_ns;
};

// Whether name is a valid chip name.
bool syncap_gpiosim_name_is_valid(const char* name);

// Writes "/dev/shm/syncap-gpiosim-NAME" into path (for messages); false for an invalid name.
bool syncap_gpiosim_path(const char* name, char* path, size_t size);

// Opens the chip; with create, creates it (every line low, run 0) when it does not exist yet.
// Two processes may race to create the same chip: one creates it, the other opens it. NULL with
// errno: EINVAL invalid name, ENOENT no such chip (and create false), EPROTO the object is not a
// chip of this layout, plus shm_open/mmap errors.
struct syncap_gpiosim* syncap_gpiosim_open(const char* name, bool create);

// Unmaps the chip; the chip itself stays until unlinked. NULL is allowed.
void syncap_gpiosim_close(struct syncap_gpiosim* chip);

// Removes the chip's name; processes that have it open keep using it, later opens create a new
// one. ENOENT when there is none, EINVAL for an invalid name.
int syncap_gpiosim_unlink(const char* name);

// The name the chip was opened with.
const char* syncap_gpiosim_name(const struct syncap_gpiosim* chip);

// A sentence naming the chip and what is wrong, for an errno from open or unlink, e.g.
// "shared GPIO chip 'cam' (/dev/shm/syncap-gpiosim-cam) does not exist". Returns out.
const char* syncap_gpiosim_describe_error(const char* name, int error, char* out, size_t size);

// Starts a new run on each line: run + 1, rising-edge count 0, level low. A writer calls this once
// before it drives the lines, so that watchers number the edges of its run from 1.
// EINVAL for a line >= SYNCAP_GPIOSIM_NUM_LINES.
int syncap_gpiosim_claim_lines(struct syncap_gpiosim* chip, const unsigned* lines,
                               size_t num_lines);

// Drives lines to value (0 low, anything else high) at one instant, read under the lock and
// stored in *time_ns when not NULL. Each line that goes low -> high is a rising edge: its count
// grows by one, the time is recorded and the watchers wake. EINVAL for a bad line.
int syncap_gpiosim_set_lines(struct syncap_gpiosim* chip, const unsigned* lines, size_t num_lines,
                             int value, int64_t* time_ns);

// The line's state now. EINVAL for a bad line.
int syncap_gpiosim_read_line(struct syncap_gpiosim* chip, unsigned line,
                             struct syncap_gpiosim_line* state);

// Waits for the rising edge after *rise (the last one the caller has seen; start from
// {state.run, state.count, state.last_rise_ns} of read_line to see only edges from now on) and
// overwrites *rise with it:
//  - same run: the edge numbered rise->count + 1; when that one has left the history (the caller
//    fell more than SYNCAP_GPIOSIM_HISTORY edges behind) the oldest kept one, so the count jumps;
//  - the line was claimed again since: the first kept edge of the new run (count 1 normally).
// Waits at most timeout_ns (< 0: without limit); ETIMEDOUT when no such edge came, EINVAL for a
// bad line.
int syncap_gpiosim_wait_rising(struct syncap_gpiosim* chip, unsigned line, int64_t timeout_ns,
                               struct syncap_gpiosim_rise* rise);

#ifdef __cplusplus
}
#endif
