"""`syncap view --calibration DIR`: a `syncap calibrate --out` folder (cameras.json, residuals.csv,
points.csv) shown alone, read back from the .rrd: the wand points in 3D, each camera's residual
vectors (magnified, rejected ones red) and coverage in its image; a broken table named by file
and line; an older folder without the tables shows its cameras and says what it lacks."""

import json
import tempfile
import unittest
from pathlib import Path

import support
from test_cameras import DOC_CAMERA, STEEP_CAMERA
from test_replay import read_rrd, run


class CalibrationFolderTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.folder = Path(self.dir.name) / "calibration"
        self.folder.mkdir()
        (self.folder / "cameras.json").write_text(
            json.dumps({"cameras": [DOC_CAMERA, STEEP_CAMERA]}))
        ids = [DOC_CAMERA["id"], STEEP_CAMERA["id"]]
        rows = ["camera,frame,u_px,v_px,vu_px,vv_px,w,rejected"]
        for i in range(30):
            rows.append(f"{ids[i % 2]},{i},{100 + 10 * i},{200 + 5 * i},0.02,-0.01,0.5,"
                        f"{1 if i == 4 else 0}")
        (self.folder / "residuals.csv").write_text("\n".join(rows) + "\n")
        (self.folder / "points.csv").write_text(
            "x_mm,y_mm,z_mm\n" + "".join(f"{i},{2 * i},{1000 + i}\n" for i in range(12)))
        self.rrd = str(Path(self.dir.name) / "calibration.rrd")
        self.ids = ids

    def tearDown(self):
        self.dir.cleanup()

    def test_points_residuals_and_coverage_per_camera(self):
        result = run("--calibration", str(self.folder), "--save", self.rrd)
        self.assertIn("2 cameras, 12 wand points, 30 residuals", result.stderr)
        entities, frames = read_rrd(self.rrd)
        self.assertEqual(frames, set(), "the calibration belongs to no frame")
        points = entities["/world/calibration/points"][None]
        self.assertEqual(len(points[0]["Points3D:positions"]), 12)
        for camera in self.ids:
            path = f"/world/cameras/{camera:02d}/calibration"
            arrows = entities[f"{path}/residuals"][None][0]
            self.assertEqual(len(arrows["Arrows2D:vectors"]), 15)
            self.assertEqual(len(entities[f"{path}/coverage"][None][0]["Points2D:positions"]), 15)
        # camera of row 4 (the first camera's third row) is the rejected one: red
        colors = entities[f"/world/cameras/{self.ids[0]:02d}/calibration/residuals"][None][0][
            "Arrows2D:colors"]
        self.assertEqual(len(set(colors)), 2)

    def test_the_residuals_are_magnified_so_the_rms_is_visible(self):
        result = run("--calibration", str(self.folder), "--save", self.rrd)
        entities, _ = read_rrd(self.rrd)
        vector = entities[f"/world/cameras/{self.ids[0]:02d}/calibration/residuals"][None][0][
            "Arrows2D:vectors"][0]
        length = (vector[0] ** 2 + vector[1] ** 2) ** 0.5
        widest = max(DOC_CAMERA["image_size"][0], STEEP_CAMERA["image_size"][0])
        self.assertAlmostEqual(length, widest * 10 / 300, delta=0.01 * widest)
        self.assertRegex(result.stderr, r"drawn x \d+")

    def test_a_broken_table_is_named_by_file_and_line(self):
        with open(self.folder / "residuals.csv", "a") as f:
            f.write("0,31,1,2,x,0,0,0\n")
        result = run("--calibration", str(self.folder), "--save", self.rrd, check=False)
        self.assertEqual(result.returncode, 2)
        self.assertIn("residuals.csv:32:", result.stderr)
        (self.folder / "points.csv").write_text("x,y,z\n1,2,3\n")
        (self.folder / "residuals.csv").unlink()
        result = run("--calibration", str(self.folder), "--save", self.rrd, check=False)
        self.assertEqual(result.returncode, 2)
        self.assertIn("points.csv:1: the header", result.stderr)

    def test_an_older_folder_shows_its_cameras_and_says_what_it_lacks(self):
        (self.folder / "residuals.csv").unlink()
        (self.folder / "points.csv").unlink()
        result = run("--calibration", str(self.folder), "--save", self.rrd)
        self.assertIn("no residuals.csv, points.csv", result.stderr)
        entities, _ = read_rrd(self.rrd)
        self.assertIn(f"/world/cameras/{self.ids[0]:02d}", entities)
        self.assertNotIn("/world/calibration/points", entities)

    def test_a_folder_without_cameras_is_a_usage_error(self):
        (self.folder / "cameras.json").unlink()
        result = run("--calibration", str(self.folder), "--save", self.rrd, check=False)
        self.assertEqual(result.returncode, 2)
        self.assertIn("no cameras.json", result.stderr)


if __name__ == "__main__":
    unittest.main()
