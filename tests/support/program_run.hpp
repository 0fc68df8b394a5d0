// Runs a built program through the shell and keeps what it printed and its exit status, for the
// tests that check a program's messages and exit codes.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace syncap::test {

struct ProgramRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

// `command` is a shell command line; its stderr is joined to stdout.
inline ProgramRun run_program(const std::string& command) {
  ProgramRun run;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return run;
  char buffer[4096];
  for (std::size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    run.output.append(buffer, n);
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace syncap::test
