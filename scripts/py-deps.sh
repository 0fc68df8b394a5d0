#!/usr/bin/env bash
# Installs the Python packages the tests use into a venv (Debian 12's system pip is "externally
# managed", PEP 668): the independent C3D readers ezc3d and c3d and the BVH reader bvh from PyPI,
# which read the trajectory and motion exports back (tests/host/io/check_exports.py); the viewer
# `syncap view` (host/viewer, docs/guide/view.md): rerun-sdk, the lcm bindings, and what rerun-sdk
# pulls in (numpy, pyarrow, attrs, pillow, psutil, typing_extensions), pinned too, so that every
# venv holds the same versions. The venv is $SYNCAP_PY_VENV, default
# <build dir>/py-venv, where the tests and host/viewer/syncap-view look for it.
# Idempotent: nothing is done when the pinned versions are already there.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=${SYNCAP_PY_VENV:-${SYNCAP_BUILD_DIR:-build}/py-venv}
PACKAGES=(ezc3d==1.7.2 c3d==0.6.0 bvh==0.3
  rerun-sdk==0.41.0 lcm==1.5.3 numpy==2.4.6 pyarrow==26.0.1 attrs==26.1.0 pillow==13.0.0
  psutil==7.2.2 typing_extensions==4.16.0)

installed() {
  "$venv/bin/python3" - "${PACKAGES[@]}" <<'PY' 2>/dev/null
import sys
from importlib.metadata import version
sys.exit(0 if all(version(p.split("==")[0]) == p.split("==")[1] for p in sys.argv[1:]) else 1)
PY
}

if [ -x "$venv/bin/python3" ] && installed; then
  echo "py-deps: ${PACKAGES[*]} already in $venv"
  exit 0
fi
echo "py-deps: installing ${PACKAGES[*]} into $venv"
mkdir -p "$(dirname "$venv")"
# python3 -m venv needs Debian's python3-venv (scripts/deps.sh installs it).
"${PYTHON:-python3}" -m venv "$venv"
"$venv/bin/python3" -m pip install --quiet --disable-pip-version-check "${PACKAGES[@]}"
installed
echo "py-deps: done"
