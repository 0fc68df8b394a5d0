// `syncap calibrate`: calibrates the cameras from wand (or LED) observations and writes the
// calibration folder (host/src/calibration/outputs.hpp; docs/calibration.md, "syncap calibrate").
#pragma once

#include <ostream>
#include <span>
#include <string>

namespace syncap::tools {

inline constexpr const char* kCalibrateUsage =
    "usage: syncap calibrate --input SOURCE (--wand-length MM | --led) --out DIR [options]\n"
    "SOURCE:\n"
    "  lcm:URL        blob frames live (udpm://239.255.76.67:7667?ttl=0); needs --cameras; stops\n"
    "                 at Ctrl-C, after --frames groups, or --idle-timeout s without blob frames\n"
    "  lcmlog:FILE    blob frames recorded by lcm-logger (hil/run: OUT/traffic.lcmlog)\n"
    "  csv:FILE       frame,camera,x,y[,point] in pixels (point: target index from end A)\n"
    "  mcsc:DIR       a MultiCamSelfCal folder (points.dat, Res.dat, camera_order.txt)\n"
    "Writes DIR/cameras.json (with a \"quality\" block), report.txt, report.html,\n"
    "cameras.opencv.yaml, calibration.toml and, when built with the SDL writer, scene.sdl.\n"
    "DIR is created and checked writable before SOURCE is read.\n"
    "Options:\n"
    "  --wand-length MM      distance between the wand's end targets\n"
    "  --led                 one point per frame (no scale: the result is in arbitrary units)\n"
    "  --scale-from A,B,MM   --led: the scale from the distance of cameras A and B's centres\n"
    "  --wand-targets N      2 or 3 (default 3)\n"
    "  --wand-ratio R        middle target's distance from end A / length (default 0.4)\n"
    "  --wand-ends size|continuity  how a 2-target (or symmetric) wand's ends are told apart\n"
    "                        (default continuity: the upper spot starts as end A)\n"
    "  --pixel-size MM       the sensors' pixel pitch (default 0.005, nominal)\n"
    "  --image-size WxH      the image size of cameras the source gives none for (csv:)\n"
    "  --fov DEG             horizontal field of view for the start value of c, tried first\n"
    "                        (default 60)\n"
    "  --start-fovs LIST     the fields of view the start is also searched from, each run on\n"
    "                        200 frames, the best (plausible, lowest median residual) kept\n"
    "                        (default 40,50,60,70,80,90,100; none: --fov alone)\n"
    "  --principal-point-sigma S  the principal point is observed at the image centre with\n"
    "                        S x the sensor width as its sigma (default 0.03 with --led, none\n"
    "                        with a wand; 0: no prior, e.g. for images cropped off-centre)\n"
    "  --check-share S       share of the frames held out and predicted as check points\n"
    "                        (default 0.1; 0: none)\n"
    "  --interior LIST       interior values that may be estimated, of c,xp,yp,k1,k2,k3,p1,p2,\n"
    "                        sc,sh (default c,xp,yp,k1,k2,k3,p1,p2; --led without k3)\n"
    "  --shared-interior     one interior orientation for all cameras (identical cameras and\n"
    "                        lenses; their image and pixel sizes must agree)\n"
    "  --model auto|all      auto (default with --led): the base model (c, xp, yp, k1, k2 of\n"
    "                        --interior) first, then each further group (p1+p2, k3, sc, sh) only\n"
    "                        where it improves the fit significantly, is significant and not too\n"
    "                        correlated; all (default with a wand): every --interior value\n"
    "  --sigma-px PX         a priori standard deviation of a measured coordinate (0.1)\n"
    "  --wand-sigma MM       standard deviation of a wand distance (0.2)\n"
    "  --critical-w W        data snooping's critical value (3.29)\n"
    "  --max-frames N        use at most N frames (N >= 1), evenly spread (default all)\n"
    "  --bootstrap N         also the interior sigmas of N re-adjustments of simulated\n"
    "                        measurements (a parametric bootstrap: honest in weak networks)\n"
    "  --cameras LIST        camera ids to wait for in each frame group (lcm:, lcmlog:; for a\n"
    "                        log default: every camera in it)\n"
    "  --frame-range A-B     lcm:, lcmlog: only frames A to B (\"300-\", \"-299\": open ends);\n"
    "                        lcm: stops after frame B\n"
    "  --frames N            lcm: stop after N frame groups\n"
    "  --idle-timeout S      lcm: stop S seconds after the last blob frame (default 5)\n"
    "  --progress            print progress on stderr (default: only when stderr is a terminal)\n"
    "A malformed record in lcmlog:FILE is named (event, offset, channel), counted and skipped.\n"
    "The summary and report.txt start with the verdict: good, weak (usable; the reasons say\n"
    "what the data could not determine) or failed (the geometry is wrong).\n"
    "Exit status: 0 calibrated (good or weak), 1 the calibration failed (did not converge, or its\n"
    "verdict is failed; the outputs are written for inspection), 2 usage error or unusable "
    "input.\n";

int calibrate_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
