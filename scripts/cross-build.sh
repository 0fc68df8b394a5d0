#!/usr/bin/env bash
# scripts/cross-build.sh arm64 [--host] [--test] [CMAKE_ARGS...]
# Cross-compiles syncap for arm64 boards (Raspberry Pi 4/5, Jetson, i.MX8, RK3588 with Debian
# bookworm or a derivative) into build-arm64/ (or $SYNCAP_CROSS_BUILD_DIR): firmware/ and edge/
# with their tests and the edge benchmarks; --host adds the host, its tools and the replay bench.
# --test then runs the emulated tests (ctest -L emulated: the unit tests of proto, firmware and
# edge, and the edge benchmarks' checks, under qemu-aarch64). Installs what it needs
# (scripts/deps.sh cross) and makes the arm64 sysroot (scripts/arm64-sysroot.sh, in
# build-sysroot-arm64/ or $SYNCAP_SYSROOT). Warnings are errors, as in CI. docs/guide/deploy.md.
set -euo pipefail
cd "$(dirname "$0")/.."
arch=${1:-}
if [ "$arch" != arm64 ]; then
  echo "usage: scripts/cross-build.sh arm64 [--host] [--test] [CMAKE_ARGS...] (only arm64 so far)" >&2
  exit 2
fi
shift
host=OFF
run_tests=false
cmake_args=()
for arg in "$@"; do
  case "$arg" in
    --host) host=ON ;;
    --test) run_tests=true ;;
    *) cmake_args+=("$arg") ;;
  esac
done
build_dir=${SYNCAP_CROSS_BUILD_DIR:-build-arm64}
sysroot=${SYNCAP_SYSROOT:-$PWD/build-sysroot-arm64}

scripts/deps.sh cross
scripts/arm64-sysroot.sh "$sysroot"
start=$(date +%s)
cmake -S . -B "$build_dir" -G Ninja \
  -DCMAKE_TOOLCHAIN_FILE="$PWD/cmake/toolchains/aarch64-linux-gnu.cmake" \
  -DSYNCAP_SYSROOT="$sysroot" -DSYNCAP_BUILD_HOST="$host" \
  -DSYNCAP_WERROR=ON -DSYNCAP_DEBUG_INFO=OFF "${cmake_args[@]}"
cmake --build "$build_dir" --parallel "$(nproc)"
echo "cross-build: arm64 build in $build_dir took $(( $(date +%s) - start )) s"
if $run_tests; then
  start=$(date +%s)
  ctest --test-dir "$build_dir" -L emulated --output-on-failure --timeout 600 -j "$(nproc)"
  echo "cross-build: the emulated tests took $(( $(date +%s) - start )) s"
fi
