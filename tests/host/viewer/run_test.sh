#!/usr/bin/env bash
# tests/host/viewer/run_test.sh PYTHON [--netns] MODULE.CLASS...
# Runs the viewer's unittest cases with the venv's Python (scripts/py-deps.sh makes it); skips
# (exit 77, ctest's SKIP_RETURN_CODE) saying why when the venv, rerun-sdk, lcm or lcm-gen is
# missing. With --netns the cases run inside a private network namespace (hil/netns-run).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
py=$1
shift
if [ ! -x "$py" ]; then
  echo "SKIP: no Python at $py: make the venv with scripts/py-deps.sh"
  exit 77
fi
if ! "$py" -c 'import rerun, lcm' 2>/dev/null; then
  echo "SKIP: $py lacks rerun-sdk or lcm: rerun scripts/py-deps.sh (it pins them)"
  exit 77
fi
if ! command -v lcm-gen >/dev/null && [ ! -x /usr/bin/lcm-gen ] && [ -z "${SYNCAP_LCM_GEN:-}" ]; then
  echo "SKIP: lcm-gen not found (Debian's liblcm-bin, scripts/deps.sh)"
  exit 77
fi
cd "$here"
if [ "${1:-}" = --netns ]; then
  shift
  exec "$here/../../../hil/netns-run" env SYNCAP_VIEWER_NETNS=1 "$py" -m unittest -v "$@"
fi
exec "$py" -m unittest -v "$@"
