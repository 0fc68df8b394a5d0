// The main of every cmocka test program: SYNCAP_CMOCKA_MAIN(tests) after the CMUnitTest array.
//   <exe>          runs every case
//   <exe> --list   prints the case names, one per line (what syncap_cmocka_test() discovers)
//   <exe> CASE     runs that one case; a name that is no case fails (exit 2)
// The exact-name check matters: cmocka 1.1.5's filter is a glob, and a filter matching nothing
// runs 0 tests and exits 0, so a renamed case would otherwise pass silently in ctest.
#pragma once

// cmocka.h needs these first.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <stdio.h>
#include <string.h>

// Returns the exit status when the arguments ask for something other than running cases, or -1
// to run them (all, or the one selected through cmocka's filter).
static inline int syncap_cmocka_select(int argc, char** argv, const struct CMUnitTest* tests,
                                       size_t count) {
  if (argc == 1) return -1;
  if (argc == 2 && strcmp(argv[1], "--list") == 0) {
    for (size_t i = 0; i < count; ++i) printf("%s\n", tests[i].name);
    return 0;
  }
  if (argc == 2 && argv[1][0] != '-') {
    for (size_t i = 0; i < count; ++i) {
      if (strcmp(argv[1], tests[i].name) == 0) {
        cmocka_set_test_filter(argv[1]);
        return -1;
      }
    }
    fprintf(stderr, "%s: no test case named '%s' (see --list)\n", argv[0], argv[1]);
    return 2;
  }
  fprintf(stderr, "usage: %s [--list | CASE]\n", argv[0]);
  return 2;
}

#define SYNCAP_CMOCKA_MAIN(tests)                                                             \
  int main(int argc, char** argv) {                                                           \
    int status = syncap_cmocka_select(argc, argv, tests, sizeof(tests) / sizeof((tests)[0])); \
    return status >= 0 ? status : cmocka_run_group_tests(tests, NULL, NULL);                  \
  }
