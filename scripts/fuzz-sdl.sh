#!/usr/bin/env bash
# Fuzzes the SDL parser (host/src/sdl) with libFuzzer under AddressSanitizer, LeakSanitizer and
# UndefinedBehaviorSanitizer, in its own build folder (docs/sdl.md, "Fuzzing").
#   scripts/fuzz-sdl.sh [RUNS] [LIBFUZZER ARGS...]     RUNS default 1000000
# Needs clang and its runtimes (scripts/deps.sh installs clang and libclang-rt-14-dev).
# Environment: SYNCAP_FUZZ_BUILD (default build-fuzz), SYNCAP_FUZZ_SEED (default 1).
# Exit status: 0 when all runs passed; libFuzzer's (non-zero, crash-* file written) otherwise.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
build=${SYNCAP_FUZZ_BUILD:-$root/build-fuzz}
runs=${1:-1000000}
if [ $# -gt 0 ]; then shift; fi

if ! command -v clang++ >/dev/null; then
  echo "fuzz-sdl: clang++ not found (scripts/deps.sh installs it)" >&2
  exit 2
fi

sanitizers="-fsanitize=fuzzer-no-link,address,leak,undefined -fno-sanitize-recover=undefined"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS="$sanitizers -fno-omit-frame-pointer" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,leak,undefined" \
  -DSYNCAP_FUZZ=ON -DSYNCAP_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" --target fuzz_sdl_parser -j2

# The corpus grows in the build folder; the seeds are the repository's scenes.
corpus=$build/fuzz-sdl-corpus
seeds=$build/fuzz-sdl-seeds
mkdir -p "$corpus" "$seeds"
cp "$root"/tests/host/sdl/data/*.sdl "$seeds"/
cp "$root"/docs/examples/*.sdl "$seeds"/ 2>/dev/null || true

cd "$build"  # crash-*, leak-* files land here
exec "$build/bin/fuzz_sdl_parser" -runs="$runs" -seed="${SYNCAP_FUZZ_SEED:-1}" -max_len=8192 \
  -detect_leaks=1 -print_final_stats=1 -dict="$root/tests/host/sdl/sdl.dict" \
  "$corpus" "$seeds" "$@"
