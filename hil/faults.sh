# The processes of hil/run and the faults it injects into them (sourced by hil/run, not run).
# Uses hil/run's variables: bin, out, render, chip, ids, rate, frames, cameras, fault, fault_at,
# board_url, host_url, detection, edge_mask_args, host_hull_args, scenario, pids.

edge_pids=() fakecam_pids=() host_pid="" host_log="" trigger_pid="" trigger_log=""
fault_camera=1        # whose edge is killed, whose fake camera is unplugged
clock_step_camera=2   # whose board's clock is stepped
clock_step_s=30
# libfaketime (Debian's libfaketime) on one edge: the offset is read from a file, again at most
# once a second, so writing the file steps the clock in the running process. Only
# CLOCK_REALTIME moves: a real clock step (settimeofday, NTP) leaves CLOCK_MONOTONIC alone.
faketime_env=(env "LD_PRELOAD=$(faketime_library)"
  "FAKETIME_TIMESTAMP_FILE=$out/faketime" FAKETIME_CACHE_DURATION=1
  FAKETIME_DONT_FAKE_MONOTONIC=1)

# syncap-hil-impair's options for a network fault (none for the others: it relays everything).
impairment_of() {
  case "$1" in
    loss) echo "--loss 5%" ;;
    reorder) echo "--reorder 10% --reorder-delay-ms 10" ;;
    duplicate) echo "--duplicate 5%" ;;
    corrupt) echo "--corrupt 1%" ;;
    network) echo "--loss 5% --reorder 10% --reorder-delay-ms 10 --duplicate 5% --corrupt 1%" ;;
  esac
}

# yaml_lines ARGS...: command-line options (`--key value`, `--flag`) as a rig section's
# `  key: value` lines (a flag: true).
yaml_lines() {
  while [ $# -gt 0 ]; do
    if [ $# -gt 1 ] && [[ "$2" != --* ]]; then
      printf '  %s: "%s"\n' "${1#--}" "$2"
      shift 2
    else
      printf '  %s: true\n' "${1#--}"
      shift
    fi
  done
}

# write_rig FILE: the run's installation as a rig file (docs/guide/rig.md), read by the host, the
# trigger and every edge as on a lab's machines: the scene's true cameras (render/cameras.json),
# each camera's fake GigE address, the edges', the host's and the trigger's options.
write_rig() {
  {
    echo "# hil/run's rig: $(basename "$scenario" .yaml), $cameras cameras"
    echo "calibration: \"$render/cameras.json\""
    echo "edges:"
    # Retro-reflective targets and the LED are far above the lit room (<= 190 DN): threshold 200.
    yaml_lines --lcm-url "$board_url" --exit-after-last --threshold-dn 200 --detection "$detection" \
      "${edge_mask_args[@]}"
    echo "cameras:"
    for ((c = 0; c < cameras; c++)); do
      echo "  - {camera-id: $c, board: board-$c, source: \"aravis:127.0.0.$((c + 2))\"}"
    done
    echo "host:"
    yaml_lines --until-last --idle-timeout-s 15 --max-lag 30 --lcm-url "$host_url" \
      "${host_hull_args[@]}"
    # The simulated chip's lines 0..N-1, one a camera, at the scenario's rate.
    echo "trigger:"
    yaml_lines --chip "sim:$chip" --lines "$ids" --rate-hz "$rate" --start-delay-ms 500
  } > "$1"
}

# start_host GROUPS LOG
# The host reconstructs the markers (and, with a person, its hull) live with the scene's true
# cameras, as the rig file says; syncap-hil-compare scores them against the true targets.
start_host() {
  "$bin/syncap-host" --config "$out/rig.yaml" "${track_rate_args[@]}" --out "$1" > "$2" 2>&1 &
  host_pid=$!
  host_log=$2
  pids+=("$host_pid")
}

start_fakecam() {
  local cam
  cam=$(printf %02d "$1")
  "${hardware_priority[@]}" "$bin/syncap-fakecam" --address "127.0.0.$(($1 + 2))" --images "$render/camera$cam" \
    --trigger "gpiosim:$chip:$1" >> "$out/fakecam$cam.log" 2>&1 &
  fakecam_pids[$1]=$!
  pids+=("$!")
}

# start_edge CAMERA [COMMAND PREFIX...]
start_edge() {
  local c=$1 cam
  shift
  cam=$(printf %02d "$c")
  [ $# -eq 0 ] || echo "+0" > "$out/faketime"
  "$@" "$bin/syncap-edge" --config "$out/rig.yaml" --camera-id "$c" >> "$out/edge$cam.log" 2>&1 &
  edge_pids[c]=$!
  pids+=("$!")
}

# start_trigger COUNT LOG
start_trigger() {
  "${hardware_priority[@]}" "$bin/syncap-trigger" --config "$out/rig.yaml" --count "$1" > "$2" 2>&1 &
  trigger_pid=$!
  trigger_log=$2
  pids+=("$trigger_pid")
}

# For hil/fault-figures: "inject|restore SECONDS_SINCE_EPOCH what was done".
note_fault() {
  echo "$1 $EPOCHREALTIME $2" >> "$out/faults.log"
  echo "== fault: $2"
}

# Kills a process we started and reaps it (its exit status is the kill's, not a failure).
kill_and_reap() {
  kill "-$1" "$2" 2>/dev/null || true
  wait "$2" 2>/dev/null || true
}

# Waits --fault-at seconds of pulses, then does the fault (network faults act all along).
inject_fault() {
  rm -f "$out/faults.log"
  case "$fault" in
    none|loss|reorder|duplicate|corrupt|network) return 0 ;;
  esac
  wait_for_line "$trigger_log" "pulses" 15 || return 1
  sleep "$(awk -v s="$fault_at" 'BEGIN {print s + 0.5}')"  # first pulse 500 ms after that line
  local cam
  cam=$(printf %02d "$fault_camera")
  case "$fault" in
    edge-restart)
      note_fault inject "edge of camera $fault_camera killed (SIGKILL)"
      kill_and_reap KILL "${edge_pids[fault_camera]}"
      sleep 2
      start_edge "$fault_camera"
      note_fault restore "edge of camera $fault_camera started again"
      ;;
    camera-unplug)
      note_fault inject "fake camera $fault_camera unplugged (SIGKILL)"
      kill_and_reap KILL "${fakecam_pids[fault_camera]}"
      sleep 2
      start_fakecam "$fault_camera"
      wait_for_line "$out/fakecam$cam.log" "serving.*" 15 || return 1
      note_fault restore "fake camera $fault_camera plugged in again"
      ;;
    host-restart)
      note_fault inject "host killed (SIGKILL)"
      kill_and_reap KILL "$host_pid"
      sleep 1
      start_host "$out/groups-restarted.jsonl" "$out/host-restarted.log"
      note_fault restore "host started again"
      ;;
    trigger-restart)
      note_fault inject "trigger stopped (SIGTERM)"
      kill_and_reap TERM "$trigger_pid"
      sleep 1
      local sent
      sent=$(sed -n 's/.*pulses=\([0-9]*\).*/\1/p' "$trigger_log")
      start_trigger "$((frames - ${sent:-0}))" "$out/trigger-restarted.log"
      note_fault restore "trigger started again for the remaining $((frames - ${sent:-0})) pulses"
      ;;
    clock-step)
      echo "+${clock_step_s}" > "$out/faketime"
      note_fault inject \
        "CLOCK_REALTIME of camera $clock_step_camera's board stepped +$clock_step_s s"
      ;;
  esac
}

# The processes still ours that did not end well: edges that did not exit 0 within 5 s of the
# host, fake cameras that did not stop cleanly on SIGINT. Sets `crashed` to their names (not in
# a subshell: only this shell can wait for its children).
check_processes() {
  local failed=() c status
  for ((c = 0; c < cameras; c++)); do
    for _ in $(seq 50); do kill -0 "${edge_pids[c]}" 2>/dev/null || break; sleep 0.1; done
    if kill -0 "${edge_pids[c]}" 2>/dev/null; then
      failed+=("edge$c(hung)")
      kill -KILL "${edge_pids[c]}"
    fi
    status=0
    wait "${edge_pids[c]}" 2>/dev/null || status=$?
    [ "$status" -eq 0 ] || failed+=("edge$c(exit $status)")
    kill -INT "${fakecam_pids[c]}" 2>/dev/null || true
    status=0
    wait "${fakecam_pids[c]}" 2>/dev/null || status=$?
    [ "$status" -eq 0 ] || failed+=("fakecam$c(exit $status)")
  done
  crashed="${failed[*]}"
}
