"""syncap view: options, the sinks, the loop (docs/guide/view.md)."""

from __future__ import annotations

import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

EXIT_USAGE = 2  # as every syncap program: a usage error or bad input, named


def renamed(argv):
    """argv with the old option names as the new ones (docs/reference/cli.md, "Old names"),
    each said on stderr: --cameras FILE is --calibration FILE, and --calibration DIR (a folder)
    is --calibration-dir DIR."""
    out = list(argv)
    for i, arg in enumerate(out):
        name, eq, value = arg.partition("=")
        if name == "--cameras":
            new = "--calibration"
        elif name == "--calibration":
            given = value if eq else (out[i + 1] if i + 1 < len(out) else "")
            new = "--calibration-dir" if given and Path(given).is_dir() else None
        else:
            new = None
        if new:
            print(f"syncap view: {name} is deprecated, use {new}", file=sys.stderr)
            out[i] = new + eq + value
    return out


def parse_args(argv):
    p = argparse.ArgumentParser(
        prog="syncap view",
        description="Show syncap's LCM traffic (live, or from a recorded LCM log) in Rerun: "
                    "cameras, blobs, silhouettes, 3D markers, the hull's box, the fitted body, "
                    "the edges' status. Parts that are absent are simply not shown.")
    src = p.add_mutually_exclusive_group()
    src.add_argument("--input", metavar="lcmlog:FILE",
                     help="replay a recorded LCM log (syncap record, lcm-logger)")
    src.add_argument("--groups", metavar="FILE.jsonl",
                     help="replay the host's JSON lines (syncap-host --out, syncap markers' "
                          "markers.jsonl): "
                          "blobs, silhouettes, markers, rigid sets' poses, hull, body")
    src.add_argument("--lcm-url", metavar="URL",
                     help="live: subscribe on this LCM URL (default: $LCM_DEFAULT_URL or LCM's "
                          "default, udpm://239.255.76.67:7667?ttl=0)")
    p.add_argument("--calibration", metavar="cameras.json", dest="cameras",
                   help="the calibration's cameras: frusta in 3D, 2D content in their images")
    p.add_argument("--calibration-dir", metavar="DIR", dest="calibration",
                   help="a `syncap calibrate --out-dir` folder: its cameras (unless "
                        "--calibration), the adjusted wand points, each image's residual vectors "
                        "and coverage; alone (no --input, --groups, --lcm-url) it shows just the "
                        "calibration")
    p.add_argument("--hull-meshes", metavar="DIR",
                   help="the hull's meshes, hull_<frame>.ply (syncap-host --hull-meshes, the "
                        "replay bench's RUN/hull): each at its frame")
    p.add_argument("--save", metavar="FILE.rrd", help="write a Rerun recording")
    p.add_argument("--web", action="store_true",
                   help="serve Rerun's web viewer on 127.0.0.1 (--web-port, --grpc-port); it "
                        "stays up after a recording ended, until Ctrl-C")
    p.add_argument("--web-port", type=int, default=9090, metavar="PORT")
    p.add_argument("--grpc-port", type=int, default=9876, metavar="PORT",
                   help="the data server the web viewer reads from (127.0.0.1; --spawn's "
                        "viewer listens on it too, or on the next one with --web)")
    p.add_argument("--spawn", action="store_true",
                   help="start Rerun's desktop viewer (the venv's `rerun`, on 127.0.0.1) and "
                        "stream to it")
    p.add_argument("--max-frames", type=int, metavar="N",
                   help="stop after N frame numbers were shown")
    p.add_argument("--channel", default=".*", metavar="REGEX",
                   help="only channels matching REGEX as a whole (default: all)")
    p.add_argument("--trail", type=int, default=30, metavar="FRAMES",
                   help="markers' trails over this many frames (0: none; default 30)")
    p.add_argument("--frustum-mm", type=float, default=300.0, metavar="MM",
                   help="distance of the frusta's image planes from their centres (default 300)")
    p.add_argument("--proto-msg", metavar="DIR",
                   help="the .lcm definitions (default: $SYNCAP_PROTO_MSG, else the source "
                        "tree's proto/msg)")
    p.add_argument("--quiet", action="store_true", help="print only the summary")
    args = p.parse_args(renamed(argv))
    if args.input is not None and not args.input.startswith("lcmlog:"):
        p.error(f"--input {args.input}: expected lcmlog:FILE")
    if not (args.save or args.web or args.spawn):
        p.error("say where to show it: --save FILE.rrd, --web or --spawn (any of them together)")
    if args.max_frames is not None and args.max_frames < 1:
        p.error("--max-frames must be at least 1")
    if args.trail < 0:
        p.error("--trail must be 0 or more")
    try:
        re.compile(args.channel)
    except re.error as e:
        p.error(f"--channel {args.channel}: not a regular expression: {e}")
    return args


def rerun_executable() -> str:
    """The `rerun` binary rerun-sdk ships (package rerun_cli), or $SYNCAP_RERUN. The venv's
    bin/rerun is a Python wrapper that runs it as a child: stopping the wrapper would leave the
    binary running."""
    if os.environ.get("SYNCAP_RERUN"):
        return os.environ["SYNCAP_RERUN"]
    try:
        import rerun_cli
        path = Path(rerun_cli.__file__).parent / "rerun"
        if path.is_file():
            return str(path)
    except ImportError:
        pass
    return shutil.which("rerun") or "rerun"


def start_rerun(args: list[str], detach: bool) -> subprocess.Popen:
    """A `rerun` process bound to 127.0.0.1: the viewer is for this workstation, never for the
    camera network (rr.serve_web_viewer and rr.spawn listen on every interface)."""
    env = dict(os.environ)
    env.setdefault("RUST_LOG", "warn")  # its errors, not its INFO lines
    return subprocess.Popen([rerun_executable(), "--bind", "127.0.0.1"] + args, env=env,
                            stdout=subprocess.DEVNULL, start_new_session=detach)


def open_sinks(args, rr) -> list[subprocess.Popen]:
    """Every output asked for, at once (rr.set_sinks replaces, so they are set together); the
    rerun processes started for --web and --spawn."""
    sinks, children = [], []
    if args.save:
        sinks.append(rr.FileSink(args.save))
    if args.web:
        # `rerun --serve-web` holds the data server and the web viewer's page, both on localhost.
        children.append(start_rerun(["--serve-web", "--port", str(args.grpc_port),
                                     "--web-viewer-port", str(args.web_port)], detach=False))
        sinks.append(rr.GrpcSink(f"rerun+http://127.0.0.1:{args.grpc_port}/proxy"))
        print(f"syncap view: web viewer at http://127.0.0.1:{args.web_port}/?url=rerun%2Bhttp"
              f"%3A%2F%2F127.0.0.1%3A{args.grpc_port}%2Fproxy", file=sys.stderr)
    if args.spawn:
        # The desktop viewer outlives this program (its own session), as rr.spawn's does.
        port = args.grpc_port + (1 if args.web else 0)
        args.spawned = start_rerun(["--port", str(port)], detach=True)
        sinks.append(rr.GrpcSink(f"rerun+http://127.0.0.1:{port}/proxy"))
    rr.set_sinks(*sinks)
    return children


def main(argv=None) -> int:
    args = parse_args(sys.argv[1:] if argv is None else argv)
    from . import bindings, calibration as calib, cameras as cams, meshes, sources

    # Everything that can be wrong with the inputs is found before any sink or viewer is made.
    try:
        types = bindings.types_by_fingerprint(bindings.load(args.proto_msg))
        folder = calib.read_folder(args.calibration) if args.calibration else None
        hulls = meshes.hull_files(args.hull_meshes) if args.hull_meshes else {}
        camera_list = cams.read_cameras(args.cameras) if args.cameras else []
        if folder and not args.cameras:
            camera_list = folder.cameras
        log_errors: list[str] = []
        events = open_input(args, log_errors)
    except (bindings.BindingsError, sources.InputError) as e:
        print(f"syncap view: {e}", file=sys.stderr)
        return EXIT_USAGE
    except calib.CalibrationFolderError as e:
        print(f"syncap view: --calibration {e}", file=sys.stderr)
        return EXIT_USAGE
    except meshes.MeshFileError as e:
        print(f"syncap view: --hull-meshes {e}", file=sys.stderr)
        return EXIT_USAGE
    except cams.CameraFileError as e:
        print(f"syncap view: --cameras {e}", file=sys.stderr)
        return EXIT_USAGE

    import rerun as rr
    from .logger import TIMELINE, ViewLogger

    # SIGTERM ends the program as Ctrl-C does: what arrived is flushed, the children stopped.
    signal.signal(signal.SIGTERM, _interrupt)
    signal.signal(signal.SIGINT, _interrupt)
    rr.init("syncap_view", spawn=False)
    children = open_sinks(args, rr)
    view = ViewLogger(types, camera_list, trail_frames=args.trail, max_frames=args.max_frames,
                      image_plane_mm=args.frustum_mm, quiet=args.quiet)
    if folder:
        shown = calib.log_folder(rr, folder, view.camera_path)
        print(f"syncap view: calibration {args.calibration}: {len(folder.cameras)} cameras, "
              f"{shown['points']} wand points, {sum(shown['residuals'].values())} residuals "
              f"(drawn x {shown['scale']:.0f})"
              + (f"; no {', '.join(folder.missing)}" if folder.missing else ""), file=sys.stderr)
    if hulls:
        shown, unreadable = meshes.log_hull_meshes(rr, args.hull_meshes, TIMELINE)
        print(f"syncap view: {shown} hull meshes from {args.hull_meshes}", file=sys.stderr)
        for e in unreadable:  # named in the summary; the other meshes are shown
            view.input_error(f"--hull-meshes {e}")
    start = time.monotonic()
    interrupted = run(view, events, groups=bool(args.groups))
    for e in log_errors:
        view.input_error(e)
    elapsed = time.monotonic() - start
    print(f"syncap view: {view.summary()}\nsyncap view: {elapsed:.2f} s, "
          f"{len(view.frames) / elapsed if elapsed > 0 else 0:.1f} frames/s", file=sys.stderr)
    rr.disconnect()  # flushes the sinks (the .rrd's footer, the data to the web server)
    failed = children and not interrupted and not serve_until_interrupted(children)
    spawned = getattr(args, "spawned", None)
    if spawned is not None and spawned.poll() not in (None, 0):
        # The desktop viewer could not start (e.g. a software OpenGL without the texture formats
        # Rerun needs): what was sent to it is lost, which must not look like success.
        print(f"syncap view: --spawn: the desktop viewer ({rerun_executable()}) exited with status "
              f"{spawned.returncode} (its message above); nothing was shown there. --save or --web "
              "instead", file=sys.stderr)
        failed = True
    for c in children:
        c.terminate()
        c.wait()
    return 1 if failed else 0


def open_input(args, log_errors: list):
    """The events of the input the options name; a file that cannot be read raises here."""
    from . import sources

    if args.groups:
        return sources.group_lines(args.groups)
    if (args.calibration or args.hull_meshes) and not args.input and not args.lcm_url:
        return iter(())  # the calibration or the meshes alone
    if args.input:
        # Run to the first event now, so that a missing file or one without an event is an
        # error before anything is shown.
        return _prime(sources.log_events(args.input[len("lcmlog:"):], args.channel, log_errors))
    _Stop.polling_live = True
    return sources.live_events(args.lcm_url, args.channel, stop=lambda: _Stop.requested)


def run(view, events, groups: bool) -> bool:
    """Logs every event until the input ends, --max-frames, or Ctrl-C (then returns True)."""
    from .logger import StopInput

    try:
        for event in events:
            if event is None:  # live, nothing arrived for a moment
                view.tick()
                continue
            if groups:
                view.handle_group(*event)
            else:
                view.handle(*event)
    except StopInput:
        pass
    except KeyboardInterrupt:
        view.finish()
        return True
    view.finish()
    _Stop.polling_live = False  # a Ctrl-C from here on (the web server's wait) raises again
    return _Stop.requested


def serve_until_interrupted(children: list) -> bool:
    """After a recording, the web server holds the data: it stays until Ctrl-C. False when it
    ended by itself (it could not listen)."""
    print("syncap view: input ended; the web viewer stays up until Ctrl-C", file=sys.stderr)
    try:
        while all(c.poll() is None for c in children):
            time.sleep(0.5)
    except KeyboardInterrupt:
        return True
    for c in children:
        if c.returncode is not None:
            print(f"syncap view: rerun --serve-web exited with status {c.returncode} (a port in "
                  "use? --web-port, --grpc-port)", file=sys.stderr)
    return False


class _Stop:
    """Ctrl-C or SIGTERM asked: live input polls `requested`; elsewhere the handler raises
    KeyboardInterrupt as Python's own does."""
    requested = False
    polling_live = False


def _interrupt(signum, frame):
    _Stop.requested = True
    if not _Stop.polling_live:
        raise KeyboardInterrupt


def _prime(events):
    """Runs a generator to its first event (opening the input) and gives it back whole."""
    try:
        first = next(events)
    except StopIteration:
        return iter(())
    def chained():
        yield first
        yield from events
    return chained()
