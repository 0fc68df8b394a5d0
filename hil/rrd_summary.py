#!/usr/bin/env python3
"""rrd_summary.py FILE.rrd [ENTITY...]: reads a Rerun recording back with Rerun's own reader
(rerun.chunk.RrdReader) and prints "rrd: N frames, M entities"; exits 1, naming them, when an
ENTITY given is not in it. hil/run checks each run's view.rrd with it (docs/guide/view.md)."""

import sys

from rerun.chunk import RrdReader


def main() -> int:
    if len(sys.argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    frames, entities = set(), set()
    for chunk in RrdReader(sys.argv[1]).stream().to_chunks():
        entities.add(chunk.entity_path)
        batch = chunk.to_record_batch()
        if "frame" in batch.schema.names:
            frames.update(v for v in batch.column("frame").to_pylist() if v is not None)
    missing = [e for e in sys.argv[2:] if e not in entities]
    print(f"rrd: {len(frames)} frames, {len(entities)} entities"
          + (f"; missing: {' '.join(missing)}" if missing else ""))
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
