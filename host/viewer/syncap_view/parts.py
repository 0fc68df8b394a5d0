"""Joining messages sent in parts: blob frames and silhouettes per camera, marker frames.

Every part decodes on its own (proto/src/blob_parts.cpp, marker_parts.cpp, contour_codec.cpp),
but Rerun keeps only the last value an entity got at a frame, so a frame's parts are gathered
before they are logged. A frame is handed out when all its parts arrived, or incomplete once its
stream (kind and camera) has moved `max_lag` frames past it, or live when it waited `max_wait_s`
(a camera that stopped sending), or at the end of the input: a lost part costs only its own
content, as in the host.
"""

from __future__ import annotations

import time
from dataclasses import dataclass


@dataclass
class Joined:
    kind: str          # "blobs", "silhouette", "markers"
    camera: int | None
    frame: int
    parts: list        # the messages, sorted by part_index
    part_count: int

    @property
    def complete(self) -> bool:
        return len(self.parts) == self.part_count


class PartJoiner:
    def __init__(self, max_lag: int = 2, max_wait_s: float = 1.0, clock=time.monotonic):
        self.max_lag = max_lag
        self.max_wait_s = max_wait_s
        self.clock = clock
        # (kind, camera) -> frame -> (part_count, {part_index: message}, first arrival)
        self._pending: dict[tuple, dict[int, tuple[int, dict, float]]] = {}

    def add(self, kind: str, camera: int | None, frame: int, part_index: int, part_count: int,
            message) -> list[Joined]:
        if part_count < 1 or not 0 <= part_index < part_count:
            raise ValueError(f"part_index {part_index} of part_count {part_count}")
        stream = self._pending.setdefault((kind, camera), {})
        count, parts, _ = stream.setdefault(frame, (part_count, {}, self.clock()))
        parts[part_index] = message  # a duplicate replaces its twin
        out = []
        if len(parts) >= count:
            del stream[frame]
            out.append(self._joined(kind, camera, frame, count, parts))
        for old in sorted(f for f in stream if f <= frame - self.max_lag):
            old_count, old_parts, _ = stream.pop(old)
            out.append(self._joined(kind, camera, old, old_count, old_parts))
        return out

    def expired(self) -> list[Joined]:
        """Frames that waited longer than max_wait_s for a part (live: its sender went quiet)."""
        limit = self.clock() - self.max_wait_s
        out = []
        for (kind, camera), stream in self._pending.items():
            for frame in sorted(f for f, (_, _, since) in stream.items() if since <= limit):
                count, parts, _ = stream.pop(frame)
                out.append(self._joined(kind, camera, frame, count, parts))
        return out

    def flush(self) -> list[Joined]:
        """Everything still waiting, incomplete: the input ended."""
        out = []
        for (kind, camera), stream in self._pending.items():
            for frame in sorted(stream):
                count, parts, _ = stream[frame]
                out.append(self._joined(kind, camera, frame, count, parts))
        self._pending.clear()
        return out

    @staticmethod
    def _joined(kind, camera, frame, count, parts: dict) -> Joined:
        return Joined(kind, camera, frame, [parts[i] for i in sorted(parts)], count)
