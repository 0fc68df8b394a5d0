#!/usr/bin/env bash
# tests/hil/stopped_host_run.sh BUILD OUT
# The host stops as a loaded machine stops it (SIGSTOP for 1.5 s: 15 frames of six cameras at
# 10 Hz, their blobs and silhouettes, paced as hil.run.RingSixCameraPersonShort) in the middle of the short ring-6cam-person run, and still
# gets every message the edges sent: hil/run's comparison passes (every frame complete) and the
# host's summary names no camera with records lost between edge and host. Before the receive path
# was sized (docs/design/architecture.md, "Receiving without loss") this lost 160-210 of the 540 blob
# messages, every time. Exit 77 (skipped) when hil/run skips (no motion data).
set -euo pipefail
[ $# -eq 2 ] || { sed -n '2,2p' "$0" >&2; exit 2; }
build=$1 out=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$out"
rm -f "$out/run/trigger.log"
"$root/hil/run" ring-6cam-person --short --rate 10 --build "$build" --out "$out/run" > "$out/run.log" 2>&1 &
run=$!
# The trigger's first line comes 500 ms before its first pulse; stop the host 1.5 s into the pulses.
while ! grep -q "pulses" "$out/run/trigger.log" 2>/dev/null; do
  if ! kill -0 "$run" 2>/dev/null; then
    status=0
    wait "$run" || status=$?
    cat "$out/run.log"
    [ "$status" -eq 77 ] && exit 77
    echo "stopped_host_run.sh: hil/run ended (exit $status) before the trigger started" >&2
    exit 1
  fi
  sleep 0.05
done
sleep 2.0
host=$(pgrep -f -- "syncap-host .*--out $out/run/groups.jsonl" || true)
if [ -z "$host" ]; then
  echo "stopped_host_run.sh: no syncap-host of this run found" >&2
  wait "$run" || true
  cat "$out/run.log"
  exit 1
fi
echo "== syncap-host (pid $host) stopped for 1.5 s"
kill -STOP "$host"
sleep 1.5
kill -CONT "$host"
status=0
wait "$run" || status=$?
cat "$out/run.log"
if grep -q "lost between edge and host" "$out/run/host.log"; then
  echo "== FAIL: the stopped host lost records (above)"
  exit 1
fi
exit "$status"
