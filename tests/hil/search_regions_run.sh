#!/usr/bin/env bash
# tests/hil/search_regions_run.sh BUILD OUT
# The edges' search regions live (docs/design/segmentation.md, "Regions from the host"): hil/run's short
# ring-6cam-person with --search-regions, paced at 6 Hz so that the host's live body fit (every
# 4th frame, ~110-280 ms each on 2 cores beside six edges) keeps up. The run must pass as any (silhouette IoU >= 0.95
# per camera among its checks), and every edge must have obeyed at least one signed region.
# Exit 77 when hil/run skips (no motion data).
set -euo pipefail
trap 'echo "search_regions_run.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
[ $# -eq 2 ] || { sed -n '2,7p' "$0" >&2; exit 2; }
build=$1 out=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
status=0
"$root/hil/run" ring-6cam-person --short --rate 6 --search-regions --build "$build" \
  --out "$out" > "$out.log" 2>&1 || status=$?
[ "$status" -eq 77 ] && { cat "$out.log"; exit 77; }
grep -E "^== (silhouettes|   [0-9]  |PASS|FAIL)|host body" "$out.log" || true
[ "$status" -eq 0 ] || { echo "hil/run failed (exit $status), see $out.log" >&2; exit 1; }
for log in "$out"/edge??.log; do
  obeyed=$(sed -n 's/.* \([0-9]*\) commands obeyed.*/\1/p' "$log" | tail -n 1)
  echo "$(basename "$log" .log): ${obeyed:-0} search regions obeyed"
  [ "${obeyed:-0}" -ge 1 ] || { echo "FAIL: $log obeyed no search region" >&2; exit 1; }
done
