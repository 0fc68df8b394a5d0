#!/usr/bin/env python3
"""Do the host's marker sigmas cover its errors? (issue #38, "sigmas that cover the errors")

hil/marker_sigmas.py --truth RENDER --groups GROUPS.jsonl [--match-radius-mm 5] [--after-frame N]

Every host marker (not predicted) within the match radius of a true target of its frame
(RENDER/truth/targets.csv) gives its error per axis divided by its sigma per axis (the JSON
line's "sigma", mm). Prints the RMS of those normalised errors (1 when the sigmas cover the
errors exactly; above 1 they are overconfident) and the share beyond 3. Only for markers in the
truth's frame: the true cameras' runs, not a calibration's (its axes differ by a rotation).
"""
import argparse
import csv
import json
import math
import sys


def read_targets(path):
    targets = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            targets.setdefault(int(row["frame"]), []).append(
                (float(row["X_mm"]), float(row["Y_mm"]), float(row["Z_mm"])))
    return targets


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--truth", required=True)
    parser.add_argument("--groups", required=True)
    parser.add_argument("--match-radius-mm", type=float, default=5.0)
    parser.add_argument("--after-frame", type=int, default=-1,
                        help="only frames after this one (e.g. the wand phase's last)")
    args = parser.parse_args()
    targets = read_targets(f"{args.truth}/truth/targets.csv")
    squares, beyond, count = 0.0, 0, 0
    with open(args.groups) as f:
        for number, line in enumerate(f, 1):
            try:
                group = json.loads(line)
            except json.JSONDecodeError:
                sys.exit(f"{args.groups}:{number}: not JSON")
            frame = group.get("frame", -1)
            if frame <= args.after_frame:
                continue
            for m in group.get("markers") or []:
                sigma = m.get("sigma")
                if m.get("predicted") or not sigma or min(sigma) <= 0:
                    continue
                p = (m["x"], m["y"], m["z"])
                nearest = min(targets.get(frame, []), key=lambda t: math.dist(t, p), default=None)
                if nearest is None or math.dist(nearest, p) > args.match_radius_mm:
                    continue
                for axis in range(3):
                    z = (p[axis] - nearest[axis]) / sigma[axis]
                    squares += z * z
                    beyond += abs(z) > 3
                    count += 1
    if count == 0:
        sys.exit(f"{args.groups}: no marker near a true target")
    print(f"marker sigmas: {count // 3} markers, RMS error/sigma {math.sqrt(squares / count):.3f} "
          f"per axis, {100.0 * beyond / count:.2f} % beyond 3 sigma (0.27 % for Gaussian errors)")


if __name__ == "__main__":
    main()
