#!/usr/bin/env bash
# Writes the sample exports and reads them back with independent readers (check_exports.py).
# Usage: check_exports.sh <python> <syncap-io-export-samples> <output folder>
# Exits 77 (skip) when <python> is missing: scripts/py-deps.sh makes it.
set -euo pipefail
python=$1 samples=$2 out=$3
if [ ! -x "$python" ]; then
  echo "SKIP: no Python with ezc3d/c3d at $python (run scripts/py-deps.sh)"
  exit 77
fi
rm -rf "$out"
mkdir -p "$out"
"$samples" "$out"
exec "$python" "$(dirname "$0")/check_exports.py" "$out"
