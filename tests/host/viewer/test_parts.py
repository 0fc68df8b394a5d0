"""Joining split messages (host/viewer/syncap_view/parts.py): whole frames at once, a frame
that lost a part after its stream moved on, after a wait (live), or at the end."""

import unittest

import support  # noqa: F401  (sys.path)
from syncap_view.parts import PartJoiner


class Clock:
    def __init__(self):
        self.now = 0.0

    def __call__(self):
        return self.now


class PartJoinerTest(unittest.TestCase):
    def test_a_frame_is_handed_out_when_its_last_part_arrives(self):
        j = PartJoiner()
        self.assertEqual(j.add("blobs", 3, 10, 1, 3, "b"), [])
        self.assertEqual(j.add("blobs", 3, 10, 0, 3, "a"), [])
        self.assertEqual(j.add("blobs", 3, 10, 1, 3, "b2"), [])  # a duplicate replaces
        (whole,) = j.add("blobs", 3, 10, 2, 3, "c")
        self.assertEqual((whole.kind, whole.camera, whole.frame), ("blobs", 3, 10))
        self.assertEqual(whole.parts, ["a", "b2", "c"])
        self.assertTrue(whole.complete)
        self.assertEqual(j.flush(), [])

    def test_a_frame_that_lost_a_part_waits_two_frames_of_its_stream(self):
        j = PartJoiner(max_lag=2)
        j.add("blobs", 1, 10, 0, 2, "a")            # part 1 of frame 10 never comes
        self.assertEqual(len(j.add("blobs", 2, 12, 0, 1, "other camera")), 1)
        self.assertEqual(len(j.add("blobs", 1, 11, 0, 1, "x")), 1)  # frame 11 itself only
        out = j.add("blobs", 1, 12, 0, 1, "y")
        self.assertEqual([(o.frame, o.complete) for o in out], [(12, True), (10, False)])

    def test_live_a_frame_is_handed_out_after_max_wait(self):
        clock = Clock()
        j = PartJoiner(max_wait_s=1.0, clock=clock)
        j.add("silhouette", 0, 5, 0, 2, "a")
        clock.now = 0.5
        self.assertEqual(j.expired(), [])
        clock.now = 1.0
        (late,) = j.expired()
        self.assertEqual((late.frame, late.parts, late.complete), (5, ["a"], False))
        self.assertEqual(j.flush(), [])

    def test_the_end_hands_out_what_waits(self):
        j = PartJoiner()
        j.add("markers", None, 7, 1, 2, "b")
        (last,) = j.flush()
        self.assertEqual((last.frame, last.parts, last.part_count), (7, ["b"], 2))

    def test_impossible_part_numbers_are_errors(self):
        j = PartJoiner()
        for index, count in ((0, 0), (2, 2), (-1, 3)):
            with self.assertRaisesRegex(ValueError, f"part_index {index} of part_count {count}"):
                j.add("blobs", 0, 1, index, count, "x")


if __name__ == "__main__":
    unittest.main()
