#!/usr/bin/env bash
# tests/hil/ctl_auth_run.sh BUILD OUT    (inside hil/netns-run)
# The real syncap-edge with the installation's key obeys `syncap ctl` signed with that key and
# acknowledges it; a command signed with another key, or a replayed datagram, changes nothing and
# is counted in the heartbeat; `syncap ctl` says which and exits 1. Before issue 15 any process on
# the segment could stop an edge, and nothing sent commands at all.
set -euo pipefail
[ $# -eq 2 ] || { sed -n '2,2p' "$0" >&2; exit 2; }
build=$1 out=$2
syncap=$build/bin/syncap
rm -rf "$out"
mkdir -p "$out/replay"
{ printf 'P5\n8 8\n255\n'; head -c 64 /dev/zero; } > "$out/replay/000000.pgm"
fail() { echo "== FAIL: $*"; cat "$out/edge.log" 2>/dev/null || true; exit 1; }

"$syncap" keygen --out "$out/command.key" > /dev/null
"$syncap" keygen --out "$out/stranger.key" > /dev/null
if "$syncap" keygen --out "$out/command.key" 2> "$out/keygen-again.err"; then
  fail "keygen replaced an existing key without --force"
fi

lcm-logger --force --channel 'SYNCAP_EDGE_CMD' "$out/commands.lcmlog" > "$out/logger.log" 2>&1 &
logger=$!
"$build/bin/syncap-edge" --camera-id 5 --source "replay:$out/replay" \
  --command-key "$out/command.key" > "$out/edge.log" 2>&1 &
edge=$!
trap 'kill $edge $logger 2>/dev/null || true' EXIT
sleep 1.2  # the edge is up and subscribed

# A stranger's key: refused (with the next heartbeat), exit 1, the edge still acquiring.
status=0
"$syncap" ctl stop --camera 5 --command-key "$out/stranger.key" > "$out/stranger.out" 2>&1 || status=$?
cat "$out/stranger.out"
[ "$status" -eq 1 ] || fail "a command signed with another key: exit $status, expected 1"
grep -q "camera 5: refused: not signed with this installation's key" "$out/stranger.out" ||
  fail "syncap ctl did not report the refusal"
grep -q "acquiring" "$out/stranger.out" || fail "the forged STOP stopped the camera"

# The installation's key: obeyed and acknowledged at once.
"$syncap" ctl stop --camera 5 --command-key "$out/command.key" > "$out/genuine.out" 2>&1 ||
  fail "the signed STOP was not acknowledged: $(cat "$out/genuine.out")"
cat "$out/genuine.out"
grep -q "camera 5: accepted (idle" "$out/genuine.out" || fail "no acknowledgement of the STOP"

# Both STOPs captured by the logger, replayed byte for byte: the stranger's refused again, the
# genuine one refused as a replay.
sleep 0.3
kill -INT "$logger"
wait "$logger" || true
lcm-logplayer "$out/commands.lcmlog" > "$out/player.log" 2>&1 || true
"$syncap" ctl status --camera 5 --wait-s 1.5 > "$out/after.out" 2>&1 || true
cat "$out/after.out"
grep -q "1 commands obeyed, 3 refused" "$out/after.out" ||
  fail "the replayed STOPs were not refused and counted (expected 1 obeyed, 3 refused)"
grep -q "refused: replayed" "$out/edge.log" || fail "the edge did not log the replay as one"

"$syncap" ctl shutdown --camera 5 --command-key "$out/command.key" > "$out/shutdown.out" 2>&1 ||
  fail "shutdown not acknowledged: $(cat "$out/shutdown.out")"
wait "$edge" || fail "syncap-edge exited $? after SHUTDOWN"
trap - EXIT
grep -q "2 commands obeyed, 3 refused" "$out/edge.log" ||
  fail "the edge's last line does not count what it obeyed and refused"
echo "== PASS: signed commands obeyed and acknowledged; forged and replayed ones refused"
