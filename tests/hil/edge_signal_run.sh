#!/usr/bin/env bash
# tests/hil/edge_signal_run.sh BUILD OUT SIGNAL    (inside hil/netns-run)
# syncap-edge stopped by SIGNAL (TERM: systemd's stop, INT: Ctrl-C) while it waits for messages
# ends cleanly: exit 0, its final status (STATE_STOPPED = 3) on the network. Before issue 15 the
# receive the signal interrupted made it exit 1 ("LCM receive failed") without the final status,
# and systemd marked the unit failed.
set -euo pipefail
[ $# -eq 3 ] || { sed -n '2,2p' "$0" >&2; exit 2; }
build=$1 out=$2 signal=$3
rm -rf "$out"
mkdir -p "$out/replay"
{ printf 'P5\n8 8\n255\n'; head -c 64 /dev/zero; } > "$out/replay/000000.pgm"

lcm-logger --force --channel 'SYNCAP_STATUS_07' "$out/status.lcmlog" > "$out/logger.log" 2>&1 &
logger=$!
"$build/bin/syncap-edge" --camera-id 7 --source "replay:$out/replay" > "$out/edge.log" 2>&1 &
edge=$!
sleep 1.5  # the edge is up, its first heartbeat out, and it waits in LCM's receive
kill -"$signal" "$edge"
status=0
wait "$edge" || status=$?
sleep 0.5  # the logger writes what arrived
kill -INT "$logger"
wait "$logger" || true
cat "$out/edge.log"
if [ "$status" -ne 0 ]; then
  echo "== FAIL: syncap-edge exited $status after SIG$signal"
  exit 1
fi
"$build/bin/syncap" log "$out/status.lcmlog" > "$out/status.jsonl"
if ! grep -q '"state":3' "$out/status.jsonl"; then
  echo "== FAIL: no final status (state 3) of camera 7 in $out/status.jsonl:"
  cat "$out/status.jsonl"
  exit 1
fi
echo "== PASS: SIG$signal: exit 0, final status published"
