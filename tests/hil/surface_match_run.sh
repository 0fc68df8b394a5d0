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
# A JSON file's number for a key: {"key":value,...}
value() { sed -E "s/.*\"$2\":([-0-9.e+]+).*/\1/" "$1"; }
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
  "$build/bin/syncap" match --cameras "$render/cameras.json" --images "$dir/images" \
    --masks "$dir/masks" --out "$dir/match" > "$dir/match.log"
  "$build/bin/syncap-hil-surface-check" --points "$dir/match/points.csv" --truth "$render" \
    --frame "$f" --json "$dir/check.json" > "$dir/check.txt"
  echo "frame $f: $(grep -E '^seeds' "$dir/match.log"); $(grep -E '^time' "$dir/match.log")"
  echo "  $(grep -E '^rejected' "$dir/match.log" | sed 's/^rejected, //' | paste -sd ';')"
  cat "$dir/check.txt"
  j=$dir/check.json
  awk -v rms="$(value "$j" rms_normal_mm)" -v n="$(value "$j" points)" \
      -v b="$(value "$j" blunders)" -v z="$(value "$j" rms_normalised)" \
      -v w="$(value "$j" within_3_sigma)" -v sweep="$(value "$j" sweep_rms_normal_mm)" '
    BEGIN {
      printf "  least squares %.3f mm, their GC3 peaks %.3f mm: %.1fx\n", rms, sweep, sweep / rms
      bad = 0
      if (rms > 1.5) { print "  FAIL: RMS on the normal > 1.5 mm"; bad = 1 }
      if (n < 100) { print "  FAIL: fewer than 100 points"; bad = 1 }
      if (b > 0.01 * n) { print "  FAIL: blunders > 1 %"; bad = 1 }
      if (z > 2.0 || w < 0.90) { print "  FAIL: the sigmas are far from honest"; bad = 1 }
      if (sweep < 3.5 * rms) { print "  FAIL: least squares not 3.5x more precise than GC3"; bad = 1 }
      exit bad
    }' || failed=1
done
exit $failed
