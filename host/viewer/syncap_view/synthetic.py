"""Made-up but consistent traffic for the tests and the benchmark: cameras in a ring looking at
the origin, markers moving in the volume and their blobs where the cameras see them (the
collinearity equations without distortion), a silhouette, a hull's box and a body per frame.
Messages are encoded with the bindings generated from proto/msg, as the system sends them."""

from __future__ import annotations

import json
import math

import lcm
import numpy as np

from .cameras import rotation_matrix
from .contour import encode_pieces

WIDTH, HEIGHT, PIXEL_MM, C_MM = 640, 480, 0.0099, 6.0


def angles_from_rotation(r: np.ndarray) -> tuple[float, float, float]:
    """omega, phi, kappa of R = R_kappa R_phi R_omega (host/src/sensor/rotation.cpp)."""
    phi = math.atan2(-r[2, 0], math.hypot(r[0, 0], r[1, 0]))
    return math.atan2(r[2, 1], r[2, 2]), phi, math.atan2(r[1, 0], r[0, 0])


def look_at(centre, target) -> tuple[float, float, float]:
    """The angles of a camera at `centre` looking at `target`, image right horizontal."""
    back = np.asarray(centre, float) - np.asarray(target, float)
    z = back / np.linalg.norm(back)               # z': the camera looks along -z'
    x = np.cross([0.0, 0.0, 1.0], z)
    x /= np.linalg.norm(x)                        # x': right, horizontal
    y = np.cross(z, x)                            # y': up
    return angles_from_rotation(np.column_stack([x, y, z]))


def ring_cameras(n: int, radius_mm: float = 4000.0, height_mm: float = 2200.0) -> list[dict]:
    """cameras.json entries (docs/reference/camera-model.md) of n cameras in a ring around the origin."""
    out = []
    for i in range(n):
        a = 2 * math.pi * i / n
        centre = [radius_mm * math.cos(a), radius_mm * math.sin(a), height_mm]
        omega, phi, kappa = look_at(centre, [0.0, 0.0, 900.0])
        out.append({"id": i, "image_size": [WIDTH, HEIGHT], "pixel_size": [PIXEL_MM, PIXEL_MM],
                    "c": C_MM, "xp": 0.01 * (i % 3 - 1), "yp": -0.02 * (i % 2),
                    "k1": 0.0, "k2": 0.0, "k3": 0.0, "p1": 0.0, "p2": 0.0, "sc": 0.0, "sh": 0.0,
                    "X0": centre[0], "Y0": centre[1], "Z0": centre[2],
                    "omega": omega, "phi": phi, "kappa": kappa})
    return out


def write_cameras(path, cameras: list[dict]) -> None:
    with open(path, "w") as f:
        json.dump({"cameras": cameras}, f, indent=1)


def project(camera: dict, point) -> tuple[float, float] | None:
    """The pixel (syncap's: (0, 0) the top-left pixel's centre) of a point, by the collinearity
    equations (eq 4.9, 4.13) without distortion; None behind the camera."""
    r = rotation_matrix(camera["omega"], camera["phi"], camera["kappa"])
    q = r.T @ (np.asarray(point, float) - [camera["X0"], camera["Y0"], camera["Z0"]])
    if q[2] >= 0:
        return None
    x = camera["xp"] - camera["c"] * q[0] / q[2]
    y = camera["yp"] - camera["c"] * q[1] / q[2]
    nx, ny = camera["image_size"]
    mx, my = camera["pixel_size"]
    return x / mx + (nx - 1) / 2, -y / my + (ny - 1) / 2


def marker_positions(frame: int, count: int) -> np.ndarray:
    """count markers on a slowly turning, bobbing cloud around (0, 0, 1000) mm."""
    k = np.arange(count)
    a = 2 * math.pi * k / max(count, 1) + 0.05 * frame
    r = 300.0 + 10.0 * (k % 7)
    return np.column_stack([r * np.cos(a), r * np.sin(a),
                            1000.0 + 400.0 * np.sin(0.7 * k + 0.02 * frame)])


class LogWriter:
    """Messages into an LCM log file, as `syncap record` writes them."""

    def __init__(self, path: str, types):
        self.log = lcm.EventLog(path, "w", overwrite=True)
        self.t = types
        self.utime = 1_000_000

    def write(self, channel: str, msg_or_bytes) -> None:
        data = msg_or_bytes if isinstance(msg_or_bytes, bytes) else msg_or_bytes.encode()
        self.log.write_event(self.utime, channel, data)
        self.utime += 100

    def close(self):
        self.log.close()

    # --- one message type each ---

    def trigger(self, frame: int):
        m = self.t.trigger_t()
        m.frame_number, m.monotonic_ns, m.rate_hz = frame, 10**9 + frame * 33_333_333, 30.0
        m.realtime_ns = m.monotonic_ns
        self.write("SYNCAP_TRIGGER", m)

    def blobs(self, camera: int, frame: int, pixels, per_part: int | None = None):
        """A blob frame split into parts of at most per_part blobs (default MAX_BLOBS)."""
        per_part = per_part or self.t.blob_frame_t.MAX_BLOBS
        blobs = []
        for u, v in pixels:
            b = self.t.blob_t()
            b.x, b.y, b.area, b.peak = float(u), float(v), 12.0, 200
            b.bbox_x, b.bbox_y, b.bbox_w, b.bbox_h = int(u) - 2, int(v) - 2, 5, 5
            blobs.append(b)
        chunks = [blobs[i:i + per_part] for i in range(0, len(blobs), per_part)] or [[]]
        for index, chunk in enumerate(chunks):
            m = self.t.blob_frame_t()
            m.camera_id, m.frame_number, m.processing_us = camera, frame, 150 + camera
            m.image_width, m.image_height = WIDTH, HEIGHT
            m.part_index, m.part_count, m.total_blobs = index, len(chunks), len(blobs)
            m.num_blobs, m.blobs = len(chunk), chunk
            self.write(f"SYNCAP_BLOBS_{camera:02d}", m)

    def silhouette(self, camera: int, frame: int, parts_pieces):
        """parts_pieces: per part, a list of pieces (points, hole, continues)."""
        for index, pieces in enumerate(parts_pieces):
            m = self.t.silhouette_part_t()
            m.camera_id, m.frame_number = camera, frame
            m.image_width, m.image_height = WIDTH, HEIGHT
            m.part_index, m.part_count = index, len(parts_pieces)
            m.data = encode_pieces(pieces)
            m.num_pieces, m.data_size = len(pieces), len(m.data)
            self.write(f"SYNCAP_SIL_{camera:02d}", m)

    def markers(self, frame: int, positions, per_part: int | None = None):
        per_part = per_part or self.t.marker_frame_t.MAX_MARKERS
        markers = []
        for i, p in enumerate(positions):
            mk = self.t.marker_t()
            mk.id, (mk.x, mk.y, mk.z) = i, (float(v) for v in p)
            mk.sigma_x = mk.sigma_y = mk.sigma_z = 0.5
            mk.cameras = 3
            markers.append(mk)
        chunks = [markers[i:i + per_part] for i in range(0, len(markers), per_part)] or [[]]
        for index, chunk in enumerate(chunks):
            m = self.t.marker_frame_t()
            m.frame_number, m.host_us, m.cameras = frame, 800, 3
            m.part_index, m.part_count, m.total_markers = index, len(chunks), len(markers)
            m.num_markers, m.markers = len(chunk), chunk
            self.write("SYNCAP_MARKERS", m)

    def hull(self, frame: int, lo, hi, flags: int = 0):
        m = self.t.hull_frame_t()
        m.frame_number, m.flags, m.cameras, m.vertices, m.faces = frame, flags, 3, 500, 996
        m.hull_us, m.host_us = 19000, 19500
        m.min_mm, m.max_mm = [float(v) for v in lo], [float(v) for v in hi]
        m.volume_mm3 = 0.0 if flags & 4 else float(np.prod(np.subtract(hi, lo))) * 0.4
        m.area_mm2 = 2.0e6
        self.write("SYNCAP_HULL", m)

    def body(self, frame: int, offset_mm=(0.0, 0.0, 0.0)):
        m = self.t.body_frame_t()
        m.frame_number, m.flags, m.rms_mm, m.points, m.points_kept = frame, 2, 9.5, 2000, 1900
        m.fit_us, m.host_us = 30000, 31000
        m.joint_mm = [[float(a + b) for a, b in zip(j, offset_mm)] for j in STANDING_JOINTS_MM]
        self.write("SYNCAP_BODY", m)

    def status(self, camera: int, frame: int, message: str = ""):
        m = self.t.camera_status_t()
        m.camera_id, m.state, m.last_frame_number = camera, 1, frame
        m.frames_received, m.frames_lost, m.frame_rate_hz = frame + 1, 0, 30.0
        m.processing_us_mean, m.last_command_result, m.message = 150.0, -1, message
        self.write(f"SYNCAP_STATUS_{camera:02d}", m)


# A standing person's joint centres [mm], in body_frame_t's order.
STANDING_JOINTS_MM = [
    (0, 0, 950), (0, 0, 1050), (0, 0, 1250), (0, 0, 1450), (0, 0, 1600),  # root .. skullbase
    (-30, 0, 1430), (30, 0, 1430), (-180, 0, 1420), (180, 0, 1420),        # sternoclav., shoulders
    (-200, 0, 1150), (200, 0, 1150), (-210, 0, 900), (210, 0, 900),        # elbows, wrists
    (-90, 0, 900), (90, 0, 900), (-95, 0, 500), (95, 0, 500),              # hips, knees
    (-100, 0, 80), (100, 0, 80)]                                           # ankles
