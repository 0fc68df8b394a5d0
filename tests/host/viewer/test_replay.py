"""A recorded LCM log replayed into `syncap view --save`, the .rrd read back with Rerun's own
reader (rerun.chunk.RrdReader): which entities, how many frames on the frame timeline, what a
joined frame holds, and the corrupt event named and skipped."""

import collections
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import support
import make_log
from rerun.chunk import RrdReader

FRAMES = 10


def read_rrd(path):
    """entity path -> {frame: [rows' record batch columns as python]}, and the frame values."""
    entities = collections.defaultdict(lambda: collections.defaultdict(list))
    frames = set()
    for chunk in RrdReader(path).stream().to_chunks():
        batch = chunk.to_record_batch()
        # log_time (ns) does not convert to Python's datetime; the test needs only "frame"
        columns = {name: batch.column(name).to_pylist() for name in batch.schema.names
                   if name != "log_time"}
        values = columns.get("frame", [None] * batch.num_rows)
        frames.update(v for v in values if v is not None)
        for row in range(batch.num_rows):
            entities[chunk.entity_path][values[row]].append(
                {k: v[row] for k, v in columns.items()})
    return entities, frames


def run(*args, check=True):
    result = subprocess.run(support.program() + list(args), capture_output=True, text=True,
                            env=support.run_env(), timeout=120)
    if check and result.returncode != 0:
        raise AssertionError(f"syncap view {' '.join(args)} exited {result.returncode}:\n"
                             f"{result.stderr}")
    return result


class ReplayTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.TemporaryDirectory()
        d = Path(cls.dir.name)
        cls.log = str(d / "test.lcmlog")
        cls.cameras = str(d / "cameras.json")
        make_log.write(cls.log, cls.cameras, None, FRAMES)
        cls.rrd = str(d / "view.rrd")
        cls.result = run("--input", f"lcmlog:{cls.log}", "--cameras", cls.cameras,
                         "--save", cls.rrd)
        cls.entities, cls.frames = read_rrd(cls.rrd)

    @classmethod
    def tearDownClass(cls):
        cls.dir.cleanup()

    def test_every_part_of_the_scene_is_there(self):
        want = {"/world", "/world/markers", "/world/markers/trails", "/world/hull/bbox",
                "/world/body/joints", "/world/body/bones", "/world/cameras/00/silhouette",
                "/plots/body/rms_mm", "/plots/hull/volume_l", "/plots/markers/count",
                "/plots/trigger/interval_ms", "/log/skipped", "/log/cameras/00",
                "/world/cameras/02/clip", "/log/commands"}
        for cam in ("00", "01", "02"):
            want |= {f"/world/cameras/{cam}", f"/world/cameras/{cam}/blobs",
                     f"/plots/cameras/{cam}/fps", f"/plots/cameras/{cam}/frames_lost",
                     f"/plots/cameras/{cam}/processing_us", f"/plots/cameras/{cam}/blobs"}
        self.assertLessEqual(want, set(self.entities), self.result.stderr)
        self.assertFalse([e for e in self.entities if e.startswith("/cameras/")],
                         "calibrated cameras' content belongs under their pinholes")

    def test_frames_on_the_timeline(self):
        self.assertEqual(self.frames, set(range(FRAMES)))
        self.assertEqual(set(self.entities["/world/markers"]), set(range(FRAMES)))

    def test_parts_are_joined(self):
        """40 markers in 3 parts and 40 blobs in 3 parts per camera are one frame's entity."""
        rows = self.entities["/world/markers"][3]
        self.assertEqual(len(rows), 1)
        self.assertEqual(len(rows[0]["Points3D:positions"]), 40)
        self.assertEqual(sorted(rows[0]["Points3D:labels"]), sorted(str(i) for i in range(40)))
        for cam in ("00", "01", "02"):
            rows = self.entities[f"/world/cameras/{cam}/blobs"][3]
            self.assertEqual(len(rows[0]["Points2D:positions"]), 40, cam)
        strips = self.entities["/world/cameras/00/silhouette"][2][0]["LineStrips2D:strips"]
        self.assertEqual(len(strips), 2)  # the outline (joined over 2 parts) and the hole
        self.assertEqual([list(p) for p in strips[0]],
                         [[202.5, 100.5], [300.5, 100.5], [300.5, 400.5], [202.5, 400.5],
                          [202.5, 100.5]])

    def test_commands_are_named(self):
        row = self.entities["/log/commands"][1][0]
        self.assertTrue(row["TextLog:text"][0].startswith("TRAIN_BACKGROUND to all cameras: int 60"),
                        row)

    def test_body_has_nineteen_joints_and_eighteen_bones(self):
        row = self.entities["/world/body/joints"][0][0]
        self.assertEqual(len(row["Points3D:positions"]), 19)
        self.assertEqual(row["Points3D:labels"][0], "HumanoidRoot")
        self.assertEqual(len(self.entities["/world/body/bones"][0][0]["LineStrips3D:strips"]), 18)

    def test_a_failed_hull_clears_its_box(self):
        rows = self.entities["/world/hull/bbox"][make_log.FAILED_HULL_FRAME]
        self.assertTrue(any(k.startswith("Clear") for k in rows[0]), rows[0].keys())

    def test_the_corrupt_event_is_named_and_the_rest_shown(self):
        err = self.result.stderr
        self.assertRegex(err, r"lcmlog:\S+test.lcmlog event \d+ channel SYNCAP_BLOBS_01: "
                              r"blob_frame_t does not decode")
        self.assertIn("1 messages skipped", err)
        self.assertIn(f"{FRAMES} frames", err)

    def test_without_calibration_the_cameras_are_2d_only(self):
        rrd = str(Path(self.dir.name) / "uncalibrated.rrd")
        run("--input", f"lcmlog:{self.log}", "--save", rrd, "--quiet")
        entities, frames = read_rrd(rrd)
        self.assertEqual(frames, set(range(FRAMES)))
        self.assertIn("/cameras/01/blobs", entities)
        self.assertIn("/cameras/01/sensor", entities)
        self.assertFalse([e for e in entities if e.startswith("/world/cameras")])

    def test_max_frames_and_channel(self):
        rrd = str(Path(self.dir.name) / "four.rrd")
        run("--input", f"lcmlog:{self.log}", "--save", rrd, "--max-frames", "4",
            "--channel", "SYNCAP_(MARKERS|HULL)", "--quiet")
        entities, frames = read_rrd(rrd)
        self.assertEqual(frames, set(range(4)))
        self.assertIn("/world/markers", entities)
        self.assertIn("/world/hull/bbox", entities)
        self.assertNotIn("/world/body/joints", entities)
        self.assertFalse([e for e in entities if "/cameras/" in e])

    def test_a_log_cut_short_or_garbled_shows_what_reads(self):
        data = Path(self.log).read_bytes()
        d = Path(self.dir.name)
        (d / "cut.lcmlog").write_bytes(data[:len(data) // 2])
        result = run("--input", f"lcmlog:{d / 'cut.lcmlog'}", "--save", str(d / "cut.rrd"))
        self.assertRegex(result.stderr, r"cut.lcmlog after event \d+: the log ends inside an event")
        _, frames = read_rrd(str(d / "cut.rrd"))
        self.assertTrue(3 <= len(frames) < FRAMES, frames)
        # 100 bytes of junk in the middle: skipped, the frames after it still shown
        junk = bytes(range(100))
        (d / "junk.lcmlog").write_bytes(data[:len(data) // 2] + junk + data[len(data) // 2:])
        result = run("--input", f"lcmlog:{d / 'junk.lcmlog'}", "--save", str(d / "junk.rrd"))
        self.assertRegex(result.stderr, r"junk.lcmlog after event \d+: bytes \d+\.\.\d+ are not "
                                        r"an event; skipped to the next one")
        _, frames = read_rrd(str(d / "junk.rrd"))
        self.assertEqual(frames, set(range(FRAMES)))
        (d / "text.lcmlog").write_text("not a log\n")
        result = run("--input", f"lcmlog:{d / 'text.lcmlog'}", "--save", str(d / "t.rrd"),
                     check=False)
        self.assertEqual(result.returncode, 2)
        self.assertIn("no LCM log event in its 10 bytes", result.stderr)

    def test_the_launcher_finds_the_venv_of_its_build_tree(self):
        """build/bin/syncap-view (the link `syncap view` runs) uses build/py-venv."""
        build = Path(self.dir.name) / "build"
        (build / "bin").mkdir(parents=True)
        (build / "py-venv").symlink_to(sys.prefix)
        (build / "bin" / "syncap-view").symlink_to(support.VIEWER / "syncap-view")
        rrd = str(Path(self.dir.name) / "launched.rrd")
        env = {k: v for k, v in os.environ.items() if k not in ("SYNCAP_PY_VENV", "PYTHONPATH")}
        result = subprocess.run([str(build / "bin" / "syncap-view"), "--input",
                                 f"lcmlog:{self.log}", "--save", rrd, "--quiet"],
                                capture_output=True, text=True, env=env, timeout=120)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(read_rrd(rrd)[1], set(range(FRAMES)))
        env["SYNCAP_PY_VENV"] = str(Path(self.dir.name) / "no-venv")
        result = subprocess.run([str(build / "bin" / "syncap-view"), "--help"],
                                capture_output=True, text=True, env=env)
        self.assertEqual(result.returncode, 2)
        self.assertIn("make it with:", result.stderr)
        self.assertIn("scripts/py-deps.sh", result.stderr)

    def test_a_missing_log_is_a_usage_error_naming_it(self):
        result = run("--input", "lcmlog:/nonexistent/x.lcmlog", "--save", "/tmp/never.rrd",
                     check=False)
        self.assertEqual(result.returncode, 2)
        self.assertIn("lcmlog:/nonexistent/x.lcmlog: no such file", result.stderr)
        self.assertFalse(Path("/tmp/never.rrd").exists())

    def test_a_desktop_viewer_that_cannot_start_is_an_error(self):
        """--spawn whose viewer exits at once (here `false` as the rerun binary; on a display
        without the GPU features Rerun needs, its own error): exit 1, said, not success."""
        env = support.run_env()
        env["SYNCAP_RERUN"] = "/bin/false"
        rrd = str(Path(self.dir.name) / "spawn.rrd")
        result = subprocess.run(support.program() + ["--input", f"lcmlog:{self.log}", "--spawn",
                                                     "--save", rrd, "--quiet"],
                                capture_output=True, text=True, env=env, timeout=120)
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn("--spawn: the desktop viewer (/bin/false) exited with status 1",
                      result.stderr)
        self.assertTrue(Path(rrd).stat().st_size > 0, "the --save recording is still written")

    def test_a_body_definition_without_the_sigmas_is_taken(self):
        """body_frame_t gained sigma0, parameter_sigmas[60] and joint_sigma_mm[19] at its end: a
        log written with the older definition, viewed with it, shows the body without sigma0;
        the tree's definition cannot read it and names it."""
        d = Path(self.dir.name) / "msg-older"
        d.mkdir()
        for f in (support.REPO / "proto" / "msg").glob("*.lcm"):
            text = f.read_text()
            if f.name == "body_frame_t.lcm":
                start = text.index("    // The fit's precision")
                text = text[:start].rstrip() + "\n}\n"
                self.assertNotIn("sigma0", text)
            (d / f.name).write_text(text)
        log = str(Path(self.dir.name) / "older.lcmlog")
        subprocess.run([sys.executable, str(Path(__file__).with_name("make_log.py")), log,
                        "--proto-msg", str(d)], check=True, env=support.run_env())
        rrd = str(Path(self.dir.name) / "older.rrd")
        run("--input", f"lcmlog:{log}", "--save", rrd, "--proto-msg", str(d), "--quiet")
        entities, _ = read_rrd(rrd)
        self.assertNotIn("/plots/body/sigma0", entities)
        self.assertEqual(len(entities["/world/body/joints"][0][0]["Points3D:positions"]), 19)
        result = run("--input", f"lcmlog:{log}", "--save", rrd, "--quiet")
        self.assertRegex(result.stderr, r"unknown message type .* SYNCAP_BODY")

    def test_the_body_sigma0_is_plotted(self):
        """The tree's body_frame_t carries sigma0: it is plotted beside the fit's RMS."""
        self.assertIn("/plots/body/sigma0", self.entities)

if __name__ == "__main__":
    unittest.main()
