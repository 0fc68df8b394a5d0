// The automatic start of the body fit, without a GUI (issue 18, "Automatic start"; thesis section
// 5.2.3.1 started the model by hand): from one frame's points on the person's surface (the visual
// hull's), where the person stands, how tall, which way they face, and a first pose.
//
// The person is the points' horizontal median, standing on their lowest point. A standing body
// is wider across the shoulders than deep, so the points' principal horizontal axis is the
// figure's left-right axis, up to its sign, and a wide stride can swap it with the walking
// direction: the rest figure is turned to each of the four headings those leave (the axis and
// its quarter turns), fitted briefly from each, and the heading whose fit keeps most of the
// points closest to the surface is fitted to the end.
#pragma once

#include <span>
#include <string>

#include "fitting/surface_fit.hpp"

namespace syncap::fitting {

struct BodyStartOptions {
  // Each heading's brief fit (fewer rounds), and the winner's full one.
  int trial_rounds = 8;
  SurfaceFitOptions fit;
  // A person's height [mm], the points' vertical extent: outside it there is no person to start.
  double min_height_mm = 1000;
  double max_height_mm = 2400;
  // The winner must keep this share of the points within its gate, else no start (a hull of
  // something that is not one standing person, or a pose the rest figure cannot reach).
  double min_points_kept = 0.8;
};

struct BodyStart {
  bool found = false;
  std::string why_not;     // when not found
  SurfaceFit fit;          // the winner's full fit (its pose: fit.x)
  double heading_rad = 0;  // the rest figure's turn about the vertical that won
  double height_mm = 0;    // the points' vertical extent
  int trials = 0;          // brief fits run
};

// Throws what fit_surface throws for bad points (too few, a sigma not positive).
BodyStart start_body(const PoseParameters& parameters, std::span<const SurfacePoint> points,
                     const BodyStartOptions& options = {});

}  // namespace syncap::fitting
