#!/usr/bin/env bash
# tests/hil/segment_lamps_run.sh BUILD OUT MIN_IOU
# The masking under changed illumination (docs/design/segmentation.md "Changed illumination"): renders
# ring-6cam-person-lamps (lamps drifting by 20 % and flickering by 5 %) at the short length and
# scores syncap-segment-eval with its defaults against the exact silhouettes: every camera's mean
# IoU must reach MIN_IOU. The same without the illumination correction must fall below it, or
# the scene would not test the correction. Exit 77 without the motion data (the person's BVH).
set -euo pipefail
trap 'echo "segment_lamps_run.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
[ $# -eq 3 ] || { sed -n '2,7p' "$0" >&2; exit 2; }
build=$1 out=$2 min_iou=$3
root=$(cd "$(dirname "$0")/../.." && pwd)
if [ ! -f "${SYNCAP_DATA:-/nonexistent}/motion/mixamo-free.bvh" ]; then
  echo "skipped: \$SYNCAP_DATA/motion/mixamo-free.bvh not found (SYNCAP_DATA=${SYNCAP_DATA:-unset})"
  exit 77
fi
rm -rf "$out" && mkdir -p "$out"
"$build/bin/syncap" sim --scenario "$root/hil/scenarios/ring-6cam-person-lamps.yaml" \
  --max-phase-frames 30 --out "$out/render" > "$out/sim.log"
# Lines "camera frames iou_mean ...", then one per camera; "all MEAN" last.
"$build/bin/syncap-segment-eval" --scene "$out/render" | tee "$out/with.txt"
"$build/bin/syncap-segment-eval" --scene "$out/render" --illumination off > "$out/without.txt"
echo "without the illumination correction:"; cat "$out/without.txt"
lowest() { awk '$1 ~ /^[0-9]+$/ { if (min == "" || $3 < min) min = $3 } END { print min }' "$1"; }
with=$(lowest "$out/with.txt") without=$(lowest "$out/without.txt")
echo "lowest camera mean IoU: $with with the correction, $without without (need >= $min_iou)"
awk -v a="$with" -v m="$min_iou" 'BEGIN { exit !(a >= m) }' ||
  { echo "FAIL: a camera's mean IoU $with < $min_iou with the correction" >&2; exit 1; }
awk -v b="$without" -v m="$min_iou" 'BEGIN { exit !(b < m) }' ||
  { echo "FAIL: without the correction $without >= $min_iou: the scene does not test it" >&2; exit 1; }
