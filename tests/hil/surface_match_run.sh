#!/usr/bin/env bash
# tests/hil/surface_match_run.sh BUILD OUT [FRAMES...]
# Surface matching on the replay bench (docs/design/matching.md, "Measured"): renders ring-6cam-person
# at the short length, runs `syncap match` on FRAMES of the person phase (default 62 70 78 86)
# with the exact masks (the hull's seeds) and scores each frame's points against the true body
# with syncap-hil-surface-check: RMS on the true normal <= 1.5 mm, blunders <= 1 %, at least 100
# points, the sigmas near honest (RMS of error/sigma <= 2, >= 90 % within 3 sigma), and least
# squares >= 3.5x more precise than the same points' GC3 peaks (the NCC sweep's answer on the
# same scan lines). Exit 77 without the motion data (the person's BVH).
set -euo pipefail
trap 'echo "surface_match_run.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
[ $# -ge 2 ] || { sed -n '2,9p' "$0" >&2; exit 2; }
build=$1 out=$2
shift 2
frames=("$@")
[ ${#frames[@]} -gt 0 ] || frames=(62 70 78 86)
root=$(cd "$(dirname "$0")/../.." && pwd)
if [ ! -f "${SYNCAP_DATA:-/nonexistent}/motion/mixamo-free.bvh" ]; then
  echo "skipped: \$SYNCAP_DATA/motion/mixamo-free.bvh not found (SYNCAP_DATA=${SYNCAP_DATA:-unset})"
  exit 77
fi
rm -rf "$out" && mkdir -p "$out"
render=$out/render
"$build/bin/syncap" sim --scenario "$root/hil/scenarios/ring-6cam-person.yaml" \
  --max-phase-frames 30 --out "$render" > "$out/sim.log"
failed=0
for f in "${frames[@]}"; do
  name=$(printf 'frame_%06d' "$f")
  dir=$out/$name
  mkdir -p "$dir/images" "$dir/masks"
  for cam in "$render"/camera*; do
    c=$(basename "$cam")
    ln -s "$cam/$name.pgm" "$dir/images/$c.pgm"
    ln -s "$render/truth/masks/$c/$(printf 'mask_%06d' "$f").png" "$dir/masks/$c.png"
  done
  "$build/bin/syncap" match --calibration "$render/cameras.json" --images "$dir/images" \
    --masks "$dir/masks" --out-dir "$dir/match" > "$dir/match.log"
  # The limits live in the checker.
  "$build/bin/syncap-hil-surface-check" --points "$dir/match/points.csv" --truth "$render" \
    --frame "$f" --json "$dir/check.json" --max-rms-mm 1.5 --min-points 100 \
    --max-blunder-fraction 0.01 --max-rms-error-over-sigma 2 --min-within-3-sigma 0.9 \
    --min-gain-over-gc3 3.5 > "$dir/check.txt" || failed=1
  echo "frame $f: $(grep -E '^seeds' "$dir/match.log"); $(grep -E '^time' "$dir/match.log")"
  echo "  $(grep -E '^rejected' "$dir/match.log" | sed 's/^rejected, //' | paste -sd ';')"
  cat "$dir/check.txt"
done
exit $failed
