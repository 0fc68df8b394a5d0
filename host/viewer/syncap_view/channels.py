"""The LCM channel names, read from the one table C and C++ take them from
(proto/include/syncap/proto/channels.h): `#define SYNCAP_CHANNEL_<NAME> "<channel>"` lines."""

import re
from pathlib import Path

# The source tree's table, found from this file: host/viewer/syncap_view/channels.py.
TABLE = Path(__file__).resolve().parents[3] / "proto" / "include" / "syncap" / "proto" / "channels.h"

_DEFINE = re.compile(r'^#define SYNCAP_CHANNEL_([A-Z_]+) "([A-Z0-9_]+)"$')


def read(table: Path = TABLE) -> dict[str, str]:
    """NAME -> channel (e.g. "TRIGGER" -> "SYNCAP_TRIGGER", "BLOBS_PREFIX" -> "SYNCAP_BLOBS_")."""
    names = {}
    for line in table.read_text().splitlines():
        m = _DEFINE.match(line.strip())
        if m:
            names[m.group(1)] = m.group(2)
    if not names:
        raise RuntimeError(f"{table}: no '#define SYNCAP_CHANNEL_<NAME> \"...\"' line")
    return names


CHANNELS = read()


def camera_channel(prefix_name: str, camera_id: int) -> str:
    """The per-camera channel of a prefix: camera_channel("BLOBS_PREFIX", 3) == "SYNCAP_BLOBS_03"."""
    if not 0 <= camera_id <= 99:
        raise ValueError(f"camera id {camera_id}: not 0..99")
    return f"{CHANNELS[prefix_name]}{camera_id:02d}"
