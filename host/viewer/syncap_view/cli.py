"""syncap view: options, the sinks, the loop (docs/viewer.md)."""

from __future__ import annotations

import argparse
import sys
import time

EXIT_USAGE = 2  # as every syncap program: a usage error or bad input, named


def parse_args(argv):
    p = argparse.ArgumentParser(
        prog="syncap view",
        description="Show syncap's LCM traffic (live, or from a recorded LCM log) in Rerun: "
                    "cameras, blobs, silhouettes, 3D markers, the hull's box, the fitted body, "
                    "the edges' status. Parts that are absent are simply not shown.")
    src = p.add_mutually_exclusive_group()
    src.add_argument("--input", metavar="lcmlog:FILE",
                     help="replay a recorded LCM log (syncap record, lcm-logger)")
    src.add_argument("--lcm-url", metavar="URL",
                     help="live: subscribe on this LCM URL (default: $LCM_DEFAULT_URL or LCM's "
                          "default, udpm://239.255.76.67:7667?ttl=0)")
    p.add_argument("--cameras", metavar="cameras.json",
                   help="the calibration's cameras: frusta in 3D, 2D content in their images")
    p.add_argument("--save", metavar="FILE.rrd", help="write a Rerun recording")
    p.add_argument("--web", action="store_true",
                   help="serve Rerun's web viewer on localhost (--web-port, --grpc-port)")
    p.add_argument("--web-port", type=int, default=9090, metavar="PORT")
    p.add_argument("--grpc-port", type=int, default=9876, metavar="PORT",
                   help="the data server the web viewer reads from (localhost)")
    p.add_argument("--spawn", action="store_true",
                   help="start Rerun's desktop viewer (the `rerun` of the venv) and stream to it")
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
    args = p.parse_args(argv)
    if args.input is not None and not args.input.startswith("lcmlog:"):
        p.error(f"--input {args.input}: expected lcmlog:FILE")
    if not (args.save or args.web or args.spawn):
        p.error("say where to show it: --save FILE.rrd, --web or --spawn (any of them together)")
    if args.max_frames is not None and args.max_frames < 1:
        p.error("--max-frames must be at least 1")
    if args.trail < 0:
        p.error("--trail must be 0 or more")
    import re
    try:
        re.compile(args.channel)
    except re.error as e:
        p.error(f"--channel {args.channel}: not a regular expression: {e}")
    return args


def open_sinks(args, rr):
    """Every output asked for, at once (rr.set_sinks replaces, so they are set together)."""
    sinks = []
    if args.save:
        sinks.append(rr.FileSink(args.save))
    if args.web:
        # The data server and the web viewer's page on localhost only: the viewer is for the
        # workstation, not for the camera network.
        server = rr.GrpcServerSink(bind_ip="127.0.0.1", port=args.grpc_port)
        sinks.append(server)
    if args.spawn:
        rr.spawn(port=args.grpc_port + (1 if args.web else 0), connect=False)
        sinks.append(rr.GrpcSink(f"rerun+http://127.0.0.1:{args.grpc_port + (1 if args.web else 0)}/proxy"))
    rr.set_sinks(*sinks)
    if args.web:
        rr.serve_web_viewer(web_port=args.web_port, open_browser=False, connect_to=server.uri)
        print(f"syncap view: web viewer at http://localhost:{args.web_port}/?url={server.uri}",
              file=sys.stderr)


def main(argv=None) -> int:
    args = parse_args(sys.argv[1:] if argv is None else argv)
    from . import bindings, cameras as cams, sources

    try:
        types = bindings.types_by_fingerprint(bindings.load(args.proto_msg))
    except bindings.BindingsError as e:
        print(f"syncap view: {e}", file=sys.stderr)
        return EXIT_USAGE
    camera_list = []
    if args.cameras:
        try:
            camera_list = cams.read_cameras(args.cameras)
        except cams.CameraFileError as e:
            print(f"syncap view: --cameras {e}", file=sys.stderr)
            return EXIT_USAGE
    log_errors: list[str] = []
    try:
        if args.input:
            events = sources.log_events(args.input[len("lcmlog:"):], args.channel, log_errors)
            # Open the file now, so that a missing one is an error before any sink is made.
            events = _prime(events)
        else:
            events = sources.live_events(args.lcm_url, args.channel)
    except sources.InputError as e:
        print(f"syncap view: {e}", file=sys.stderr)
        return EXIT_USAGE

    import rerun as rr
    from .logger import StopInput, ViewLogger

    rr.init("syncap_view", spawn=False)
    open_sinks(args, rr)
    view = ViewLogger(types, camera_list, trail_frames=args.trail, max_frames=args.max_frames,
                      image_plane_mm=args.frustum_mm, quiet=args.quiet)
    start = time.monotonic()
    try:
        for event in events:
            if event is not None:
                view.handle(*event)
    except StopInput:
        pass
    except KeyboardInterrupt:
        pass
    view.finish()
    for e in log_errors:
        view.skip(e.split(" ")[0], "", e)
    elapsed = time.monotonic() - start
    print(f"syncap view: {view.summary()}\nsyncap view: {elapsed:.2f} s, "
          f"{len(view.frames) / elapsed if elapsed > 0 else 0:.1f} frames/s", file=sys.stderr)
    if args.web:  # the server goes with the recording stream: keep it until Ctrl-C
        rr.flush()
        print("syncap view: input ended; the web viewer stays up until Ctrl-C", file=sys.stderr)
        try:
            while True:
                time.sleep(1)
        except KeyboardInterrupt:
            pass
    rr.disconnect()  # flushes the sinks (the .rrd's footer)
    return 0


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
