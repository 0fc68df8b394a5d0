#!/usr/bin/env bash
# Installs, configures, builds and runs every test through ctest (unit, hil, data), warnings as
# errors. Ends with ctest's summary line. .ci/run calls exactly this.
# Extra arguments go to ctest (e.g. -L unit, -R proto, --output-on-failure is always on).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${SYNCAP_BUILD_DIR:-build}
# The package test (label package) builds, checks and installs the Debian packages.
scripts/deps.sh package
# Without debug information: the build takes half the time and runs the same code.
scripts/build.sh -DSYNCAP_WERROR=ON -DSYNCAP_DEBUG_INFO=OFF
export SYNCAP_DATA=${SYNCAP_DATA:-$(cd .. && pwd)/shared/data}
[ -d "$SYNCAP_DATA" ] || echo "test: real data absent at $SYNCAP_DATA; 'data' tests will skip"
exec ctest --test-dir "$build_dir" --output-on-failure --timeout 300 -j "$(nproc)" "$@"
