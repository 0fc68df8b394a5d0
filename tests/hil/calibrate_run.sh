#!/usr/bin/env bash
# tests/hil/calibrate_run.sh BUILD OUT SCENARIO WAND_LENGTH_MM PIXEL_SIZE_MM MAX_REPROJECTION_PX
# The calibration end to end from the edges' blob messages: hil/run records the traffic of a
# short replay run (OUT/run/traffic.lcmlog), `syncap calibrate` calibrates from that log, and
# `syncap-hil-compare --calibration` checks the cameras against the truth after a similarity (the
# true targets reprojected through both camera sets). Then the live source: lcm-logplayer replays
# the log in a private namespace while `syncap calibrate --input lcm:URL` listens; its cameras
# pass the same check (they equal the log's to the last digits). Exit 77 when hil/run skips.
set -euo pipefail
trap 'echo "calibrate_run.sh: failed at line $LINENO: $BASH_COMMAND" >&2' ERR
[ $# -eq 6 ] || { sed -n '2,6p' "$0" >&2; exit 2; }
build=$1 out=$2 scenario=$3 wand=$4 pixel=$5 max_px=$6
root=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$out"
status=0
"$root/hil/run" "$scenario" --short --build "$build" --out "$out/run" > "$out/run.log" 2>&1 || status=$?
[ "$status" -eq 77 ] && { cat "$out/run.log"; exit 77; }
tail -n 3 "$out/run.log"
[ -s "$out/run/traffic.lcmlog" ] || { echo "no traffic.lcmlog (hil/run exit $status)" >&2; cat "$out/run.log" >&2; exit 1; }
"$build/bin/syncap" calibrate --input "lcmlog:$out/run/traffic.lcmlog" --wand-length-mm "$wand" \
  --pixel-size "$pixel" --out-dir "$out/calibration" --progress
"$build/bin/syncap-hil-compare" --truth "$out/run/render" --calibration "$out/calibration/cameras.json" \
  --max-reprojection-px "$max_px"

# The live source on the same traffic.
"$root/hil/netns-run" bash -c '
  url="udpm://239.255.76.67:7667?ttl=0"
  "$1/bin/syncap" calibrate --input "lcm:$url" --camera-ids "$2" --wand-length-mm "$3" --pixel-size "$4" \
    --idle-timeout-s 3 --out-dir "$5/live" > "$5/live.log" 2>&1 &
  sleep 1
  lcm-logplayer --lcm-url="$url" "$5/run/traffic.lcmlog" > /dev/null
  wait $!' _ "$build" "$(seq -s, 0 $(($(ls -d "$out"/run/render/camera?? | wc -l) - 1)))" \
  "$wand" "$pixel" "$out" || { cat "$out/live.log" >&2; exit 1; }
head -n 1 "$out/live.log"
"$build/bin/syncap-hil-compare" --truth "$out/run/render" --calibration "$out/live/cameras.json" \
  --max-reprojection-px "$max_px" | tail -n 2
