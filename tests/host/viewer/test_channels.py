"""The channel names Python reads from proto's one table (syncap_view.channels) are the ones the
C++ side publishes on (checked here against the names the host and edges use)."""

import unittest

import support  # noqa: F401  (sys.path)
from syncap_view import channels


class ChannelTableTest(unittest.TestCase):
    def test_every_channel_of_the_contract_is_read(self):
        c = channels.CHANNELS
        self.assertEqual(c["TRIGGER"], "SYNCAP_TRIGGER")
        self.assertEqual(c["TRIGGER_STATUS"], "SYNCAP_TRIGGER_STATUS")
        self.assertEqual(c["EDGE_COMMAND"], "SYNCAP_EDGE_CMD")
        self.assertEqual(c["EDGE_CLIP"], "SYNCAP_EDGE_CLIP")
        self.assertEqual(c["MARKERS"], "SYNCAP_MARKERS")
        self.assertEqual(c["HULL"], "SYNCAP_HULL")
        self.assertEqual(c["BODY"], "SYNCAP_BODY")
        self.assertEqual(len(c), 11)

    def test_per_camera_channels_carry_two_digits(self):
        self.assertEqual(channels.camera_channel("BLOBS_PREFIX", 3), "SYNCAP_BLOBS_03")
        self.assertEqual(channels.camera_channel("SILHOUETTE_PREFIX", 12), "SYNCAP_SIL_12")
        with self.assertRaises(ValueError):
            channels.camera_channel("STATUS_PREFIX", 100)


if __name__ == "__main__":
    unittest.main()
