#!/usr/bin/env python3
"""How many frames per second `syncap view --save` logs, replaying a made-up recording of
CAMERAS cameras x MARKERS markers per frame (docs/viewer.md, "Speed").

    build/py-venv/bin/python3 host/viewer/bench_view.py [--frames 300] [--cameras 8] [--markers 32]

Writes the log (trigger, every camera's blob frame, the marker frame per frame), replays it with
--cameras and --save RUNS times, and prints the logging loop's frames/s (the program's own
figure: reading, decoding, joining and logging, without Python's and Rerun's start) and the
whole run's wall time."""

import argparse
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from syncap_view import bindings, synthetic  # noqa: E402


def write_log(path: str, cameras_json: str, frames: int, n_cameras: int, n_markers: int) -> None:
    t = bindings.load()
    cams = synthetic.ring_cameras(n_cameras)
    synthetic.write_cameras(cameras_json, cams)
    w = synthetic.LogWriter(path, t)
    for f in range(frames):
        w.trigger(f)
        markers = synthetic.marker_positions(f, n_markers)
        for cam in cams:
            w.blobs(cam["id"], f, [p for p in (synthetic.project(cam, x) for x in markers) if p])
        w.markers(f, markers)
    w.close()


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--frames", type=int, default=300)
    p.add_argument("--cameras", type=int, default=8)
    p.add_argument("--markers", type=int, default=32)
    p.add_argument("--runs", type=int, default=3)
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as d:
        log, cams, rrd = f"{d}/bench.lcmlog", f"{d}/cameras.json", f"{d}/bench.rrd"
        write_log(log, cams, a.frames, a.cameras, a.markers)
        rates, walls = [], []
        for _ in range(a.runs):
            start = time.monotonic()
            r = subprocess.run([sys.executable, "-m", "syncap_view", "--input", f"lcmlog:{log}",
                                "--cameras", cams, "--save", rrd, "--quiet"],
                               cwd=HERE, capture_output=True, text=True)
            walls.append(time.monotonic() - start)
            if r.returncode != 0:
                print(r.stderr, file=sys.stderr)
                return 1
            rates.append(float(re.search(r"([\d.]+) frames/s", r.stderr).group(1)))
        size = Path(rrd).stat().st_size
    print(f"bench_view: {a.frames} frames of {a.cameras} cameras x {a.markers} markers, "
          f"{a.runs} runs: logging {min(rates):.0f}-{max(rates):.0f} frames/s "
          f"(median {statistics.median(rates):.0f}); whole run {min(walls):.2f}-{max(walls):.2f} s "
          f"with start; .rrd {size / 1e6:.1f} MB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
