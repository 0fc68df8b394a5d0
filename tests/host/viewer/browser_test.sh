#!/usr/bin/env bash
# tests/host/viewer/browser_test.sh PYTHON [SCREENSHOT.png]
# `syncap view --web` as a person opens it: a made-up recording (make_log.py: 3 cameras, 10
# frames) served by Rerun's web viewer on 127.0.0.1, loaded by Chromium on a virtual X display
# (Xvfb; Chromium draws WebGL there through SwiftShader, while its --headless mode here draws
# nothing), the screen grabbed with Pillow and checked to hold a drawn interface: at least 1500
# distinct colours (measured 2026-11-27: Rerun's viewer with the ring run 2810; Chromium's "site
# can't be reached" page 712; a page still loading under 100). Runs inside a private network
# namespace (hil/netns-run): the servers and the browser never leave it. Skips (exit 77), saying
# why, without chromium, Xvfb, or the venv's rerun-sdk, lcm and Pillow. ctest label: browser.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../../.." && pwd)
py=$1
shot=${2:-}
if [ -z "${SYNCAP_BROWSER_NETNS:-}" ]; then
  for tool in chromium Xvfb; do
    command -v "$tool" >/dev/null || { echo "SKIP: no $tool (Debian: chromium, xvfb)"; exit 77; }
  done
  "$py" -c 'import rerun, lcm, PIL' 2>/dev/null ||
    { echo "SKIP: $py lacks rerun-sdk, lcm or Pillow: scripts/py-deps.sh"; exit 77; }
  exec "$repo/hil/netns-run" env SYNCAP_BROWSER_NETNS=1 "$0" "$@"
fi

work=$(mktemp -d)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
export XDG_CACHE_HOME=${XDG_CACHE_HOME:-$work/cache}
"$py" "$here/make_log.py" "$work/test.lcmlog" --cameras-json "$work/cameras.json"
PYTHONPATH="$repo/host/viewer" "$py" -m syncap_view --input "lcmlog:$work/test.lcmlog" \
  --cameras "$work/cameras.json" --web --web-port 9090 --grpc-port 9876 > "$work/view.log" 2>&1 &
pids+=($!)
for _ in $(seq 120); do grep -q "stays up" "$work/view.log" && break; sleep 0.5; done
grep -q "stays up" "$work/view.log" || { cat "$work/view.log"; echo "FAIL: no web viewer"; exit 1; }
sleep 2  # the web server's page and data port listen a moment after the recording ended
# A free display number (the X sockets live in the shared /tmp, not in the namespace).
Xvfb -displayfd 3 -screen 0 1600x900x24 -nolisten tcp 3> "$work/display" > "$work/xvfb.log" 2>&1 &
pids+=($!)
for _ in $(seq 40); do [ -s "$work/display" ] && break; sleep 0.25; done
display=:$(head -n 1 "$work/display")
[ "$display" != : ] || { cat "$work/xvfb.log"; echo "FAIL: Xvfb did not start"; exit 1; }
DISPLAY=$display chromium --no-sandbox --no-first-run --kiosk --window-size=1600,900 \
  --use-gl=angle --use-angle=swiftshader --enable-unsafe-swiftshader --ignore-gpu-blocklist \
  --user-data-dir="$work/profile" \
  "http://127.0.0.1:9090/?url=rerun%2Bhttp://127.0.0.1:9876/proxy" > "$work/chromium.log" 2>&1 &
pids+=($!)
sleep 45  # the viewer's wasm compiles and draws in software
status=0
"$py" - "$work/shot.png" "$display" <<'PY' || status=$?
import sys
from PIL import Image, ImageGrab
im = ImageGrab.grab(xdisplay=sys.argv[2]).convert("RGB")
im.save(sys.argv[1])
colours = len(im.getcolors(maxcolors=1 << 24))
print(f"browser: screenshot {im.size[0]}x{im.size[1]}, {colours} distinct colours")
sys.exit(0 if colours >= 1500 else 1)
PY
[ -z "$shot" ] || cp "$work/shot.png" "$shot"
exit "$status"
