#!/usr/bin/env bash
# tests/cli/programs_test.sh BIN_DIR: every program and `syncap` subcommand refuses an unknown
# option, and a bad number for one of its numeric options, with exit status 2 and a message
# that names the option (docs/reference/cli.md, "Errors").
set -uo pipefail
bin=$1
export PATH=$bin:$PATH

# Program (or `syncap SUBCOMMAND`) | one numeric option ("" where it has none).
TABLE=(
  "syncap-trigger|--rate-hz"
  "syncap-edge|--threshold-dn"
  "syncap-host|--max-lag"
  "syncap calibrate|--frames"
  "syncap bundle|"
  "syncap record|--duration-s"
  "syncap log|"
  "syncap markers|--max-lag"
  "syncap fit|--max-lag"
  "syncap reconstruct|--every"
  "syncap hull|--resolution"
  "syncap match|--spacing"
  "syncap cameras convert|--toml-unit-mm"
  "syncap clip|--margin"
  "syncap regions|--margin"
  "syncap ctl|--wait-s"
  "syncap keygen|"
  "syncap sim|--max-phase-frames"
  "syncap segment-eval|--frame-step"
  "syncap mask|--every"
  "syncap-gpiosim|"
  "syncap-fakecam|--seed"
  "syncap-hil-compare|--max-rms-px"
  "syncap-hil-impair|--loss"
  "syncap-hil-surface-check|--frame"
  "syncap-calib-study|--runs"
)
# syncap view (Python) only where its venv is: it is tested the same way then.
if [ -x "$bin/../py-venv/bin/python3" ]; then TABLE+=("syncap view|--web-port"); fi

failures=0
# expect_usage_error WHAT NAME ARGS...: exit 2 and NAME in the output.
expect_usage_error() {
  local what=$1 name=$2 output status
  shift 2
  output=$("$@" 2>&1 < /dev/null)
  status=$?
  if [ $status -ne 2 ] || [[ "$output" != *"$name"* ]]; then
    echo "FAIL: $* ($what): exit $status, expected 2 naming $name; it said:"
    echo "$output" | head -5 | sed 's/^/    /'
    failures=$((failures + 1))
  fi
}

for entry in "${TABLE[@]}"; do
  read -r -a program <<< "${entry%%|*}"
  number=${entry#*|}
  expect_usage_error "unknown option" --no-such-option "${program[@]}" --no-such-option
  if [ -n "$number" ]; then
    expect_usage_error "bad number" "$number" "${program[@]}" "$number" 12abc
  fi
done
if [ $failures -gt 0 ]; then
  echo "programs_test: $failures failure(s) of ${#TABLE[@]} programs"
  exit 1
fi
echo "programs_test: ${#TABLE[@]} programs refuse unknown options and bad numbers, naming them"
