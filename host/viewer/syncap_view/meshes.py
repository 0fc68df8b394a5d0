"""The hull's meshes in the viewer (issue 19: "the hull mesh of each frame"): `hull_frame_t`
carries the hull's measures, not its surface, so the meshes come from the PLY files the host
writes (`syncap-host --hull-meshes DIR`, `syncap markers --hull`, the replay bench's RUN/hull/):
one `hull_<frame>.ply` a frame, ASCII PLY as CGAL writes it (vertices x y z, then triangles)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

HULL_FILE = re.compile(r"hull_(\d+)\.ply")


class MeshFileError(ValueError):
    """A mesh file that cannot be read; the message names the file and line."""


def hull_files(folder: str | Path) -> dict[int, Path]:
    """The folder's hull_<frame>.ply files by frame number."""
    folder = Path(folder)
    if not folder.is_dir():
        raise MeshFileError(f"{folder}: not a folder")
    return {int(m.group(1)): p for p in folder.iterdir() if (m := HULL_FILE.fullmatch(p.name))}


def read_ascii_ply(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """(vertices (n, 3) float32, triangles (m, 3) uint32) of an ASCII PLY of triangles."""
    path = Path(path)
    lines = path.read_text().splitlines()
    if not lines or lines[0].strip() != "ply":
        raise MeshFileError(f"{path}:1: not a PLY file")
    vertices = faces = None
    body = None
    for i, line in enumerate(lines[1:], start=2):
        words = line.split()
        if words[:2] == ["format", "binary_little_endian"] or words[:2] == [
                "format", "binary_big_endian"]:
            raise MeshFileError(f"{path}:{i}: binary PLY is not read (ASCII only)")
        if words[:2] == ["element", "vertex"]:
            vertices = int(words[2])
        elif words[:2] == ["element", "face"]:
            faces = int(words[2])
        elif words == ["end_header"]:
            body = i
            break
    if body is None or vertices is None or faces is None:
        raise MeshFileError(f"{path}: a header without vertex and face counts or end_header")
    try:
        v = np.loadtxt(lines[body:body + vertices], dtype=np.float32, ndmin=2)[:, :3]
        f = np.loadtxt(lines[body + vertices:body + vertices + faces], dtype=np.int64, ndmin=2)
    except ValueError as e:
        raise MeshFileError(f"{path}: {e}") from None
    if len(v) != vertices or len(f) != faces or (faces and (f[:, 0] != 3).any()):
        raise MeshFileError(f"{path}: expected {vertices} vertices and {faces} triangles")
    triangles = f[:, 1:4] if faces else np.zeros((0, 3), dtype=np.int64)
    if triangles.size and (triangles.min() < 0 or triangles.max() >= vertices):
        raise MeshFileError(f"{path}: a triangle names a vertex that is not there")
    return v, triangles.astype(np.uint32)


def log_hull_meshes(rr, folder: str | Path, timeline: str) -> tuple[int, list[str]]:
    """Logs every hull mesh of the folder at its frame on `timeline`; returns how many, and the
    files that could not be read (named, left out; the others are shown)."""
    shown, errors = 0, []
    for frame, path in sorted(hull_files(folder).items()):
        try:
            vertices, triangles = read_ascii_ply(path)
        except (MeshFileError, OSError) as e:
            errors.append(str(e))
            continue
        rr.set_time(timeline, sequence=frame)
        rr.log("world/hull/mesh", rr.Mesh3D(vertex_positions=vertices, triangle_indices=triangles,
                                             albedo_factor=[0.35, 0.75, 0.45, 0.5]))
        shown += 1
    rr.reset_time()
    return shown, errors
