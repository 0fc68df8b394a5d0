#!/usr/bin/env bash
# The main job, end to end on one machine: installs, configures, builds, then runs the system in
# a private network namespace with a simulated trigger and replayed cameras, and reports what
# arrived at the host. Options:
#   --frames N    pulses of the thin slice (default 60)   --out DIR   outputs (default out/demo)
set -euo pipefail
cd "$(dirname "$0")/.."
frames=60 out=out/demo
while [ $# -gt 0 ]; do
  case "$1" in
    --frames) frames=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    -h|--help) sed -n '2,6p' "$0"; exit 0 ;;
    *) echo "demo: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
build=${SYNCAP_BUILD_DIR:-build}

echo "demo: [1/5] installing packages and building into $build/"
scripts/build.sh > "${TMPDIR:-/tmp}/syncap-demo-build.log" 2>&1 ||
  { tail -n 30 "${TMPDIR:-/tmp}/syncap-demo-build.log"; echo "demo: build failed" >&2; exit 1; }

echo "demo: [2/5] thin slice: trigger -> 2 replaying edge processes -> host, private namespace"
echo "      ($frames pulses at 30 Hz; simulated GPIO chip; edges replay a rendered wand scene)"
status=0
hil/netns-run hil/run-slice --build "$build" --out "$out" --frames "$frames" || status=$?

echo "demo: [3/5] replay bench: hil/run ring-6cam-person --short (six fake GigE cameras"
echo "      triggered through the simulated GPIO chip, six edges segmenting the person, the host"
echo "      building the person's visual hull live; compared with the truth; then, through a"
echo "      calibration from the run's wand phase, the articulated body fitted to every hull)"
bench_status=0
ring_out=$out/ring-6cam-person
hil/run ring-6cam-person --short --build "$build" --out "$ring_out" || bench_status=$?
[ "$bench_status" -eq 77 ] && bench_status=0  # skipped: motion data absent (said above)
[ "$bench_status" -eq 0 ] || status=$bench_status
if [ -s "$ring_out/traffic.lcmlog" ]; then
  echo "      the hulls on SYNCAP_HULL as syncap record received them (meshes in $ring_out/hull/):"
  "$build/bin/syncap" log "$ring_out/traffic.lcmlog" --channel SYNCAP_HULL 2>/dev/null |
    jq -r 'select(.fields.frame_number % 10 == 5) | .fields as $f
      | "      frame \($f.frame_number): hull of \($f.cameras) silhouettes, "
        + "\($f.volume_mm3 / 1e6 | floor) litres, \($f.faces) triangles, built in "
        + "\($f.hull_us / 1000 | floor) ms, flags \($f.flags)"'
fi
body_dir=$ring_out/calibrated-body
if [ -s "$body_dir/body.bvh" ]; then
  echo "      the body fitted to the hulls (syncap fit; the skeleton and its motion in"
  echo "      $body_dir/body.bvh, the joints' centres in joints.c3d and joints.trc):"
  jq -r 'select(.body.joints and .frame % 10 == 5) | .body as $b
    | "      frame \(.frame): root at (\($b.joints.HumanoidRoot | map(floor) | join(", "))) mm, "
      + "head at (\($b.joints.skullbase | map(floor) | join(", "))) mm, hull points "
      + "\($b.rms_mm) mm RMS from the body, flags \($b.flags)"' "$body_dir/body.jsonl"
fi

echo "demo: [4/5] live 3D markers: hil/run markers-8cam-body (eight fake cameras, a wand phase,"
echo "      then a person wearing 33 markers); the host reconstructs and tracks them live and"
echo "      publishes them on SYNCAP_MARKERS; as syncap record received them during the run:"
markers_out=$out/markers-8cam-body
markers_status=0
hil/run markers-8cam-body --max-phase-frames 60 --marker-limits 0.99,0.01,3 --max-rms-px 0.3 \
  --build "$build" --out "$markers_out" > "$markers_out.log" 2>&1 || markers_status=$?
if [ "$markers_status" -eq 77 ]; then
  markers_status=0
  grep SKIP "$markers_out.log" || true
elif [ -s "$markers_out/traffic.lcmlog" ]; then
  # Each marker message as it arrived: the logger's receive time against the trigger's pulse.
  "$build/bin/syncap" log "$markers_out/traffic.lcmlog" --channel SYNCAP_MARKERS 2>/dev/null |
    jq -r 'select(.fields.frame_number % 20 == 5) | .fields as $f
      | "      frame \($f.frame_number): \($f.total_markers) markers from \($f.cameras) cameras, "
        + "arrived \(((.timestamp_us * 1000 - $f.trigger_realtime_ns) / 1e6) | floor) ms after"
        + " its pulse; marker \($f.markers[0].id) at (\($f.markers[0].x | floor),"
        + " \($f.markers[0].y | floor), \($f.markers[0].z | floor)) mm"'
  grep -E '^== (calibrated )?(markers|PASS|FAIL)' "$markers_out.log" | sed 's/^/      /'
fi
[ "$markers_status" -eq 0 ] || status=$markers_status

# The runs in Rerun (docs/guide/view.md): hil/run replayed each run's traffic into RUN/view.rrd; the
# ring's fitted body (syncap fit's frame lines) and its calibration go into one more.
if [ -s "$ring_out/calibrated-body/body.jsonl" ] && [ -x "$build/py-venv/bin/python3" ]; then
  "$build/bin/syncap" view --groups "$ring_out/calibrated-body/body.jsonl" \
    --calibration-dir "$ring_out/calibration" --save "$ring_out/body.rrd" --quiet > "$ring_out/body-view.log" 2>&1 ||
    echo "demo: syncap view of the body failed, see $ring_out/body-view.log"
fi
recordings=()
for rrd in "$ring_out/view.rrd" "$ring_out/body.rrd" "$markers_out/view.rrd"; do
  [ ! -s "$rrd" ] || recordings+=("$rrd")
done
if [ ${#recordings[@]} -gt 0 ]; then
  echo "demo: the runs in Rerun (${#recordings[@]} recordings): the cameras, blobs, silhouettes,"
  echo "      markers, the hulls' boxes, the fitted skeleton and the calibration's residuals:"
  echo "      $build/py-venv/bin/rerun ${recordings[*]}"
  echo "      in a browser, replayed: $build/bin/syncap view --input lcmlog:$ring_out/traffic.lcmlog \\"
  echo "        --calibration-dir $ring_out/calibration --web    (then open the address it prints)"
else
  echo "demo: no Rerun recordings (the viewer's venv is missing: scripts/py-deps.sh)"
fi

echo "demo: [5/5] outputs in $out/:"
echo "      groups.jsonl      one JSON line per frame group the host formed (thin slice)"
echo "      traffic.lcmlog    all LCM traffic (decode: $build/bin/syncap log $out/traffic.lcmlog)"
echo "      render/           the slice's rendered frames and truth"
echo "      ring-6cam-person/ the bench run: render/ (images, truth), groups.jsonl, compare.json,"
echo "                        hull/ (the person's hull of every frame, PLY), calibrated-body/"
echo "                        (the fitted body: body.jsonl, body.bvh, joints.c3d, joints.trc),"
echo "                        view.rrd and body.rrd (Rerun), logs"
echo "      markers-8cam-body/ the mocap run: offline/ and calibrated/ markers (.jsonl, .c3d, .trc),"
echo "                        calibration/ (from the run's wand phase), traffic.lcmlog, view.rrd"
echo "      *.log             each process' own output"
exit "$status"
