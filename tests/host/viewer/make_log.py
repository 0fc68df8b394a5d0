"""Writes the replay test's LCM log: 3 cameras over 10 frames, each message type the viewer
shows, blobs and markers in several parts, a silhouette over two parts, and one corrupt event.
Run as a program so that a test can make it with other .lcm definitions (--proto-msg) than the
ones it has loaded itself."""

import argparse

import support  # noqa: F401  (sys.path)
from syncap_view import bindings, synthetic

CORRUPT_FRAME = 5
FAILED_HULL_FRAME = 7


def write(path: str, cameras_json: str | None, proto_msg: str | None, frames: int = 10,
          cameras: int = 3) -> None:
    t = bindings.load(proto_msg)
    cams = synthetic.ring_cameras(cameras)
    if cameras_json:
        synthetic.write_cameras(cameras_json, cams)
    w = synthetic.LogWriter(path, t)
    for f in range(frames):
        w.trigger(f)
        markers = synthetic.marker_positions(f, 40)
        for cam in cams:
            pixels = [p for p in (synthetic.project(cam, x) for x in markers) if p]
            w.blobs(cam["id"], f, pixels, per_part=16)  # 40 blobs: 3 parts
        # camera 0's outline: a rectangle over two parts, the second continuing the first
        w.silhouette(0, f, [[([(200 + f, 100), (300, 100), (300, 400)], False, False)],
                            [([(200 + f, 400)], False, True),
                             ([(240, 200), (260, 200), (260, 220)], True, False)]])
        w.markers(f, markers, per_part=16)
        if f == FAILED_HULL_FRAME:
            w.hull(f, (0, 0, 0), (0, 0, 0), flags=4)  # hull_frame_t.FLAG_FAILED
        else:
            w.hull(f, (-400, -400, 0), (400, 400, 1800))
        w.body(f, offset_mm=(10.0 * f, 0.0, 0.0))
        w.status(f % cameras, f, message="warming up" if f == 0 else "")
        if f == 1:  # the host's clip polygon for camera 2 and a command to all cameras
            clip = t.clip_polygon_t()
            clip.camera_id, clip.image_width, clip.image_height = 2, 640, 480
            clip.x, clip.y, clip.num_points = [10, 600, 300], [400, 400, 50], 3
            clip.mac = [0] * 32
            w.write("SYNCAP_EDGE_CLIP", clip)
            cmd = t.edge_command_t()
            cmd.camera_id, cmd.command, cmd.int_value = -1, t.edge_command_t.TRAIN_BACKGROUND, 60
            cmd.mac = [0] * 32
            w.write("SYNCAP_EDGE_CMD", cmd)
        if f == CORRUPT_FRAME:  # a blob frame cut short: its fingerprint, then 2 of 40 bytes
            w.write("SYNCAP_BLOBS_01", t.blob_frame_t._get_packed_fingerprint() + b"\x00\x01")
    w.close()


if __name__ == "__main__":
    p = argparse.ArgumentParser()
    p.add_argument("out")
    p.add_argument("--cameras-json")
    p.add_argument("--proto-msg")
    p.add_argument("--frames", type=int, default=10)
    a = p.parse_args()
    write(a.out, a.cameras_json, a.proto_msg, a.frames)
