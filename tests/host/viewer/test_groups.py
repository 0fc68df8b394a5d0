"""`syncap view --groups FILE`: the host's JSON lines (host/src/io/frame_json.hpp) replayed into
an .rrd: the fuzz corpus' sample lines as the host writes them, and a line with a rigid set, a
hull and a body; a broken line named by file and line number, the rest still shown."""

import json
import tempfile
import unittest
from pathlib import Path

import support
from test_replay import read_rrd, run

CORPUS = support.REPO / "tests" / "fuzz" / "corpus" / "frame_json"
JOINTS = ["HumanoidRoot", "vl5", "vt10", "vc7", "skullbase", "l_sternoclavicular",
          "r_sternoclavicular", "l_shoulder", "r_shoulder", "l_elbow", "r_elbow", "l_wrist",
          "r_wrist", "l_hip", "r_hip", "l_knee", "r_knee", "l_ankle", "r_ankle"]

FULL_LINE = {
    "body": {"fit_us": 30000, "flags": 2, "points": 2000, "points_kept": 1900, "rms_mm": 9.5,
             "joints": {n: [10.0 * i, 0.0, 1000.0 + i] for i, n in enumerate(JOINTS)}},
    "cameras": {}, "complete": True, "frame": 50,
    "hull": {"area_mm2": 2.0e6, "cameras": 6, "faces": 996, "flags": 0, "hull_us": 19000,
             "max": [400, 400, 1800], "min": [-400, -400, 0], "vertices": 500,
             "volume_mm3": 7.0e7},
    "markers": [{"cameras": [0, 1, 2], "id": 3, "residual_px": 0.2, "sigma": [0.1, 0.1, 0.1],
                 "x": 1.0, "y": 2.0, "z": 3.0}],
    "missing_cameras": [],
    "rigid_sets": [{"found": True, "marker_ids": [3, 4, 5], "name": "tool", "rms_mm": 0.4,
                    "rotation": [0, -1, 0, 1, 0, 0, 0, 0, 1], "translation": [100, 200, 1200]},
                   {"found": False, "name": "wand"}],
}


class GroupsTest(unittest.TestCase):
    def test_json_lines_replayed(self):
        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "groups.jsonl"
            lines = [(CORPUS / f).read_text().strip() for f in
                     ("short_with_defaults.json", "non_finite_as_null.json",
                      "silhouettes_without_markers.json", "tracked_group.json")]
            lines += ["{not json", json.dumps(FULL_LINE)]
            path.write_text("\n".join(lines) + "\n")
            rrd = str(Path(d) / "groups.rrd")
            result = run("--groups", str(path), "--save", rrd)
            entities, frames = read_rrd(rrd)
        self.assertEqual(frames, {4, 9, 41, 1207, 50})
        self.assertRegex(result.stderr, r"groups.jsonl:5 .*does not read")
        self.assertIn("1 messages skipped", result.stderr)
        for path in ("/cameras/02/blobs", "/cameras/01/silhouette", "/cameras/03/silhouette",
                     "/world/markers", "/world/rigid/tool", "/world/rigid/wand",
                     "/plots/rigid/tool/rms_mm", "/world/hull/bbox", "/plots/hull/volume_l",
                     "/world/body/joints", "/world/body/bones", "/plots/body/rms_mm"):
            self.assertIn(path, entities, result.stderr)
        self.assertEqual(len(entities["/world/body/bones"][50][0]["LineStrips3D:strips"]), 18)
        # the null coordinates of non_finite_as_null are left out, the rest kept
        self.assertEqual(entities["/cameras/04/blobs"][9][0].get("Points2D:positions"), [])
        self.assertEqual(len(entities["/world/markers"][9][0]["Points3D:positions"]), 1)
        strips = entities["/cameras/01/silhouette"][41][0]["LineStrips2D:strips"]
        self.assertEqual(len(strips), 2)


if __name__ == "__main__":
    unittest.main()
