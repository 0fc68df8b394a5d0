"""cameras.json (docs/reference/camera-model.md) as Rerun transforms and pinholes.

The thesis' camera (host/src/sensor/camera_model.hpp, rotation.hpp, projection.hpp): a point's
sensor coordinates are q = R^T (X - X0) with R = R_kappa R_phi R_omega, whose columns are the
sensor axes x' (right), y' (up), z' in the calibration's frame; the camera looks along -z'.
So each camera is a Transform3D (translation X0, matrix R: world from sensor) and a Pinhole
whose camera axes are Right, Up, Back (ViewCoordinates.RUB).

Pixels: syncap puts (0, 0) at the centre of the top-left pixel (u right, v down); Rerun at its
top-left corner. Everything 2D the viewer logs under a pinhole is therefore shifted by +0.5 px
(PIXEL_OFFSET), and so is the principal point:
  u = (xp + x') / mu_x + (nx - 1) / 2 in syncap's pixels  ->  cx = xp / mu_x + nx / 2 in Rerun's,
  v = -(yp + y') / mu_y + (ny - 1) / 2                     ->  cy = -yp / mu_y + ny / 2.
The pinhole has no lens distortion or affinity (k1.., p1, p2, sc, sh): the frustum is the
camera's ideal one; blobs and contours are shown where the camera measured them.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

PIXEL_OFFSET = 0.5  # syncap pixel -> Rerun pixel


class CameraFileError(ValueError):
    """cameras.json does not read; the message names the file, the camera and the field."""


@dataclass
class Camera:
    id: int
    width: int
    height: int
    pixel_w: float  # mm
    pixel_h: float
    c: float        # principal distance, mm
    xp: float       # principal point from the sensor centre, mm, y' up
    yp: float
    centre: np.ndarray    # X0, Y0, Z0 [mm]
    rotation: np.ndarray  # R: columns are the sensor axes in the calibration's frame

    def focal_px(self) -> tuple[float, float]:
        return self.c / self.pixel_w, self.c / self.pixel_h

    def principal_point_rerun(self) -> tuple[float, float]:
        return (self.xp / self.pixel_w + self.width / 2.0,
                -self.yp / self.pixel_h + self.height / 2.0)


def rotation_matrix(omega: float, phi: float, kappa: float) -> np.ndarray:
    """R = R_kappa R_phi R_omega, the elementary rotations right-handed about x, y, z
    (host/src/sensor/rotation.hpp)."""
    co, so = math.cos(omega), math.sin(omega)
    cp, sp = math.cos(phi), math.sin(phi)
    ck, sk = math.cos(kappa), math.sin(kappa)
    r_omega = np.array([[1, 0, 0], [0, co, -so], [0, so, co]])
    r_phi = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    r_kappa = np.array([[ck, -sk, 0], [sk, ck, 0], [0, 0, 1]])
    return r_kappa @ r_phi @ r_omega


def _number(obj: dict, name: str, where: str) -> float:
    if name not in obj:
        raise CameraFileError(f'{where}: field "{name}" is missing')
    value = obj[name]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise CameraFileError(f'{where}: field "{name}" must be a number')
    return float(value)


def _pair(obj: dict, name: str, where: str, integer: bool) -> tuple:
    value = obj.get(name)
    ok = (isinstance(value, list) and len(value) == 2 and
          all(isinstance(v, (int, float)) and not isinstance(v, bool) and v > 0 for v in value))
    if ok and integer:
        ok = all(float(v).is_integer() for v in value)
    if not ok:
        kind = "two positive integers" if integer else "two positive numbers"
        raise CameraFileError(f'{where}: field "{name}" must be [width, height], {kind}')
    return (int(value[0]), int(value[1])) if integer else (float(value[0]), float(value[1]))


def read_cameras(path: str | Path) -> list[Camera]:
    """The cameras of a cameras.json; what the viewer does not show (k1.., std, quality) is not
    checked here (syncap's own reader is strict about those)."""
    path = Path(path)
    try:
        doc = json.loads(path.read_text())
    except OSError as e:
        raise CameraFileError(f"{path}: cannot read: {e.strerror}") from None
    except json.JSONDecodeError as e:
        raise CameraFileError(f"{path}: not JSON: {e}") from None
    if not isinstance(doc, dict) or not isinstance(doc.get("cameras"), list):
        raise CameraFileError(f'{path}: field "cameras" must be a list')
    cameras = []
    for index, obj in enumerate(doc["cameras"]):
        where = f"{path}: cameras[{index}]"
        if not isinstance(obj, dict):
            raise CameraFileError(f"{where}: must be an object")
        cid = obj.get("id")
        if isinstance(cid, bool) or not isinstance(cid, int) or not 0 <= cid <= 99:
            raise CameraFileError(f'{where}: field "id" must be an integer from 0 to 99')
        where = f"{path}: camera {cid}"
        width, height = _pair(obj, "image_size", where, integer=True)
        pixel_w, pixel_h = _pair(obj, "pixel_size", where, integer=False)
        c = _number(obj, "c", where)
        if c <= 0:
            raise CameraFileError(f'{where}: field "c" must be a positive number')
        centre = np.array([_number(obj, n, where) for n in ("X0", "Y0", "Z0")])
        angles = [_number(obj, n, where) for n in ("omega", "phi", "kappa")]
        cameras.append(Camera(cid, width, height, pixel_w, pixel_h, c,
                              _number(obj, "xp", where), _number(obj, "yp", where),
                              centre, rotation_matrix(*angles)))
    return cameras


def archetypes(camera: Camera, image_plane_mm: float | None = None):
    """(Transform3D, Pinhole) placing `camera` in the calibration's frame (Z up, mm)."""
    import rerun as rr

    transform = rr.Transform3D(translation=camera.centre, mat3x3=camera.rotation)
    pinhole = rr.Pinhole(resolution=[camera.width, camera.height],
                         focal_length=list(camera.focal_px()),
                         principal_point=list(camera.principal_point_rerun()),
                         camera_xyz=rr.ViewCoordinates.RUB,
                         image_plane_distance=image_plane_mm)
    return transform, pinhole
