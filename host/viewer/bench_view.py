#!/usr/bin/env python3
"""How many frames per second `syncap view --save` logs, replaying a made-up recording of
CAMERAS cameras x MARKERS markers per frame (docs/guide/view.md, "Speed").

    build/py-venv/bin/python3 host/viewer/bench_view.py [--frames 300] [--cameras 8] [--markers 32]
    hil/netns-run build/py-venv/bin/python3 host/viewer/bench_view.py --live 100

Writes the log (trigger, every camera's blob frame, the marker frame per frame), replays it with
--cameras and --save RUNS times, and prints the logging loop's frames/s (the program's own
figure: reading, decoding, joining and logging, without Python's and Rerun's start) and the
whole run's wall time. With --live HZ the frames are published on LCM at HZ to the viewer running
live, which prints, when it stops, how many frame numbers it showed and how many were missing."""

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


def write_log(path: str, cameras_json: str, frames: int, n_cameras: int, n_markers: int,
              with_hull: bool = False) -> None:
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
        if with_hull:  # the hull's message and a body a frame, as syncap-host --body sends
            w.hull(f, markers.min(axis=0), markers.max(axis=0))
            w.body(f)
    w.close()


def replay_live(log: str, cams: str, rrd: str, rate_hz: float) -> str:
    """Publishes the log's events on LCM's default URL, frame by frame at rate_hz, to a live
    `syncap view --save`; returns the viewer's summary. Inside a network namespace only."""
    import lcm

    viewer = subprocess.Popen([sys.executable, "-m", "syncap_view", "--lcm-url", LIVE_URL,
                               "--cameras", cams, "--save", rrd, "--quiet"], cwd=HERE,
                              stderr=subprocess.PIPE, text=True, start_new_session=True)
    time.sleep(5.0)  # Python, Rerun and the bindings start before anything is sent
    out = lcm.LCM(LIVE_URL)
    frames: list[list] = []  # each frame's events: its trigger, then its cameras' and markers'
    for event in lcm.EventLog(log, "r"):
        if event.channel == "SYNCAP_TRIGGER" or not frames:
            frames.append([])
        frames[-1].append(event)
    start = time.monotonic()
    for i, events in enumerate(frames):
        time.sleep(max(0.0, start + i / rate_hz - time.monotonic()))
        for e in events:
            out.publish(e.channel, e.data)
    sent_s = time.monotonic() - start
    time.sleep(2.0)
    viewer.terminate()
    _, err = viewer.communicate(timeout=60)
    return f"sent {len(frames)} frames in {sent_s:.2f} s ({len(frames) / sent_s:.0f} Hz)\n{err}"


LIVE_URL = "udpm://239.255.76.67:7667?ttl=0"


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--frames", type=int, default=300)
    p.add_argument("--cameras", type=int, default=8)
    p.add_argument("--markers", type=int, default=32)
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--hull", action="store_true",
                   help="a hull_frame_t and a body_frame_t every frame too")
    p.add_argument("--live", type=float, metavar="HZ",
                   help="publish the frames live at HZ to `syncap view --lcm-url` instead "
                        "(inside a network namespace: hil/netns-run)")
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as d:
        log, cams, rrd = f"{d}/bench.lcmlog", f"{d}/cameras.json", f"{d}/bench.rrd"
        write_log(log, cams, a.frames, a.cameras, a.markers, a.hull)
        if a.live:
            print(f"bench_view: live, {a.cameras} cameras x {a.markers} markers: "
                  + replay_live(log, cams, rrd, a.live))
            return 0
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
