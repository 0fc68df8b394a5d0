# Shell helpers shared by hil/run and hil/run-slice (sourced, not run).

# True inside a namespace made by hil/netns-run: the multicast route on lo and the fake
# cameras' addresses. (Output captured first: `cmd | grep -q` under pipefail fails when grep
# stops reading early.)
in_private_namespace() {
  local routes addresses
  routes=$(ip route show 239.0.0.0/8 2>/dev/null || true)
  addresses=$(ip -o addr show lo 2>/dev/null || true)
  [[ "$routes" == *"dev lo"* && "$addresses" == *" 127.0.0.33/32 "* ]]
}

# wait_for_line FILE PATTERN SECONDS: waits until FILE holds PATTERN (a process saying it is
# ready on its log's first line); names the file on stderr and fails after SECONDS.
wait_for_line() {
  for _ in $(seq $(($3 * 10))); do grep -q "$2" "$1" 2>/dev/null && return 0; sleep 0.1; done
  echo "$(basename "$0"): no '$2' in $1 after $3 s" >&2
  return 1
}

# The path of libfaketime's multi-threaded preload library (Debian's libfaketime), or nothing.
faketime_library() {
  local found
  for found in /usr/lib/*/faketime/libfaketimeMT.so.1 /usr/lib/faketime/libfaketimeMT.so.1; do
    [ -f "$found" ] && { echo "$found"; return 0; }
  done
  return 0
}

# "FIRST LAST": the frames of the render's first phase when it is a wand phase (the frames a
# mocap scenario calibrates from); nothing otherwise. hil/run and hil/calibrated.
wand_phase_frames() {
  awk -F, 'NR > 1 && $3 == 0 && $4 == "wand" { if (first == "") first = $1; last = $1 }
    END { if (first != "") print first, last }' "$1/truth/frames.csv"
}
