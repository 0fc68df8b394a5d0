"""The contour codec of silhouette_part_t.data, decoded (proto/include/syncap/proto/contour_codec.hpp).

A part's data is a sequence of pieces. Each piece is a varint header
(point_count << 2) | (continues << 1) | hole, the first point as two zigzag varints (absolute
pixels), then each step to the next point as two zigzag varints. Varints are little-endian
base-128 (7 bits a byte, high bit: more follow), at most 5 bytes. A piece with `continues` set
extends the polygon of the piece before it, possibly in the previous part. This mirrors
proto/src/contour_codec.cpp's decoder, including which contours it marks incomplete.
"""

from __future__ import annotations

from dataclasses import dataclass, field

HOLE_BIT = 1
CONTINUES_BIT = 2
MAX_VARINT_BYTES = 5
INT16_MIN, INT16_MAX = -32768, 32767


class ContourDecodeError(ValueError):
    """Data that does not decode; the message names camera, frame, part and byte offset."""


@dataclass
class Contour:
    hole: bool = False
    complete: bool = True  # False when a part holding some of its points was lost
    points: list[tuple[int, int]] = field(default_factory=list)


def _unzigzag(u: int) -> int:
    return (u >> 1) ^ -(u & 1)


class _Reader:
    def __init__(self, part):
        self.part = part
        self.data = bytes(part.data)
        self.pos = 0

    def fail(self, what: str):
        p = self.part
        raise ContourDecodeError(f"silhouette camera {p.camera_id} frame {p.frame_number} part "
                                 f"{p.part_index}/{p.part_count} byte {self.pos}: {what}")

    def varint(self) -> int:
        value = 0
        for i in range(MAX_VARINT_BYTES):
            if self.pos >= len(self.data):
                self.fail("data ends inside a varint")
            byte = self.data[self.pos]
            self.pos += 1
            value |= (byte & 0x7F) << (7 * i)
            if not byte & 0x80:
                return value & 0xFFFFFFFF  # the C++ reads into uint32
        self.fail("varint longer than 5 bytes")


def decode_part(part, previous_part_present: bool, contours: list[Contour]) -> None:
    """Appends the contours of one part to `contours` (extending the last one on `continues`)."""
    reader = _Reader(part)
    if part.data_size != len(reader.data) or part.data_size < 0:
        reader.fail("data_size does not match the data")
    for piece in range(part.num_pieces):
        header = reader.varint()
        count = header >> 2
        if count > len(reader.data):
            reader.fail(f"piece claims {count} points")
        continues = bool(header & CONTINUES_BIT)
        # A continuation extends the last contour only when the part before it arrived.
        if piece == 0:
            extend = continues and previous_part_present and bool(contours)
        else:
            extend = continues and bool(contours)
        if not extend:
            contours.append(Contour(hole=bool(header & HOLE_BIT), complete=not continues))
        contour = contours[-1]
        x = y = 0
        for i in range(count):
            dx = _unzigzag(reader.varint())
            dy = _unzigzag(reader.varint())
            x, y = (dx, dy) if i == 0 else (x + dx, y + dy)
            if not (INT16_MIN <= x <= INT16_MAX and INT16_MIN <= y <= INT16_MAX):
                reader.fail("point outside the coordinate range int16")
            contour.points.append((x, y))
    if reader.pos != len(reader.data):
        reader.fail("bytes left after the last piece")


def decode_silhouette(parts) -> list[Contour]:
    """The contours of one frame's parts (any order, some possibly missing)."""
    contours: list[Contour] = []
    if not parts:
        return contours
    parts = sorted(parts, key=lambda p: p.part_index)
    expected = 0
    for part in parts:
        previous_present = part.part_index == expected
        if not previous_present and contours:
            contours[-1].complete = False
        decode_part(part, previous_present, contours)
        expected = part.part_index + 1
    if expected != parts[0].part_count and contours:
        contours[-1].complete = False
    return contours


def _put_varint(out: bytearray, v: int) -> None:
    while v >= 0x80:
        out.append((v & 0x7F) | 0x80)
        v >>= 7
    out.append(v)


def _zigzag(v: int) -> int:
    return ((v << 1) ^ (v >> 31)) & 0xFFFFFFFF


def encode_pieces(pieces) -> bytes:
    """The data of one part holding `pieces`, each (points, hole, continues). For tests and the
    benchmark's generated logs; the edge's encoder (proto/src/contour_codec.cpp) also splits
    polygons over parts."""
    out = bytearray()
    for points, hole, continues in pieces:
        _put_varint(out, (len(points) << 2) | (CONTINUES_BIT if continues else 0) |
                    (HOLE_BIT if hole else 0))
        prev = None
        for x, y in points:
            step = (x, y) if prev is None else (x - prev[0], y - prev[1])
            _put_varint(out, _zigzag(step[0]))
            _put_varint(out, _zigzag(step[1]))
            prev = (x, y)
    return bytes(out)
