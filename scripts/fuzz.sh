#!/usr/bin/env bash
# Fuzzes every decoder that takes outside input with libFuzzer under AddressSanitizer,
# LeakSanitizer and UndefinedBehaviorSanitizer, in its own build folder (docs/design/reliability.md,
# "Fuzzing"; the targets: tests/fuzz/CMakeLists.txt and tests/host/sdl).
#   scripts/fuzz.sh [RUNS] [TARGET...]     RUNS default 1000000; TARGETs default all of them
#   scripts/fuzz.sh --list                 the target names
# Each target starts from its seeds in the repository (tests/fuzz/corpus/<target>/; the SDL
# parser's are its test scenes) and grows its corpus in the build folder. One summary line a
# target: inputs run, executions a second, corpus size, seconds.
# Needs clang and its runtimes (scripts/deps.sh installs clang and libclang-rt-14-dev).
# Environment: SYNCAP_FUZZ_BUILD (default build-fuzz), SYNCAP_FUZZ_SEED (default 1),
# SYNCAP_FUZZ_ARGS (more libFuzzer options, e.g. "-max_total_time=60").
# Exit status: 0 when every target passed all runs; 1 otherwise (its crash-*, leak-* or
# timeout-* input is in the build folder, its log in fuzz-logs/).
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
build=${SYNCAP_FUZZ_BUILD:-$root/build-fuzz}
all_targets=(lcm_messages contour_codec image_patch frame_grouper lcm_log cameras_json frame_json
  scenario_yaml csv_observations mcsc_observations truth_csv bvh edge_config sdl_parser)

if [ "${1:-}" = "--list" ]; then
  printf '%s\n' "${all_targets[@]}"
  exit 0
fi
runs=${1:-1000000}
if [ $# -gt 0 ]; then shift; fi
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=("${all_targets[@]}"); fi

if ! command -v clang++ >/dev/null; then
  echo "fuzz: clang++ not found (scripts/deps.sh installs it)" >&2
  exit 2
fi

sanitizers="-fsanitize=fuzzer-no-link,address,leak,undefined -fno-sanitize-recover=undefined"
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" \
  -DCMAKE_CXX_FLAGS="$sanitizers -fno-omit-frame-pointer" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,leak,undefined" \
  -DSYNCAP_FUZZ=ON -DSYNCAP_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j2 --target "${targets[@]/#/fuzz_}"

# The seeds of a target: its folder in the repository (the SDL parser: its test scenes).
seed_folders() {
  if [ "$1" = sdl_parser ]; then
    echo "$root/tests/host/sdl/data $root/docs/examples"
  else
    echo "$root/tests/fuzz/corpus/$1"
  fi
}

# libFuzzer options beyond the shared ones: the SDL parser's scenes are longer, and it has a
# dictionary of its keywords.
target_options() {
  if [ "$1" = sdl_parser ]; then
    echo "-max_len=8192 -dict=$root/tests/host/sdl/sdl.dict"
  elif [ -f "$root/tests/fuzz/$1.dict" ]; then
    echo "-max_len=4096 -dict=$root/tests/fuzz/$1.dict"
  else
    echo "-max_len=4096"
  fi
}

mkdir -p "$build/fuzz-logs"
cd "$build"  # crash-*, leak-*, timeout-* files land here
failed=0
for target in "${targets[@]}"; do
  corpus=$build/fuzz-corpus/$target
  seeds=$build/fuzz-seeds/$target
  mkdir -p "$corpus" "$seeds"
  for folder in $(seed_folders "$target"); do
    find "$folder" -maxdepth 1 -type f ! -name '*.md' -exec cp {} "$seeds"/ \;
  done
  log=$build/fuzz-logs/$target.log
  start=$(date +%s)
  # shellcheck disable=SC2046,SC2086  # the options are words
  if "$build/bin/fuzz_$target" -runs="$runs" -seed="${SYNCAP_FUZZ_SEED:-1}" -timeout=10 \
    -detect_leaks=1 -print_final_stats=1 $(target_options "$target") ${SYNCAP_FUZZ_ARGS:-} \
    "$corpus" "$seeds" >"$log" 2>&1; then
    status=ok
  else
    status=FAILED
    failed=1
  fi
  seconds=$(($(date +%s) - start))
  executed=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  per_second=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  corpus_size=$(find "$corpus" -type f | wc -l)
  echo "fuzz $target: $status, ${executed:-?} inputs, ${per_second:-?} exec/s," \
    "corpus $corpus_size, ${seconds} s (log: $log)"
done
exit "$failed"
