"""From decoded messages to Rerun entities, one method per message type, on the timeline "frame".

Entity paths (docs/guide/view.md lists them):
  world                                  the calibration's frame: Z up, mm
  world/cameras/NN                       a calibrated camera: Transform3D + Pinhole
  world/cameras/NN/{blobs,silhouette,clip,floor,search}   its 2D content, in its image
  cameras/NN/{sensor,blobs,silhouette,clip,floor,search}  the same for a camera without calibration
  world/markers, world/markers/trails    3D markers (labels: their ids), their last frames
  world/rigid/NAME                       rigid sets' poses (JSON lines only)
  world/hull/bbox                        the visual hull's bounding box
  world/body/joints, world/body/bones    the fitted skeleton
  plots/...                              scalars: the edges' status, the host's times
  log/...                                text: status messages, commands, skipped messages
"""

from __future__ import annotations

import io
import json
import re
import sys
from collections import Counter, defaultdict, deque
from dataclasses import dataclass

import numpy as np
import rerun as rr

from . import cameras as cams
from .contour import Contour, decode_silhouette
from .parts import Joined, PartJoiner

TIMELINE = "frame"

# body_frame_t.joint_mm's order (proto/msg/body_frame_t.lcm) and each joint's H-Anim parent.
JOINTS = ["HumanoidRoot", "vl5", "vt10", "vc7", "skullbase", "l_sternoclavicular",
          "r_sternoclavicular", "l_shoulder", "r_shoulder", "l_elbow", "r_elbow", "l_wrist",
          "r_wrist", "l_hip", "r_hip", "l_knee", "r_knee", "l_ankle", "r_ankle"]
PARENT = {"vl5": "HumanoidRoot", "vt10": "vl5", "vc7": "vt10", "skullbase": "vc7",
          "l_sternoclavicular": "vc7", "r_sternoclavicular": "vc7",
          "l_shoulder": "l_sternoclavicular", "r_shoulder": "r_sternoclavicular",
          "l_elbow": "l_shoulder", "r_elbow": "r_shoulder", "l_wrist": "l_elbow",
          "r_wrist": "r_elbow", "l_hip": "HumanoidRoot", "r_hip": "HumanoidRoot",
          "l_knee": "l_hip", "r_knee": "r_hip", "l_ankle": "l_knee", "r_ankle": "r_knee"}

SYNCAP_CHANNEL = re.compile(r"SYNCAP_[A-Z_]+(\d\d)?")
MARKER_RADIUS_MM = 12.0
JOINT_RADIUS_MM = 25.0
RIGID_AXES_MM = 150.0
GREEN, ORANGE, GREY, RED = (60, 200, 90), (255, 150, 40), (150, 150, 150), (230, 60, 50)


def _constant_name(cls, value: int, exclude=()) -> str:
    """The name of a message type's constant with this value (edge_command_t.START), from the
    generated class, so that a new code needs no change here."""
    for name in dir(cls):
        if name.isupper() and name not in exclude and getattr(cls, name) == value:
            return name
    return f"code {value}"


def _finite(*values) -> bool:
    """JSON lines write a number that is not finite as null."""
    return all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values)


def _entity_name(name: str) -> str:
    """A rigid set's name as one entity path part."""
    return re.sub(r"[^A-Za-z0-9_.-]", "_", str(name)) or "_"


class StopInput(Exception):
    """--max-frames reached."""


@dataclass
class Skip:
    where: str     # the input and the place: "lcmlog:F event 12" or "udpm://... message 3"
    channel: str
    reason: str


class ViewLogger:
    def __init__(self, types: dict, cameras: list | None = None, trail_frames: int = 30,
                 max_frames: int | None = None, image_plane_mm: float | None = None,
                 quiet: bool = False):
        self.types = types
        self.cameras = {c.id: c for c in cameras or []}
        self.trail_frames = trail_frames
        self.max_frames = max_frames
        self.quiet = quiet
        self.joiner = PartJoiner()
        self.frames: set[int] = set()
        self.last_frame: int | None = None
        self.messages = Counter()          # logged messages by type
        self.skipped: list[Skip] = []
        self.input_errors: list[str] = []  # the input's own framing (an LCM log cut short)
        self.ignored = 0                   # messages on other applications' channels
        self.incomplete = Counter()        # joined frames missing parts, by kind
        self.trails: dict[int, deque] = {}
        self.sensor_logged: set[int] = set()
        self.last_trigger_ns: int | None = None
        self._where, self._channel = "", ""
        self._handlers = {
            "blob_frame_t": self.on_blob_part, "silhouette_part_t": self.on_silhouette_part,
            "marker_frame_t": self.on_marker_part, "hull_frame_t": self.on_hull,
            "body_frame_t": self.on_body, "camera_status_t": self.on_camera_status,
            "trigger_t": self.on_trigger, "trigger_status_t": self.on_trigger_status,
            "clip_polygon_t": self.on_clip, "edge_command_t": self.on_command,
        }
        self._log_static(image_plane_mm)

    # --- the scene that does not change ---

    def _log_static(self, image_plane_mm):
        rr.log("world", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
        for cam in self.cameras.values():
            transform, pinhole = cams.archetypes(cam, image_plane_mm)
            rr.log(f"world/cameras/{cam.id:02d}", transform, pinhole, static=True)

    def camera_path(self, camera: int) -> str:
        """Under its pinhole when calibrated (drawn in 3D too), else in its own 2D space."""
        return f"world/cameras/{camera:02d}" if camera in self.cameras else f"cameras/{camera:02d}"

    # --- input ---

    def handle(self, channel: str, data: bytes, where: str) -> None:
        """Decodes and logs one message; a bad one is counted and reported, never fatal.
        Raises StopInput once --max-frames frames were logged."""
        self._where, self._channel = where, channel
        cls = self.types.get(bytes(data[:8]))
        if cls is None:
            if SYNCAP_CHANNEL.fullmatch(channel):
                self.skip(where, channel, f"unknown message type (fingerprint {bytes(data[:8]).hex()}"
                          ", or not a syncap message): the .lcm files differ from the sender's?")
            else:
                self.ignored += 1
            return
        try:
            buf = io.BytesIO(data)
            msg = cls.decode(buf)
            if buf.tell() != len(data):
                raise ValueError(f"{len(data) - buf.tell()} bytes left after the message")
        except Exception as e:  # lcm's decoders raise struct.error, ValueError, ...
            self.skip(where, channel, f"{cls.__name__} does not decode: {e or type(e).__name__}")
            return
        handler = self._handlers.get(cls.__name__)
        if handler is None:
            self.skip(where, channel, f"{cls.__name__} is not a message sent on a channel")
            return
        try:
            handler(msg)
            self.messages[cls.__name__] += 1
        except StopInput:
            raise
        except Exception as e:
            self.skip(where, channel, f"{cls.__name__}: {e}")

    def tick(self) -> None:
        """Live, now and then: log the frames whose missing parts waited too long."""
        self._where, self._channel = "live", "(parts that waited too long)"
        self._log_all(self.joiner.expired())

    def finish(self) -> None:
        """The input ended: log what still waits for parts."""
        self._where, self._channel = "end of input", "(parts still waiting)"
        try:
            self._log_all(self.joiner.flush())
        except StopInput:
            pass

    def skip(self, where: str, channel: str, reason: str) -> None:
        self.skipped.append(Skip(where, channel, reason))
        if not self.quiet and len(self.skipped) <= 20:
            print(f"syncap view: {where} channel {channel}: {reason}; skipped", file=sys.stderr)
        self._at(self.last_frame)
        rr.log("log/skipped", rr.TextLog(f"{where} {channel}: {reason}", level=rr.TextLogLevel.WARN))

    def input_error(self, what: str) -> None:
        """A fault of the input itself, not of one message: a log cut short or with bytes that
        are not events (sources.log_events)."""
        self.input_errors.append(what)
        self._at(self.last_frame)
        rr.log("log/input", rr.TextLog(what, level=rr.TextLogLevel.WARN))

    # --- time ---

    def _frame(self, frame: int) -> None:
        """Sets the timeline to `frame`, counting it; --max-frames ends the input before a frame
        beyond the limit is logged."""
        if frame not in self.frames:
            if self.max_frames is not None and len(self.frames) >= self.max_frames:
                raise StopInput()
            self.frames.add(frame)
        self.last_frame = frame if self.last_frame is None else max(self.last_frame, frame)
        rr.set_time(TIMELINE, sequence=frame)

    def _at(self, frame: int | None) -> None:
        """The timeline for messages without a frame of their own: the latest frame seen."""
        if frame is None:
            rr.reset_time()
        else:
            rr.set_time(TIMELINE, sequence=frame)

    # --- parts ---

    def on_blob_part(self, m):
        self._log_all(self.joiner.add("blobs", m.camera_id, m.frame_number, m.part_index,
                                      m.part_count, m))

    def on_silhouette_part(self, m):
        self._log_all(self.joiner.add("silhouette", m.camera_id, m.frame_number, m.part_index,
                                      m.part_count, m))

    def on_marker_part(self, m):
        self._log_all(self.joiner.add("markers", None, m.frame_number, m.part_index,
                                      m.part_count, m))

    def _log_all(self, joined: list[Joined]):
        """Logs each joined frame; one that fails (a contour that does not decode) is skipped,
        named by the message that completed it, and the others are still logged."""
        for j in joined:
            try:
                self._log_joined(j)
            except StopInput:
                raise
            except Exception as e:
                self.skip(self._where, self._channel,
                          f"{j.kind} camera {j.camera} frame {j.frame}: {e}")

    def _log_joined(self, j: Joined):
        if not j.complete:
            self.incomplete[j.kind] += 1
        {"blobs": self.log_blobs, "silhouette": self.log_silhouette,
         "markers": self.log_markers}[j.kind](j)

    # --- per camera ---

    def _sensor_outline(self, camera: int, width: int, height: int):
        """An uncalibrated camera's image rectangle, so that its 2D view has the sensor's size."""
        if camera in self.cameras or camera in self.sensor_logged or width <= 0 or height <= 0:
            return
        self.sensor_logged.add(camera)
        rr.log(f"cameras/{camera:02d}/sensor",
               rr.Boxes2D(mins=[0, 0], sizes=[width, height], colors=[GREY]), static=True)

    def log_blobs(self, j: Joined):
        first = j.parts[0]
        blobs = [b for p in j.parts for b in p.blobs]
        self.blobs(j.camera, j.frame, [(b.x, b.y, b.area) for b in blobs],
                   max(p.processing_us for p in j.parts), first.image_width, first.image_height)

    def blobs(self, camera: int, frame: int, blobs: list, processing_us: float,
              width: int = 0, height: int = 0):
        """One camera's blobs of a frame, each (x, y, area) in syncap's pixels."""
        self._frame(frame)
        self._sensor_outline(camera, width, height)
        path = self.camera_path(camera)
        if blobs:
            xy = np.array([(x, y) for x, y, _ in blobs], dtype=np.float32) + cams.PIXEL_OFFSET
            radii = np.sqrt(np.maximum([a for _, _, a in blobs], 1.0) / np.pi).astype(np.float32)
            rr.log(f"{path}/blobs", rr.Points2D(xy, radii=radii, colors=[ORANGE]))
        else:
            rr.log(f"{path}/blobs", rr.Points2D(np.zeros((0, 2), dtype=np.float32)))
        plots = f"plots/cameras/{camera:02d}"
        rr.log(f"{plots}/blobs", rr.Scalars(len(blobs)))
        rr.log(f"{plots}/frame_processing_us", rr.Scalars(processing_us))

    def log_silhouette(self, j: Joined):
        first = j.parts[0]
        self.silhouette(j.camera, j.frame, decode_silhouette(j.parts),
                        first.image_width, first.image_height)

    def silhouette(self, camera: int, frame: int, contours: list, width: int = 0,
                   height: int = 0):
        """One camera's outline of a frame: closed polygons (green, holes orange), pieces of
        polygons that lost a part open and grey."""
        self._frame(frame)
        self._sensor_outline(camera, width, height)
        strips, colors = [], []
        for c in contours:
            if not c.points:
                continue
            pts = np.array(c.points, dtype=np.float32) + cams.PIXEL_OFFSET
            if c.complete:  # a polygon: close it
                pts = np.vstack([pts, pts[:1]])
            strips.append(pts)
            colors.append(GREY if not c.complete else (ORANGE if c.hole else GREEN))
        rr.log(f"{self.camera_path(camera)}/silhouette",
               rr.LineStrips2D(strips, colors=colors if colors else None))

    def on_camera_status(self, m):
        self._at(m.last_frame_number if m.last_frame_number >= 0 else self.last_frame)
        plots = f"plots/cameras/{m.camera_id:02d}"
        rr.log(f"{plots}/fps", rr.Scalars(m.frame_rate_hz))
        rr.log(f"{plots}/frames_lost", rr.Scalars(m.frames_lost))
        rr.log(f"{plots}/frames_incomplete", rr.Scalars(m.frames_incomplete))
        rr.log(f"{plots}/processing_us", rr.Scalars(m.processing_us_mean))
        if m.message:
            level = rr.TextLogLevel.ERROR if m.state == 2 else rr.TextLogLevel.INFO
            rr.log(f"log/cameras/{m.camera_id:02d}", rr.TextLog(m.message, level=level))

    # clip_polygon_t's region kinds (REGION_CLIP, REGION_FLOOR, REGION_SEARCH) as entity names.
    REGION_NAMES = {0: "clip", 1: "floor", 2: "search"}

    def on_clip(self, m):
        """The latest region of each kind a camera was sent (clip, floor, search), in its image."""
        self._at(self.last_frame)
        pts = np.stack([np.asarray(m.x, dtype=np.float32), np.asarray(m.y, dtype=np.float32)], 1)
        strips = [np.vstack([pts, pts[:1]]) + cams.PIXEL_OFFSET] if len(pts) else []
        name = self.REGION_NAMES.get(getattr(m, "region", 0), "clip")
        rr.log(f"{self.camera_path(m.camera_id)}/{name}", rr.LineStrips2D(strips, colors=[RED]))

    def on_command(self, m):
        self._at(self.last_frame)
        target = "all cameras" if m.camera_id == m.ALL_CAMERAS else f"camera {m.camera_id}"
        rr.log("log/commands", rr.TextLog(
            f"{_constant_name(type(m), m.command, ('ALL_CAMERAS',))} to {target}: int "
            f"{m.int_value} real {m.real_value} (sender {m.sender:x} sequence {m.sequence})"))

    # --- the trigger ---

    def on_trigger(self, m):
        self._frame(m.frame_number)
        if self.last_trigger_ns is not None and m.monotonic_ns > self.last_trigger_ns:
            rr.log("plots/trigger/interval_ms", rr.Scalars((m.monotonic_ns - self.last_trigger_ns) / 1e6))
        self.last_trigger_ns = m.monotonic_ns

    def on_trigger_status(self, m):
        self._at(m.last_frame_number if m.last_frame_number >= 0 else self.last_frame)
        rr.log("plots/trigger/late", rr.Scalars(m.late))
        rr.log("plots/trigger/missed", rr.Scalars(m.missed))
        if m.message:
            rr.log("log/trigger", rr.TextLog(m.message))

    # --- 3D ---

    def log_markers(self, j: Joined):
        markers = [mk for p in j.parts for mk in p.markers]
        self.markers(j.frame, [mk.id for mk in markers],
                     [(mk.x, mk.y, mk.z) for mk in markers],
                     [bool(mk.flags & 2) for mk in markers],  # marker_t.FLAG_PREDICTED
                     j.parts[0].host_us)

    def markers(self, frame: int, ids: list, positions: list, predicted: list,
                host_us: float | None):
        """A frame's 3D markers [mm] with their trajectory ids (-1: untracked); predicted ones
        (not seen this frame) grey."""
        self._frame(frame)
        pos = np.array(positions, dtype=np.float32).reshape(-1, 3)
        rr.log("world/markers", rr.Points3D(
            pos, radii=MARKER_RADIUS_MM, class_ids=[max(i, 0) for i in ids],
            labels=[str(i) if i >= 0 else "" for i in ids],
            colors=[GREY if p else (255, 255, 255) for p in predicted] if any(predicted) else None))
        self._log_trails(frame, ids, pos)
        rr.log("plots/markers/count", rr.Scalars(len(ids)))
        if host_us is not None:
            rr.log("plots/markers/host_ms", rr.Scalars(host_us / 1000.0))

    def _log_trails(self, frame: int, ids: list[int], pos: np.ndarray):
        """Each tracked marker's positions over the last `trail_frames` frames."""
        if self.trail_frames <= 0:
            return
        for i, p in zip(ids, pos):
            if i >= 0:
                self.trails.setdefault(i, deque()).append((frame, p))
        for i in list(self.trails):
            trail = self.trails[i]
            while trail and trail[0][0] <= frame - self.trail_frames:
                trail.popleft()
            if not trail:
                del self.trails[i]
        keep = [(i, t) for i, t in self.trails.items() if len(t) >= 2]
        rr.log("world/markers/trails", rr.LineStrips3D(
            [np.array([p for _, p in t]) for _, t in keep], class_ids=[i for i, _ in keep]))

    def on_hull(self, m):
        self.hull(m.frame_number, bool(m.flags & 4) or m.volume_mm3 <= 0,  # FLAG_FAILED
                  m.min_mm, m.max_mm, {
                      "volume_l": m.volume_mm3 / 1e6, "area_m2": m.area_mm2 / 1e6,
                      "vertices": m.vertices, "faces": m.faces, "cameras": m.cameras,
                      "hull_ms": m.hull_us / 1000.0, "host_ms": m.host_us / 1000.0})

    def hull(self, frame: int, failed: bool, lo, hi, numbers: dict):
        """The hull's bounding box [mm] (cleared when no hull was built) and its numbers."""
        self._frame(frame)
        if failed:
            rr.log("world/hull/bbox", rr.Clear(recursive=False))
        else:
            lo, hi = np.array(lo, dtype=np.float64), np.array(hi, dtype=np.float64)
            rr.log("world/hull/bbox", rr.Boxes3D(
                mins=[lo], sizes=[hi - lo], colors=[GREEN],
                labels=[f"hull {numbers.get('volume_l', 0):.1f} l"]))
        for name, value in numbers.items():
            if value is not None:
                rr.log(f"plots/hull/{name}", rr.Scalars(value))

    def on_body(self, m):
        no_fit = bool(m.flags & (8 | 16))  # FLAG_NO_HULL, FLAG_NO_START: nothing fitted
        numbers = {"rms_mm": m.rms_mm, "fit_ms": m.fit_us / 1000.0, "points_kept": m.points_kept}
        # sigma0 exists only where the .lcm files define it (added on main late 2026-11).
        if getattr(m, "sigma0", None) is not None:
            numbers["sigma0"] = m.sigma0
        self.body(m.frame_number, None if no_fit else dict(zip(JOINTS, m.joint_mm)), numbers)

    def body(self, frame: int, joints: dict | None, numbers: dict):
        """The fitted skeleton: joint centres [mm] by H-Anim name, bones to their parents;
        None clears it (no fit on this frame)."""
        self._frame(frame)
        if not joints:
            rr.log("world/body", rr.Clear(recursive=True))
        else:
            names = [n for n in JOINTS if n in joints] + [n for n in joints if n not in JOINTS]
            pos = np.array([joints[n] for n in names], dtype=np.float32).reshape(-1, 3)
            rr.log("world/body/joints", rr.Points3D(pos, radii=JOINT_RADIUS_MM, labels=names,
                                                    colors=[RED]))
            bones = [np.array([joints[PARENT[n]], joints[n]], dtype=np.float32)
                     for n in JOINTS if n in joints and PARENT.get(n) in joints]
            rr.log("world/body/bones", rr.LineStrips3D(bones, colors=[RED]))
        for name, value in numbers.items():
            if value is not None:
                rr.log(f"plots/body/{name}", rr.Scalars(value))

    def rigid_sets(self, frame: int, sets: list):
        """Rigid marker sets' poses (JSON lines only: marker_frame_t does not carry them): axes
        at world/rigid/<name>, world = R * set + t; cleared when the set was not found."""
        self._frame(frame)
        for s in sets:
            path = f"world/rigid/{_entity_name(s.get('name', '?'))}"
            if s.get("found") and s.get("rotation") and s.get("translation"):
                rr.log(path, rr.Transform3D(
                    translation=s["translation"],
                    mat3x3=np.array(s["rotation"], dtype=np.float64).reshape(3, 3)),
                       rr.TransformAxes3D(RIGID_AXES_MM))
                rr.log(f"plots/rigid/{_entity_name(s.get('name', '?'))}/rms_mm",
                       rr.Scalars(s.get("rms_mm") or 0.0))
            else:
                rr.log(path, rr.Clear(recursive=False))

    # --- the host's JSON lines (syncap-host --out, host/src/io/frame_json.hpp) ---

    def handle_group(self, line: str, where: str) -> None:
        """Logs one frame group's line; a line that does not read is counted and reported."""
        self._where, self._channel = where, "(JSON line)"
        try:
            group = json.loads(line)
            if not isinstance(group, dict) or not isinstance(group.get("frame"), int):
                raise ValueError('not an object with an integer "frame"')
            self._group(group)
            self.messages["frame group"] += 1
        except StopInput:
            raise
        except Exception as e:
            self.skip(where, "(JSON line)", f"does not read: {e}")

    def _group(self, g: dict) -> None:
        frame = g["frame"]
        self._frame(frame)
        for cid, rec in (g.get("cameras") or {}).items():
            camera = int(cid)
            if rec.get("blobs") is not None:
                self.blobs(camera, frame, [(b["x"], b["y"], b.get("area") or 1.0)
                                           for b in rec["blobs"] if _finite(b.get("x"), b.get("y"))],
                           rec.get("processing_us") or 0)
            sil = rec.get("silhouette")
            if sil is not None:
                contours = [Contour(bool(c.get("hole")), bool(c.get("complete", True)),
                                    [tuple(p) for p in c.get("points", [])])
                            for c in sil.get("contours", [])]
                self.silhouette(camera, frame, contours, sil.get("width", 0), sil.get("height", 0))
        if "markers" in g:
            ms = [m for m in g["markers"] if _finite(m.get("x"), m.get("y"), m.get("z"))]
            self.markers(frame, [m.get("id", -1) for m in ms], [(m["x"], m["y"], m["z"]) for m in ms],
                         [bool(m.get("predicted")) for m in ms], None)
        if "rigid_sets" in g:
            self.rigid_sets(frame, g["rigid_sets"])
        h = g.get("hull")
        if h is not None:
            failed = bool((h.get("flags") or 0) & 4) or "error" in h or not h.get("volume_mm3")
            self.hull(frame, failed, h.get("min"), h.get("max"), {
                "volume_l": (h.get("volume_mm3") or 0) / 1e6, "area_m2": (h.get("area_mm2") or 0) / 1e6,
                "vertices": h.get("vertices"), "faces": h.get("faces"), "cameras": h.get("cameras"),
                "hull_ms": (h.get("hull_us") or 0) / 1000.0})
        b = g.get("body")
        if b is not None:
            no_fit = bool((b.get("flags") or 0) & (8 | 16)) or not b.get("joints")
            joints = None if no_fit else {n: p for n, p in b["joints"].items() if _finite(*p)}
            self.body(frame, joints, {"rms_mm": b.get("rms_mm"), "fit_ms": (b.get("fit_us") or 0) / 1000.0,
                                      "points_kept": b.get("points_kept")})

    # --- the end ---

    def summary(self) -> str:
        lines = [f"{len(self.frames)} frames, {sum(self.messages.values())} messages logged"
                 + (f" ({', '.join(f'{n} {t}' for t, n in sorted(self.messages.items()))})"
                    if self.messages else "")]
        if len(self.frames) > 1:
            # Live, numbers missing between the first and the last were lost before the viewer
            # (the network, the socket's buffer); in a recording, before the recorder.
            lo, hi = min(self.frames), max(self.frames)
            missing = hi - lo + 1 - len(self.frames)
            lines.append(f"frame numbers {lo}..{hi}: {len(self.frames)} shown, {missing} missing")
        for kind, n in sorted(self.incomplete.items()):
            lines.append(f"{n} {kind} frames with parts missing (shown with what arrived)")
        lines += self.input_errors
        if self.ignored:
            lines.append(f"{self.ignored} messages of other applications ignored")
        if self.skipped:
            by_reason = defaultdict(list)
            for s in self.skipped:
                by_reason[s.reason].append(f"{s.where} {s.channel}")
            lines.append(f"{len(self.skipped)} messages skipped:")
            for reason, places in by_reason.items():
                more = f" and {len(places) - 3} more" if len(places) > 3 else ""
                lines.append(f"  {reason}: {'; '.join(places[:3])}{more}")
        return "\n".join(lines)
