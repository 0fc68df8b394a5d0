#!/usr/bin/env python3
"""Reads the exports of syncap-io-export-samples back with independent readers and checks every
value against the synthetic trajectories (synthetic_trajectories.hpp; the formulas are repeated
here). C3D: PyPI ezc3d and c3d; TRC: plain parsing as OpenSim's TRCFileAdapter does it; BVH:
PyPI bvh (leg.bvh, the motion export_samples_main.cpp writes).

ezc3d (1.7.2) decodes the fourth word of float data as two 16-bit integers, not as the C3D guide's
integer stored as a float (pyomeca/ezc3d issue 386), so residuals and camera masks are checked
with c3d, positions, gaps, labels, rate and frame counts with both.

Exits 77 (skip) when neither reader can be imported, 1 on the first wrong value."""
import math
import sys
import warnings

SKIP = 77


def seen(f, m):
    return (f * 7 + m * 3) % 11 != 0


def position(f, m):
    return (100.0 * m + 0.5 * f, -50.0 * m + 0.25 * f, 1000.0 + m - 0.125 * f)


def residual(f, m):
    return 0.1 + 0.01 * ((f + m) % 50)


def cameras(f, m):
    return (f + m) % 512


def labels(markers):
    return ["M%03d" % (m + 1) for m in range(markers)]


# name: (frames, markers, rate, labels, first syncap frame), as export_samples_main.cpp writes them
SMALL_LABELS = labels(3)
SMALL_LABELS[1] = "RigidSetLeftWrist_with_a_long_name"
CASES = {
    "small": (50, 3, 100.0, SMALL_LABELS, 1234),
    "wide": (4, 300, 250.0, labels(300), 0),
    "long": (70000, 2, 120.0, labels(2), 7),
}


class Mismatch(Exception):
    pass


def expect(condition, what):
    if not condition:
        raise Mismatch(what)


def check_ezc3d(ezc3d, path, frames, markers, rate, names):
    c3d = ezc3d.c3d(path)
    point = c3d["parameters"]["POINT"]
    read_names = list(point["LABELS"]["value"])
    part = 2
    while "LABELS%d" % part in point:
        read_names += list(point["LABELS%d" % part]["value"])
        part += 1
    expect(read_names == names, "ezc3d labels %s..." % read_names[:3])
    expect(point["RATE"]["value"][0] == rate, "ezc3d rate %s" % point["RATE"]["value"])
    expect(c3d["header"]["points"]["frame_rate"] == rate, "ezc3d header rate")
    points = c3d["data"]["points"]
    expect(points.shape == (4, markers, frames), "ezc3d data shape %s" % (points.shape,))
    residuals = c3d["data"]["meta_points"]["residuals"]
    for f in sampled_frames(frames):
        for m in range(markers):
            if seen(f, m):
                for axis, value in enumerate(position(f, m)):
                    expect(points[axis, m, f] == value, "ezc3d %s[%d] f%d m%d" % (path, axis, f, m))
                expect(residuals[0, m, f] >= 0, "ezc3d marks seen f%d m%d invalid" % (f, m))
            else:
                expect(math.isnan(points[0, m, f]), "ezc3d gap f%d m%d not NaN" % (f, m))
                expect(residuals[0, m, f] < 0, "ezc3d gap f%d m%d residual" % (f, m))


def check_c3d(c3d, path, frames, markers, rate, names):
    with open(path, "rb") as handle, warnings.catch_warnings():
        warnings.simplefilter("ignore")  # "No analog data found": there is none by design
        reader = c3d.Reader(handle)
        expect(c3d_labels(reader) == names, "c3d labels")
        expect(reader.point_rate == rate, "c3d rate %s" % reader.point_rate)
        expect(reader.frame_count == frames, "c3d frame count %d" % reader.frame_count)
        scale = abs(reader.point_scale)
        wanted = set(sampled_frames(frames))
        read = 0
        for index, (_, points, _) in enumerate(reader.read_frames()):
            read += 1
            if index in wanted:
                check_c3d_frame(points, index, markers, scale)
        expect(read == frames, "c3d read %d frames" % read)


def c3d_labels(reader):
    """POINT:LABELS, LABELS2, ...: c3d's point_labels stops at the first 255."""
    names = list(reader.point_labels)
    part = 2
    while reader.get("POINT:LABELS%d" % part) is not None:
        names += list(reader.get("POINT:LABELS%d" % part).string_array)
        part += 1
    return [str(n).rstrip() for n in names]


def check_c3d_frame(points, f, markers, scale):
    for m in range(markers):
        x, y, z, res, mask = points[m]
        if not seen(f, m):
            expect(res == -1, "c3d gap f%d m%d residual %s" % (f, m, res))
            continue
        expect((x, y, z) == position(f, m), "c3d position f%d m%d" % (f, m))
        units = min(255, max(1, round(residual(f, m) / scale)))
        expect(abs(res - units * scale) < 1e-6, "c3d residual f%d m%d: %s" % (f, m, res))
        expect(mask == cameras(f, m) & 0x7F, "c3d camera mask f%d m%d: %s" % (f, m, mask))


def sampled_frames(frames):
    """Every frame of a short case; a spread, with both sides of 65535, of a long one."""
    if frames <= 1000:
        return range(frames)
    return sorted(set(list(range(0, frames, 997)) + [65534, 65535, 65536, frames - 1]) - {-1})


def check_trc(path, frames, markers, rate, names, first_frame):
    with open(path) as handle:
        lines = handle.read().split("\n")
    expect(lines[0].split("\t")[:3] == ["PathFileType", "4", "(X/Y/Z)"], "TRC line 1")
    keys = lines[1].split("\t")
    values = dict(zip(keys, lines[2].split("\t")))
    expect(float(values["DataRate"]) == rate, "TRC DataRate")
    expect(int(values["NumFrames"]) == frames, "TRC NumFrames")
    expect(int(values["NumMarkers"]) == markers, "TRC NumMarkers")
    expect(values["Units"] == "mm", "TRC Units")
    expect(int(values["OrigDataStartFrame"]) == first_frame, "TRC OrigDataStartFrame")
    expect([n for n in lines[3].split("\t") if n] == ["Frame#", "Time"] + names, "TRC labels")
    xyz = [n for n in lines[4].split("\t") if n]
    expect(xyz == ["%s%d" % (a, m + 1) for m in range(markers) for a in "XYZ"], "TRC X1 Y1 Z1")
    rows = [line for line in lines[5:] if line]
    expect(len(rows) == frames, "TRC has %d rows" % len(rows))
    for f, row in enumerate(rows):
        check_trc_row(row, f, markers, rate)


def check_trc_row(row, f, markers, rate):
    fields = row.split("\t")
    if fields[-1] == "":  # OpenSim drops the empty field after a line's last tab
        fields.pop()
    expect(len(fields) == 2 + 3 * markers, "TRC row %d has %d fields" % (f, len(fields)))
    expect(int(fields[0]) == f + 1 and abs(float(fields[1]) - f / rate) < 1e-12, "TRC row %d" % f)
    for m in range(markers):
        cells = fields[2 + 3 * m: 5 + 3 * m]
        if not seen(f, m):
            expect(cells == ["", "", ""], "TRC gap f%d m%d: %s" % (f, m, cells))
            continue
        got = [float(c) for c in cells]
        expect(all(abs(a - b) < 5e-5 for a, b in zip(got, position(f, m))), "TRC f%d m%d" % (f, m))


def check_bvh(module, path):
    """leg.bvh: root, l_hip, l_knee; Y up in metres; the root rising 1 mm and the knee bending
    1 degree about X a frame, 10 frames at 50 Hz."""
    with open(path) as handle:
        motion = module.Bvh(handle.read())
    expect(motion.get_joints_names() == ["root", "l_hip", "l_knee"],
           "BVH joints %s" % motion.get_joints_names())
    expect(motion.joint_parent_index("l_knee") == 1, "BVH l_knee's parent")
    expect(motion.joint_offset("l_hip") == (0.1, -0.05, 0.0), "BVH l_hip offset %s"
           % (motion.joint_offset("l_hip"),))
    expect(motion.joint_channels("root") == ["Xposition", "Yposition", "Zposition", "Zrotation",
                                             "Xrotation", "Yrotation"], "BVH root channels")
    expect(motion.joint_channels("l_knee") == ["Zrotation", "Xrotation", "Yrotation"],
           "BVH l_knee channels")
    expect(motion.nframes == 10 and motion.frame_time == 0.02, "BVH frames %d, frame time %s"
           % (motion.nframes, motion.frame_time))
    for f in range(10):
        root_y = motion.frame_joint_channel(f, "root", "Yposition")
        expect(abs(root_y - (0.9 + 0.001 * f)) < 1e-9, "BVH f%d root Y %s" % (f, root_y))
        knee = motion.frame_joint_channels(f, "l_knee", ["Zrotation", "Xrotation", "Yrotation"])
        expect(abs(knee[0]) < 1e-9 and abs(knee[1] - f) < 1e-6 and abs(knee[2]) < 1e-9,
               "BVH f%d knee %s" % (f, knee))


def import_readers():
    readers = {}
    for name in ("ezc3d", "c3d"):
        try:
            module = __import__(name)
        except ImportError as error:
            print("reader %s not importable: %s" % (name, error))
            continue
        readers[name] = module
    return readers


def version(name):
    from importlib.metadata import version as installed
    try:
        return installed(name)
    except Exception:  # a module without package metadata
        return "unknown"


def main():
    folder = sys.argv[1]
    readers = import_readers()
    if not readers:
        print("SKIP: neither ezc3d nor c3d can be imported (run scripts/py-deps.sh)")
        return SKIP
    print("readers: " + ", ".join("%s %s" % (n, version(n)) for n in readers))
    checks = {"ezc3d": check_ezc3d, "c3d": check_c3d}
    try:
        for case, (frames, markers, rate, names, first_frame) in CASES.items():
            for name, module in readers.items():
                checks[name](module, "%s/%s.c3d" % (folder, case), frames, markers, rate, names)
                print("%s.c3d read by %s: %d frames x %d markers match" % (case, name, frames, markers))
            if case != "long":
                check_trc("%s/%s.trc" % (folder, case), frames, markers, rate, names, first_frame)
                print("%s.trc: %d frames x %d markers match" % (case, frames, markers))
        import bvh  # pinned by scripts/py-deps.sh beside the C3D readers: missing is a failure
        check_bvh(bvh, "%s/leg.bvh" % folder)
        print("leg.bvh read by bvh %s: 3 joints x 10 frames match" % version("bvh"))
    except Mismatch as error:
        print("FAIL: %s" % error)
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
