"""A camera placed in Rerun (Transform3D + Pinhole, as the viewer logs it) projects object points
where the collinearity equations of host/src/sensor (eqs 4.1, 4.9, 4.13) put them.

The Rerun side is read back from the archetypes' stored values and applied by Rerun's documented
conventions: Transform3D maps the child (camera) frame into the parent (world): X = M p + t;
Pinhole.camera_xyz names the camera axes (codes 1 Up, 2 Down, 3 Right, 4 Left, 5 Forward,
6 Back) and the pinhole projects in Right-Down-Forward with image_from_camera (column-major);
Rerun's pixel (0, 0) is the top-left pixel's corner, syncap's its centre. The reference is
written out here from rotation.hpp and projection.hpp, not taken from the viewer's code."""

import json
import math
import tempfile
import unittest
from pathlib import Path

import numpy as np

import support  # noqa: F401  (sys.path)
from syncap_view import cameras

RDF_OF_CODE = {1: (0, -1, 0), 2: (0, 1, 0), 3: (1, 0, 0), 4: (-1, 0, 0), 5: (0, 0, 1), 6: (0, 0, -1)}

# docs/reference/camera-model.md's example camera, its lens distortion left out (the pinhole has none),
# and a second one looking down at a steep angle with the principal point off centre.
DOC_CAMERA = {"id": 3, "image_size": [1280, 1024], "pixel_size": [0.0067, 0.0067], "c": 6.1,
              "xp": 0.021, "yp": -0.034, "X0": 4200.0, "Y0": -800.0, "Z0": 2300.0,
              "omega": 1.275273, "phi": -0.047836, "kappa": 1.397131}
STEEP_CAMERA = {"id": 7, "image_size": [640, 480], "pixel_size": [0.0099, 0.0088], "c": 4.0,
                "xp": -0.1, "yp": 0.07, "X0": -500.0, "Y0": 300.0, "Z0": 3500.0,
                "omega": 0.3, "phi": -0.2, "kappa": 2.5}


def collinearity_pixel(cam: dict, point) -> tuple[float, float]:
    """syncap's pixel of `point` without distortion: q = R^T (X - X0), x' = xp - c qx/qz,
    y' = yp - c qy/qz, u = x'/mu_x + (nx - 1)/2, v = -y'/mu_y + (ny - 1)/2."""
    co, so = math.cos(cam["omega"]), math.sin(cam["omega"])
    cp, sp = math.cos(cam["phi"]), math.sin(cam["phi"])
    ck, sk = math.cos(cam["kappa"]), math.sin(cam["kappa"])
    r = np.array([[ck * cp, ck * sp * so - sk * co, ck * sp * co + sk * so],  # rotation.hpp,
                  [sk * cp, sk * sp * so + ck * co, sk * sp * co - ck * so],  # written out
                  [-sp, cp * so, cp * co]])
    q = r.T @ (np.asarray(point) - [cam["X0"], cam["Y0"], cam["Z0"]])
    assert q[2] < 0, "behind the camera"
    x = cam["xp"] - cam["c"] * q[0] / q[2]
    y = cam["yp"] - cam["c"] * q[1] / q[2]
    (nx, ny), (mx, my) = cam["image_size"], cam["pixel_size"]
    return x / mx + (nx - 1) / 2, -y / my + (ny - 1) / 2


def rerun_pixel(transform, pinhole, point) -> tuple[float, float]:
    """The pixel Rerun draws `point` at, from the logged archetypes, in syncap's convention."""
    t = np.array(transform.translation.as_arrow_array().to_pylist()[0])
    m = np.array(transform.mat3x3.as_arrow_array().to_pylist()[0]).reshape(3, 3).T  # col-major
    k = np.array(pinhole.image_from_camera.as_arrow_array().to_pylist()[0]).reshape(3, 3).T
    codes = pinhole.camera_xyz.as_arrow_array().to_pylist()[0]
    rdf_from_camera = np.column_stack([RDF_OF_CODE[c] for c in codes])
    p_camera = np.linalg.solve(m, np.asarray(point) - t)
    h = k @ (rdf_from_camera @ p_camera)
    return h[0] / h[2] - 0.5, h[1] / h[2] - 0.5


def points_in_view(cam: dict, rng) -> list:
    """Object points spread over the camera's view, 1-6 m in front of it."""
    r = cameras.rotation_matrix(cam["omega"], cam["phi"], cam["kappa"])
    centre = np.array([cam["X0"], cam["Y0"], cam["Z0"]])
    out = []
    for _ in range(50):
        d = rng.uniform(1000, 6000)
        lateral = rng.uniform(-0.3, 0.3, 2) * d
        out.append(centre + r @ np.array([lateral[0], lateral[1], -d]))
    return out


class CameraPlacementTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.path = Path(self.dir.name) / "cameras.json"
        self.path.write_text(json.dumps({"cameras": [DOC_CAMERA, STEEP_CAMERA]}))

    def tearDown(self):
        self.dir.cleanup()

    def test_pinhole_projects_as_the_collinearity_equations(self):
        rng = np.random.default_rng(19)
        for cam_json, cam in zip([DOC_CAMERA, STEEP_CAMERA], cameras.read_cameras(self.path)):
            transform, pinhole = cameras.archetypes(cam)
            self.assertEqual(pinhole.resolution.as_arrow_array().to_pylist()[0],
                             [float(v) for v in cam_json["image_size"]])
            for point in points_in_view(cam_json, rng):
                want = collinearity_pixel(cam_json, point)
                got = rerun_pixel(transform, pinhole, point)
                # Rerun stores float32: 1e-7 of a 4 km translation is ~0.5 um, of a 900 px focal
                # length 1e-4 px.
                self.assertAlmostEqual(got[0], want[0], delta=2e-3, msg=f"camera {cam.id} u")
                self.assertAlmostEqual(got[1], want[1], delta=2e-3, msg=f"camera {cam.id} v")

    def test_the_camera_looks_along_its_minus_z_axis(self):
        """A point on its -z axis projects to the principal point."""
        cam = cameras.read_cameras(self.path)[0]
        transform, pinhole = cameras.archetypes(cam)
        ahead = cam.centre - 2000.0 * cam.rotation[:, 2]
        u, v = rerun_pixel(transform, pinhole, ahead)
        self.assertAlmostEqual(u, (1280 - 1) / 2 + 0.021 / 0.0067, delta=1e-3)
        self.assertAlmostEqual(v, (1024 - 1) / 2 + 0.034 / 0.0067, delta=1e-3)

    def test_errors_name_the_file_camera_and_field(self):
        bad = dict(DOC_CAMERA, c=-1)
        self.path.write_text(json.dumps({"cameras": [bad]}))
        with self.assertRaisesRegex(cameras.CameraFileError, r'cameras.json: camera 3: field "c"'):
            cameras.read_cameras(self.path)
        del bad["X0"]
        bad["c"] = 6.1
        self.path.write_text(json.dumps({"cameras": [bad]}))
        with self.assertRaisesRegex(cameras.CameraFileError, r'camera 3: field "X0" is missing'):
            cameras.read_cameras(self.path)
        with self.assertRaisesRegex(cameras.CameraFileError, "cannot read"):
            cameras.read_cameras(Path(self.dir.name) / "absent.json")


if __name__ == "__main__":
    unittest.main()
