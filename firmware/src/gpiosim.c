// The shared simulated GPIO chip: one POSIX shared-memory object per chip, see gpiosim.h.
#define _DEFAULT_SOURCE  // syscall(): futexes have no libc wrapper
#include "syncap/trigger/gpiosim.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <linux/futex.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#define SHM_PREFIX "/syncap-gpiosim-"
#define PATH_PREFIX "/dev/shm/syncap-gpiosim-"
#define CHIP_MAGIC 0x53475053u  // "SGPS"
#define CHIP_VERSION 2u         // 2: a futex word instead of a pthread condition variable
#define NS_PER_S INT64_C(1000000000)
// How long an opener waits for a chip another process is creating right now.
#define CREATION_WAIT_NS (5 * NS_PER_S)
#define CREATION_POLL_NS (1000 * 1000)

struct shared_line {
  uint32_t level;
  uint32_t reserved;
  uint64_t run;
  uint64_t count;
  int64_t last_rise_ns;
  int64_t rise_ns[SYNCAP_GPIOSIM_HISTORY];  // rising edge c of the run at [(c - 1) % HISTORY]
};

// The layout of the shared-memory object. Every field but magic is guarded by mutex.
struct shared_chip {
  _Atomic uint32_t magic;  // CHIP_MAGIC once the creator has initialised everything else
  uint32_t version;
  uint32_t size;  // sizeof(struct shared_chip): a build with another layout refuses the chip
  uint32_t num_lines;
  pthread_mutex_t mutex;  // process-shared and robust: a watcher killed holding it blocks no one
  // Counts rising edges and claims; waiters sleep on it as a futex. Not a pthread condition
  // variable: glibc's are not robust, and a watcher killed inside pthread_cond_wait (the replay
  // bench's camera-unplug fault) made the trigger's next broadcast block forever in
  // __condvar_quiesce_and_switch_g1. A dead futex waiter leaves nothing behind.
  _Atomic uint32_t changes;
  struct shared_line lines[SYNCAP_GPIOSIM_NUM_LINES];
};

struct syncap_gpiosim {
  struct shared_chip* shared;
  char name[SYNCAP_GPIOSIM_NAME_MAX + 1];
};

static int64_t monotonic_ns(void) {
  struct timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  return (int64_t)now.tv_sec * NS_PER_S + now.tv_nsec;
}

static struct timespec timespec_of(int64_t ns) {
  return (struct timespec){.tv_sec = ns / NS_PER_S, .tv_nsec = ns % NS_PER_S};
}

bool syncap_gpiosim_name_is_valid(const char* name) {
  const size_t length = name != NULL ? strlen(name) : 0;
  if (length == 0 || length > SYNCAP_GPIOSIM_NAME_MAX || name[0] == '.' || name[0] == '-') {
    return false;
  }
  for (size_t i = 0; i < length; ++i) {
    const char c = name[i];
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '.' || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

bool syncap_gpiosim_path(const char* name, char* path, size_t size) {
  if (!syncap_gpiosim_name_is_valid(name)) return false;
  return (size_t)snprintf(path, size, PATH_PREFIX "%s", name) < size;
}

const char* syncap_gpiosim_describe_error(const char* name, int error, char* out, size_t size) {
  char path[SYNCAP_GPIOSIM_PATH_MAX];
  if (!syncap_gpiosim_path(name, path, sizeof(path))) {
    snprintf(out, size,
             "'%s' is not a valid shared GPIO chip name (1 to %d of A-Z a-z 0-9 . _ -, not "
             "starting with '.' or '-')",
             name != NULL ? name : "(null)", SYNCAP_GPIOSIM_NAME_MAX);
  } else if (error == ENOENT) {
    snprintf(out, size, "shared GPIO chip '%s' (%s) does not exist", name, path);
  } else if (error == EPROTO) {
    snprintf(out, size,
             "%s is not a shared GPIO chip of this version (half-created or stale; remove it with "
             "'syncap-gpiosim rm %s')",
             path, name);
  } else {
    snprintf(out, size, "shared GPIO chip '%s' (%s): %s", name, path, strerror(error));
  }
  return out;
}

// Locks the chip; 0 or an error number. A holder that died leaves only plain fields, each
// written whole, so the state is usable as it is and the mutex is simply made consistent again.
static int lock_chip(struct shared_chip* shared) {
  const int error = pthread_mutex_lock(&shared->mutex);
  if (error == EOWNERDEAD) return pthread_mutex_consistent(&shared->mutex);
  return error;
}

static void unlock_chip(struct shared_chip* shared) { pthread_mutex_unlock(&shared->mutex); }

static int init_sync(struct shared_chip* shared) {
  pthread_mutexattr_t mutex_attr;
  pthread_mutexattr_init(&mutex_attr);
  pthread_mutexattr_setpshared(&mutex_attr, PTHREAD_PROCESS_SHARED);
  pthread_mutexattr_setrobust(&mutex_attr, PTHREAD_MUTEX_ROBUST);
  const int error = pthread_mutex_init(&shared->mutex, &mutex_attr);
  pthread_mutexattr_destroy(&mutex_attr);
  atomic_store(&shared->changes, 0);
  return error;
}

// Wakes every waiter (called with the chip locked).
static void announce_change(struct shared_chip* shared) {
  atomic_fetch_add(&shared->changes, 1);
  // A shared futex (no FUTEX_PRIVATE_FLAG): the waiters are other processes.
  syscall(SYS_futex, &shared->changes, FUTEX_WAKE, INT_MAX, NULL, NULL, 0);
}

// Fills a freshly created (zeroed) object; the magic goes last so openers never see half of it.
static int init_chip(struct shared_chip* shared) {
  shared->version = CHIP_VERSION;
  shared->size = (uint32_t)sizeof(*shared);
  shared->num_lines = SYNCAP_GPIOSIM_NUM_LINES;
  const int error = init_sync(shared);
  if (error != 0) return error;
  atomic_store_explicit(&shared->magic, CHIP_MAGIC, memory_order_release);
  return 0;
}

static bool is_chip(struct shared_chip* shared) {
  return atomic_load_explicit(&shared->magic, memory_order_acquire) == CHIP_MAGIC &&
         shared->version == CHIP_VERSION && shared->size == sizeof(*shared) &&
         shared->num_lines == SYNCAP_GPIOSIM_NUM_LINES;
}

static void sleep_ns(int64_t ns) {
  const struct timespec pause = timespec_of(ns);
  nanosleep(&pause, NULL);
}

// Waits until the object has the chip's size: a creator sets it right after creating the name.
static bool wait_for_size(int fd) {
  const int64_t deadline_ns = monotonic_ns() + CREATION_WAIT_NS;
  for (;;) {
    struct stat status;
    if (fstat(fd, &status) == 0 && (size_t)status.st_size == sizeof(struct shared_chip)) {
      return true;
    }
    if (monotonic_ns() > deadline_ns) return false;
    sleep_ns(CREATION_POLL_NS);
  }
}

static bool wait_for_magic(struct shared_chip* shared) {
  const int64_t deadline_ns = monotonic_ns() + CREATION_WAIT_NS;
  while (!is_chip(shared)) {
    if (monotonic_ns() > deadline_ns) return false;
    sleep_ns(CREATION_POLL_NS);
  }
  return true;
}

static struct shared_chip* map_chip(int fd) {
  void* address = mmap(NULL, sizeof(struct shared_chip), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  return address == MAP_FAILED ? NULL : address;
}

// Creates the object under its name; NULL with errno (EEXIST when another process was first).
static struct shared_chip* create_chip(const char* shm_name) {
  const int fd = shm_open(shm_name, O_RDWR | O_CREAT | O_EXCL, 0600);
  if (fd < 0) return NULL;
  struct shared_chip* shared = NULL;
  if (ftruncate(fd, (off_t)sizeof(struct shared_chip)) == 0) shared = map_chip(fd);
  int error = shared == NULL ? errno : init_chip(shared);
  close(fd);
  if (error == 0) return shared;
  if (shared != NULL) munmap(shared, sizeof(*shared));
  shm_unlink(shm_name);  // a half-made chip would only make every later opener fail
  errno = error;
  return NULL;
}

static struct shared_chip* open_existing_chip(const char* shm_name) {
  const int fd = shm_open(shm_name, O_RDWR, 0);
  if (fd < 0) return NULL;
  struct shared_chip* shared = NULL;
  int error = EPROTO;
  if (wait_for_size(fd)) {
    shared = map_chip(fd);
    error = shared == NULL ? errno : 0;
  }
  close(fd);
  if (shared != NULL && !wait_for_magic(shared)) {
    munmap(shared, sizeof(*shared));
    shared = NULL;
    error = EPROTO;
  }
  if (shared == NULL) errno = error;
  return shared;
}

struct syncap_gpiosim* syncap_gpiosim_open(const char* name, bool create) {
  if (!syncap_gpiosim_name_is_valid(name)) {
    errno = EINVAL;
    return NULL;
  }
  char shm_name[sizeof(SHM_PREFIX) + SYNCAP_GPIOSIM_NAME_MAX];
  snprintf(shm_name, sizeof(shm_name), SHM_PREFIX "%s", name);
  struct shared_chip* shared = create ? create_chip(shm_name) : NULL;
  if (shared == NULL && (!create || errno == EEXIST)) shared = open_existing_chip(shm_name);
  if (shared == NULL) return NULL;
  struct syncap_gpiosim* chip = calloc(1, sizeof(*chip));
  if (chip == NULL) {
    munmap(shared, sizeof(*shared));
    errno = ENOMEM;
    return NULL;
  }
  chip->shared = shared;
  snprintf(chip->name, sizeof(chip->name), "%s", name);
  return chip;
}

void syncap_gpiosim_close(struct syncap_gpiosim* chip) {
  if (chip == NULL) return;
  munmap(chip->shared, sizeof(*chip->shared));
  free(chip);
}

int syncap_gpiosim_unlink(const char* name) {
  if (!syncap_gpiosim_name_is_valid(name)) {
    errno = EINVAL;
    return -1;
  }
  char shm_name[sizeof(SHM_PREFIX) + SYNCAP_GPIOSIM_NAME_MAX];
  snprintf(shm_name, sizeof(shm_name), SHM_PREFIX "%s", name);
  return shm_unlink(shm_name);
}

const char* syncap_gpiosim_name(const struct syncap_gpiosim* chip) { return chip->name; }

static bool lines_are_valid(const unsigned* lines, size_t num_lines) {
  for (size_t i = 0; i < num_lines; ++i) {
    if (lines[i] >= SYNCAP_GPIOSIM_NUM_LINES) return false;
  }
  return true;
}

// Sets errno from an error number; -1 when there is one, else 0.
static int fail_with(int error) {
  if (error == 0) return 0;
  errno = error;
  return -1;
}

int syncap_gpiosim_claim_lines(struct syncap_gpiosim* chip, const unsigned* lines,
                               size_t num_lines) {
  if (!lines_are_valid(lines, num_lines)) return fail_with(EINVAL);
  struct shared_chip* shared = chip->shared;
  const int error = lock_chip(shared);
  if (error != 0) return fail_with(error);
  for (size_t i = 0; i < num_lines; ++i) {
    struct shared_line* line = &shared->lines[lines[i]];
    ++line->run;
    line->count = 0;
    line->level = 0;
    line->last_rise_ns = 0;
  }
  announce_change(shared);
  unlock_chip(shared);
  return 0;
}

// Applies a level to one line; true when that was a rising edge.
static bool set_level(struct shared_line* line, uint32_t level, int64_t time_ns) {
  const bool rising = level == 1 && line->level == 0;
  line->level = level;
  if (!rising) return false;
  ++line->count;
  line->rise_ns[(line->count - 1) % SYNCAP_GPIOSIM_HISTORY] = time_ns;
  line->last_rise_ns = time_ns;
  return true;
}

int syncap_gpiosim_set_lines(struct syncap_gpiosim* chip, const unsigned* lines, size_t num_lines,
                             int value, int64_t* time_ns) {
  if (!lines_are_valid(lines, num_lines)) return fail_with(EINVAL);
  struct shared_chip* shared = chip->shared;
  const int error = lock_chip(shared);
  if (error != 0) return fail_with(error);
  const int64_t now_ns = monotonic_ns();  // all lines switch at this one instant
  bool any_rising = false;
  for (size_t i = 0; i < num_lines; ++i) {
    any_rising |= set_level(&shared->lines[lines[i]], value != 0, now_ns);
  }
  if (any_rising) announce_change(shared);
  unlock_chip(shared);
  if (time_ns != NULL) *time_ns = now_ns;
  return 0;
}

int syncap_gpiosim_read_line(struct syncap_gpiosim* chip, unsigned line,
                             struct syncap_gpiosim_line* state) {
  if (line >= SYNCAP_GPIOSIM_NUM_LINES) return fail_with(EINVAL);
  struct shared_chip* shared = chip->shared;
  const int error = lock_chip(shared);
  if (error != 0) return fail_with(error);
  const struct shared_line* l = &shared->lines[line];
  *state = (struct syncap_gpiosim_line){
      .level = (int)l->level, .run = l->run, .count = l->count, .last_rise_ns = l->last_rise_ns};
  unlock_chip(shared);
  return 0;
}

// The rising edge after *rise, if the line has one (see syncap_gpiosim_wait_rising).
static bool find_next_rise(const struct shared_line* line, struct syncap_gpiosim_rise* rise) {
  uint64_t wanted = line->run == rise->run ? rise->count + 1 : 1;
  if (line->count < wanted) return false;
  const uint64_t oldest_kept =
      line->count > SYNCAP_GPIOSIM_HISTORY ? line->count - SYNCAP_GPIOSIM_HISTORY + 1 : 1;
  if (wanted < oldest_kept) wanted = oldest_kept;
  *rise = (struct syncap_gpiosim_rise){
      .run = line->run,
      .count = wanted,
      .time_ns = line->rise_ns[(wanted - 1) % SYNCAP_GPIOSIM_HISTORY],
  };
  return true;
}

// One wait for a change, entered and left with the chip locked; 0, ETIMEDOUT or another error
// number. The count is read under the lock, so a change between unlocking and sleeping makes the
// futex wait return at once (EAGAIN) instead of being missed.
static int wait_changed(struct shared_chip* shared, const struct timespec* deadline) {
  const uint32_t seen = atomic_load(&shared->changes);
  unlock_chip(shared);
  // FUTEX_WAIT_BITSET: the deadline is absolute, on CLOCK_MONOTONIC; NULL waits for ever.
  const long result = syscall(SYS_futex, &shared->changes, FUTEX_WAIT_BITSET, seen, deadline, NULL,
                              FUTEX_BITSET_MATCH_ANY);
  const int wait_error = result == -1 && errno == ETIMEDOUT ? ETIMEDOUT : 0;
  const int lock_error = lock_chip(shared);
  return lock_error != 0 ? lock_error : wait_error;
}

int syncap_gpiosim_wait_rising(struct syncap_gpiosim* chip, unsigned line, int64_t timeout_ns,
                               struct syncap_gpiosim_rise* rise) {
  if (line >= SYNCAP_GPIOSIM_NUM_LINES) return fail_with(EINVAL);
  const struct timespec deadline = timespec_of(monotonic_ns() + (timeout_ns > 0 ? timeout_ns : 0));
  struct shared_chip* shared = chip->shared;
  int error = lock_chip(shared);
  if (error != 0) return fail_with(error);
  while (!find_next_rise(&shared->lines[line], rise)) {
    error = wait_changed(shared, timeout_ns >= 0 ? &deadline : NULL);
    if (error != 0) break;
  }
  // A timeout that raced with an edge still hands the edge out.
  if (error == ETIMEDOUT && find_next_rise(&shared->lines[line], rise)) error = 0;
  unlock_chip(shared);
  return fail_with(error);
}
