#!/usr/bin/env bash
# scripts/count-instructions.sh [N]
# The edge's instructions per 1280x1024 frame, blob path (--mode blobs) and blob + mask path
# (--mode both), on amd64 and arm64, counted the same way for both: bench/edge_instructions
# runs under qemu's user-mode emulation (qemu-x86_64, qemu-aarch64) with every translated block
# listed once (-d in_asm: its instructions) and logged at every execution (-d exec, nochain so
# that no block runs without a log line); the count is the sum of the executed blocks' sizes.
# (On arm64 it equals qemu's one-instruction-per-block count, -singlestep, exactly; on amd64 it
# is within 1 % of it, on fw_config --list: 155741 against 154784.) Each mode runs with 1 and
# 1 + N person frames (N = 2 by default); the difference over N is one frame's count. Needs
# build/ and build-arm64/ (the latter from scripts/cross-build.sh arm64) and qemu-user
# (scripts/deps.sh cross).
# Prints a table for docs/design/edge.md. The counts are of the code the compiler emitted for each
# processor (SSE2 on amd64 with OpenCV's CPU dispatch as qemu's default CPU model reports it,
# NEON on arm64), not of time: retake time on a board (docs/design/edge.md).
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-2}
amd64=${SYNCAP_BUILD_DIR:-build}/bin/edge_instructions
arm64=${SYNCAP_CROSS_BUILD_DIR:-build-arm64}/bin/edge_instructions
sysroot=${SYNCAP_SYSROOT:-$PWD/build-sysroot-arm64}
for program in "$amd64" "$arm64"; do
  [ -x "$program" ] || { echo "count-instructions: $program is not built" >&2; exit 1; }
done
command -v qemu-x86_64 >/dev/null || scripts/deps.sh cross
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$amd64" render "$work/frames"

# count EMULATOR... PROGRAM ARGS...: guest instructions of one run.
count() {
  mkfifo "$work/log"
  awk '
    /^IN:/ { block = 1; start = ""; n = 0; next }
    block && /^0x[0-9a-f]+:/ {
      if (start == "") { start = substr($1, 3, length($1) - 3); sub(/^0+/, "", start) }
      n++; next
    }
    block && /^ *$/ { if (start != "") size[start] = n; block = 0; next }
    /^Trace/ { split($0, f, "/"); pc = f[2]; sub(/^0+/, "", pc); total += size[pc] }
    END { print total + 0 }' <"$work/log" >"$work/count" &
  local reader=$!
  "$@" 2>/dev/null
  wait "$reader"
  rm -f "$work/log"
  cat "$work/count"
}
per_frame() {  # ARCH MODE: instructions of one frame
  local emulator program
  if [ "$1" = amd64 ]; then emulator=(qemu-x86_64); program=$amd64
  else emulator=(qemu-aarch64-static -L "$sysroot"); program=$arm64; fi
  local flags=(-d nochain,exec,in_asm -D "$work/log")
  local one more
  one=$(count "${emulator[@]}" "${flags[@]}" "$program" "$2" 1 "$work/frames")
  more=$(count "${emulator[@]}" "${flags[@]}" "$program" "$2" $((1 + n)) "$work/frames")
  echo $(( (more - one) / n ))
}
echo "| path | amd64 (SSE2) | arm64 (NEON) | arm64 / amd64 |"
echo "|---|---|---|---|"
for mode in blobs both; do
  a=$(per_frame amd64 "$mode")
  b=$(per_frame arm64 "$mode")
  ratio=$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.2f", b / a }')
  label=$([ "$mode" = blobs ] && echo "blobs (--mode blobs)" || echo "blobs + mask (--mode both)")
  echo "| $label | $a | $b | $ratio |"
done
