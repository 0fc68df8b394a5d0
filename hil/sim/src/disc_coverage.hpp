// Exact area of a disc inside a pixel: the wand targets and the LED are rendered with it, so a
// rendered target's total brightness is exactly pi r^2 times its brightness and its centre is
// known exactly.
#pragma once

#include <functional>

namespace syncap::sim {

// Area of the disc of radius r centred at (cx, cy) inside the rectangle [x0, x1] x [y0, y1].
double disc_rect_area(double cx, double cy, double r, double x0, double y0, double x1, double y1);

// Calls paint(x, y, coverage) for every pixel with coverage > 0 of a disc centred at (cx, cy)
// with radius r, in the project's pixel convention: pixel (x, y) covers [x-0.5, x+0.5] x
// [y-0.5, y+0.5] (integer coordinates at pixel centres). Pixels outside width x height are
// skipped.
void for_each_covered_pixel(double cx, double cy, double r, int width, int height,
                            const std::function<void(int, int, double)>& paint);

}  // namespace syncap::sim
