"""The contour decoder against hand-made data (the codec: proto/include/syncap/proto/contour_codec.hpp)."""

import unittest
from types import SimpleNamespace

import support  # noqa: F401  (sys.path)
from syncap_view.contour import ContourDecodeError, decode_silhouette, encode_pieces


def part(data: bytes, pieces: int, index=0, count=1, camera=4, frame=17):
    return SimpleNamespace(camera_id=camera, frame_number=frame, part_index=index,
                           part_count=count, num_pieces=pieces, data_size=len(data), data=data)


# A unit square from (10, 20), traced right, down, left: header (4 << 2) = 0x10, the first point
# as zigzag(10) = 0x14, zigzag(20) = 0x28, then steps (1, 0) (0, 1) (-1, 0) as 02 00, 00 02, 01 00.
SQUARE = bytes([0x10, 0x14, 0x28, 0x02, 0x00, 0x00, 0x02, 0x01, 0x00])
# A hole of two points from (100, -3): header (2 << 2) | hole = 0x09, zigzag(100) = 200 as the
# two-byte varint C8 01, zigzag(-3) = 5; step (-70, 64): zigzag 139 = 8B 01, 128 = 80 01.
HOLE = bytes([0x09, 0xC8, 0x01, 0x05, 0x8B, 0x01, 0x80, 0x01])


class ContourDecoderTest(unittest.TestCase):
    def test_hand_made_square_and_hole(self):
        contours = decode_silhouette([part(SQUARE + HOLE, 2)])
        self.assertEqual(len(contours), 2)
        self.assertEqual(contours[0].points, [(10, 20), (11, 20), (11, 21), (10, 21)])
        self.assertFalse(contours[0].hole)
        self.assertTrue(contours[0].complete)
        self.assertEqual(contours[1].points, [(100, -3), (30, 61)])
        self.assertTrue(contours[1].hole)

    def test_encoder_gives_the_hand_made_bytes(self):
        self.assertEqual(encode_pieces([([(10, 20), (11, 20), (11, 21), (10, 21)], False, False)]),
                         SQUARE)
        self.assertEqual(encode_pieces([([(100, -3), (30, 61)], True, False)]), HOLE)

    def test_a_polygon_continues_in_the_next_part(self):
        first = encode_pieces([([(0, 0), (1, 0)], False, False)])
        second = encode_pieces([([(1, 1), (0, 1)], False, True)])
        parts = [part(second, 1, index=1, count=2), part(first, 1, index=0, count=2)]  # any order
        contours = decode_silhouette(parts)
        self.assertEqual(len(contours), 1)
        self.assertEqual(contours[0].points, [(0, 0), (1, 0), (1, 1), (0, 1)])
        self.assertTrue(contours[0].complete)

    def test_a_lost_part_marks_its_contours_incomplete(self):
        second = encode_pieces([([(1, 1), (0, 1)], False, True), ([(5, 5)], False, False)])
        contours = decode_silhouette([part(second, 2, index=1, count=2)])
        self.assertEqual([c.complete for c in contours], [False, True])
        first = encode_pieces([([(0, 0), (1, 0)], False, False)])
        contours = decode_silhouette([part(first, 1, index=0, count=2)])  # the rest lost
        self.assertFalse(contours[0].complete)

    def test_bad_data_names_camera_frame_part_and_byte(self):
        with self.assertRaisesRegex(ContourDecodeError,
                                    r"camera 4 frame 17 part 0/1 byte 9: data ends inside a varint"):
            decode_silhouette([part(SQUARE, 2)])  # claims a second piece
        with self.assertRaisesRegex(ContourDecodeError, "bytes left after the last piece"):
            decode_silhouette([part(SQUARE + b"\x00", 1)])
        with self.assertRaisesRegex(ContourDecodeError, "varint longer than 5 bytes"):
            decode_silhouette([part(b"\xff" * 6, 1)])
        with self.assertRaisesRegex(ContourDecodeError, "outside the coordinate range int16"):
            decode_silhouette([part(encode_pieces([([(32767, 0), (32768, 0)], False, False)]), 1)])

    def test_the_cpp_tests_int16_edges(self):
        """tests/proto/contour_codec_test.cpp, DecodedPointOutsideInt16IsAnError, byte for byte."""
        past_int16 = bytes([0x08, 0xFE, 0xFF, 0x03, 0x00, 0x02, 0x00])
        past_int32 = bytes([0x08, 0xFE, 0xFF, 0xFF, 0xFF, 0x0F, 0x00, 0x02, 0x00])
        at_the_edge = bytes([0x08, 0xFD, 0xFF, 0x03, 0x00, 0x01, 0x00])
        for data in (past_int16, past_int32):
            with self.assertRaises(ContourDecodeError):
                decode_silhouette([part(data, 1)])
        self.assertEqual(decode_silhouette([part(at_the_edge, 1)])[0].points[1], (-32768, 0))


if __name__ == "__main__":
    unittest.main()
