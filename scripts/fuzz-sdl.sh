#!/usr/bin/env bash
# Fuzzes the SDL parser (host/src/sdl): scripts/fuzz.sh for that one target (docs/reference/sdl.md,
# "Fuzzing"; every target: docs/design/reliability.md, "Fuzzing").
#   scripts/fuzz-sdl.sh [RUNS] [LIBFUZZER ARGS...]     RUNS default 1000000
set -euo pipefail
runs=${1:-1000000}
if [ $# -gt 0 ]; then shift; fi
SYNCAP_FUZZ_ARGS="${SYNCAP_FUZZ_ARGS:-} $*" exec "$(dirname "$0")/fuzz.sh" "$runs" sdl_parser
