#!/usr/bin/env bash
# Builds the benchmark programs if needed (scripts/build.sh), runs every build/bin/bench_* (or
# $SYNCAP_BUILD_DIR/bin) and prints one line per comparison: a program that registers
# "<name>/ours" and "<name>/baseline" yields "<name>: R x (ours vs baseline)", R = baseline time /
# our time (real time, from --benchmark_format=json); a lone "<name>/ours" (a goal in seconds, no
# baseline) yields "<name>: S s on one core (CPU time; wall W s)"; a pair with an "error_rms"
# counter adds the precision ratio (baseline's over ours). Extra arguments go to every program
# (e.g. --benchmark_filter=blobs).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${SYNCAP_BUILD_DIR:-build}
if [ ! -f "$build_dir/build.ninja" ]; then
  scripts/build.sh
else
  targets=$(ninja -C "$build_dir" -t targets all | sed -n 's/^\(bench_[A-Za-z0-9_]*\): phony$/\1/p')
  [ -z "$targets" ] || cmake --build "$build_dir" --target $targets
fi
shopt -s nullglob
programs=("$build_dir"/bin/bench_*)
[ ${#programs[@]} -gt 0 ] || { echo "bench: no bench_* programs in $build_dir/bin" >&2; exit 1; }
for program in "${programs[@]}"; do
  json=$(mktemp)
  echo "== $(basename "$program")" >&2
  if ! "$program" --benchmark_format=json "$@" >"$json" || ! grep -q '"benchmarks"' "$json"; then
    echo "bench: $(basename "$program") produced no results" >&2
    rm -f "$json"
    continue
  fi
  if command -v python3 >/dev/null; then
    python3 - "$json" <<'PY'
import json, sys
runs = json.load(open(sys.argv[1])).get("benchmarks", [])
times, cpu, errors = {}, {}, {}
for b in runs:
    if b.get("run_type", "iteration") != "iteration" or b.get("error_occurred"):
        continue
    # "<name>/<side>" may carry suffixes Google Benchmark appends ("/min_time:2.000", args).
    parts = b["name"].split("/")
    name, side = parts[0], parts[1] if len(parts) > 1 else ""
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b.get("time_unit", "ns")]
    if side in ("ours", "baseline"):
        times.setdefault(name, {})[side] = float(b["real_time"]) * scale
        cpu.setdefault(name, {})[side] = float(b["cpu_time"]) * scale
        if "error_rms" in b:  # an accuracy counter: the ratio is printed beside the time's
            errors.setdefault(name, {})[side] = float(b["error_rms"])
for name, t in times.items():
    if "ours" in t and "baseline" in t and t["ours"] > 0:
        e = errors.get(name, {})
        precision = (f"; error RMS {e['ours']:.3g} vs {e['baseline']:.3g}: "
                     f"{e['baseline'] / e['ours']:.1f} x more precise"
                     if "ours" in e and "baseline" in e and e["ours"] > 0 else "")
        print(f"{name}: {t['baseline'] / t['ours']:.1f} x (ours vs baseline){precision}")
    elif "ours" in t:
        print(f"{name}: {cpu[name]['ours']:.2f} s on one core (CPU time; wall {t['ours']:.2f} s)")
PY
  else
    # Without python3: Google Benchmark's JSON has one "key": value per line.
    awk -F'"' '
      /"name":/ { split($4, part, "/"); name = part[1]; side = part[2] }
      /"real_time":/ { v = $3; gsub(/[:, ]/, "", v); if (side == "ours" || side == "baseline") t[name, side] = v; names[name] = 1 }
      /"cpu_time":/ { v = $3; gsub(/[:, ]/, "", v); if (side == "ours") c[name] = v }
      /"time_unit":/ { u = $4; if (side == "ours") unit[name] = (u == "ms" ? 1e-3 : u == "us" ? 1e-6 : u == "s" ? 1 : 1e-9) }
      END { for (n in names) if ((n, "ours") in t && (n, "baseline") in t && t[n, "ours"] > 0)
              printf "%s: %.1f x (ours vs baseline)\n", n, t[n, "baseline"] / t[n, "ours"]
            else if ((n, "ours") in t)
              printf "%s: %.2f s on one core (CPU time; wall %.2f s)\n", n, c[n] * unit[n], t[n, "ours"] * unit[n] }' "$json"
  fi
  rm -f "$json"
done
