"""A calibration folder of `syncap calibrate --out DIR` in the viewer (issue 19, "calibration
report plots"): the network in 3D (the cameras' frusta and the adjusted wand points), and in each
camera's image what easyWand and MultiCamSelfCal users look at: the residual vectors, magnified,
and the coverage of the image by measurements. Read from DIR/cameras.json, DIR/residuals.csv and
DIR/points.csv (the tables beside report.html); a folder from before those tables existed shows
its cameras only. Logged as static data: it belongs to no frame."""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import cameras as cams

RESIDUAL_COLUMNS = ["camera", "frame", "u_px", "v_px", "vu_px", "vv_px", "w", "rejected"]
POINT_COLUMNS = ["x_mm", "y_mm", "z_mm"]
# The residual vectors are drawn magnified so that the RMS residual is this share of the image's
# width (report.html draws it as 10 px of a 300-px image).
RMS_DRAWN_AS_WIDTH = 10.0 / 300.0


class CalibrationFolderError(ValueError):
    """A calibration folder that cannot be read; the message names the file and line."""


@dataclass
class Residual:
    camera: int
    u: float
    v: float
    vu: float
    vv: float
    rejected: bool


@dataclass
class CalibrationFolder:
    cameras: list
    residuals: list[Residual]
    points: np.ndarray  # (n, 3) mm
    missing: list[str]  # tables the folder lacks (an older calibration)


def _rows(path: Path, columns: list[str]):
    """The table's rows as dicts of floats, each with its line number; the header must match."""
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader, None)
        if header != columns:
            raise CalibrationFolderError(f"{path}:1: the header is {header}, not {columns}")
        for line, row in enumerate(reader, start=2):
            if len(row) != len(columns):
                raise CalibrationFolderError(
                    f"{path}:{line}: {len(row)} fields, not {len(columns)}")
            try:
                values = [float(x) for x in row]
            except ValueError as e:
                raise CalibrationFolderError(f"{path}:{line}: {e}") from None
            if not all(math.isfinite(x) for x in values):
                raise CalibrationFolderError(f"{path}:{line}: a value that is not finite")
            yield line, dict(zip(columns, values))


def read_folder(folder: str | Path) -> CalibrationFolder:
    folder = Path(folder)
    if not (folder / "cameras.json").is_file():
        raise CalibrationFolderError(f"{folder}: no cameras.json (a syncap calibrate --out folder?)")
    try:
        cameras = cams.read_cameras(folder / "cameras.json")
    except cams.CameraFileError as e:
        raise CalibrationFolderError(str(e)) from None
    missing, residuals, points = [], [], np.zeros((0, 3))
    if (folder / "residuals.csv").is_file():
        residuals = [Residual(int(r["camera"]), r["u_px"], r["v_px"], r["vu_px"], r["vv_px"],
                              r["rejected"] != 0)
                     for _, r in _rows(folder / "residuals.csv", RESIDUAL_COLUMNS)]
    else:
        missing.append("residuals.csv")
    if (folder / "points.csv").is_file():
        points = np.array([[r["x_mm"], r["y_mm"], r["z_mm"]]
                           for _, r in _rows(folder / "points.csv", POINT_COLUMNS)]).reshape(-1, 3)
    else:
        missing.append("points.csv")
    return CalibrationFolder(cameras, residuals, points, missing)


def residual_scale(folder: CalibrationFolder) -> float:
    """The magnification that draws the RMS residual (of the accepted ones) as RMS_DRAWN_AS_WIDTH
    of the widest image."""
    kept = [r for r in folder.residuals if not r.rejected]
    if not kept or not folder.cameras:
        return 1.0
    rms = math.sqrt(sum(r.vu * r.vu + r.vv * r.vv for r in kept) / len(kept))
    width = max(c.width for c in folder.cameras)
    return RMS_DRAWN_AS_WIDTH * width / rms if rms > 0 else 1.0


def log_folder(rr, folder: CalibrationFolder, camera_path) -> dict:
    """Logs the wand points and, per camera, its residual vectors and coverage (static). Returns
    what was logged: {"points": n, "residuals": {camera: n}, "scale": magnification}."""
    if len(folder.points):
        rr.log("world/calibration/points",
               rr.Points3D(folder.points.astype(np.float32), radii=[6.0],
                           colors=[(120, 160, 255)]), static=True)
    scale = residual_scale(folder)
    logged = {"points": len(folder.points), "residuals": {}, "scale": scale}
    by_camera: dict[int, list[Residual]] = {}
    for r in folder.residuals:
        by_camera.setdefault(r.camera, []).append(r)
    for camera, rows in sorted(by_camera.items()):
        path = camera_path(camera)
        origins = np.array([(r.u, r.v) for r in rows], dtype=np.float32) + cams.PIXEL_OFFSET
        vectors = np.array([(r.vu, r.vv) for r in rows], dtype=np.float32) * scale
        colors = [(220, 40, 40) if r.rejected else (40, 170, 90) for r in rows]
        rr.log(f"{path}/calibration/residuals",
               rr.Arrows2D(origins=origins, vectors=vectors, colors=colors), static=True)
        rr.log(f"{path}/calibration/coverage",
               rr.Points2D(origins, radii=[1.5], colors=[(120, 160, 255)]), static=True)
        logged["residuals"][camera] = len(rows)
    return logged
