#!/usr/bin/env bash
# Installs the packages (scripts/deps.sh, scripts/py-deps.sh), configures and builds syncap into build/ (or $SYNCAP_BUILD_DIR).
# Extra arguments go to cmake's configure step (e.g. -DSYNCAP_WERROR=ON).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${SYNCAP_BUILD_DIR:-build}
scripts/deps.sh
# Without the Python packages (no registry reachable) the export check and the viewer's tests
# skip, the build goes on.
SYNCAP_BUILD_DIR="$build_dir" scripts/py-deps.sh ||
  echo "build: scripts/py-deps.sh failed; host.io.ExportsReadByIndependentReaders and host.viewer.* will skip"
if [ ! -f "$build_dir/build.ninja" ] || [ $# -gt 0 ]; then
  cmake -S . -B "$build_dir" -G Ninja "$@"
fi
cmake --build "$build_dir" --parallel "$(nproc)"
