// Test helper: runs a program as a child process and waits for it with a time limit.
#pragma once

#include <sys/types.h>

// Starts argv[0] with argv (NULL-terminated); its stdout and stderr go to output_fd, or stay the
// test's own when output_fd < 0. Returns the pid, or -1 with errno set.
pid_t child_spawn(char* const argv[], int output_fd);

// Waits up to timeout_ms for the child to end and returns its wait status; on timeout kills it
// and returns -1.
int child_wait(pid_t pid, int timeout_ms);
