#include "disc_coverage.hpp"

#include <algorithm>
#include <cmath>

namespace syncap::sim {
namespace {

// Primitive of h(t) = sqrt(r^2 - t^2) on [-r, r].
double half_chord_primitive(double t, double r) {
  const double h = std::sqrt(std::max(0.0, r * r - t * t));
  return 0.5 * (t * h + r * r * std::asin(std::clamp(t / r, -1.0, 1.0)));
}

// Integral over [a, b] (clipped to [lo, hi]) of k*h(t) + y.
double integrate(double a, double b, double lo, double hi, double r, double k, double y) {
  a = std::max(a, lo);
  b = std::min(b, hi);
  if (b <= a) return 0.0;
  return k * (half_chord_primitive(b, r) - half_chord_primitive(a, r)) + y * (b - a);
}

// Area of {p in disc(0, r) : p.x <= x, p.y <= y}.
double disc_corner_area(double x, double y, double r) {
  if (y <= -r || x <= -r) return 0.0;
  const double xr = std::min(x, r);
  if (y >= r) return integrate(-r, xr, -r, xr, r, 2.0, 0.0);
  const double w = std::sqrt(r * r - y * y);  // |t| < w: the line Y = y cuts the chord at t
  if (y >= 0) {
    // Outside |t| < w the whole chord (length 2h) lies below y; inside, from -h up to y.
    return integrate(-r, -w, -r, xr, r, 2.0, 0.0) + integrate(-w, w, -r, xr, r, 1.0, y) +
           integrate(w, r, -r, xr, r, 2.0, 0.0);
  }
  return integrate(-w, w, -r, xr, r, 1.0, y);  // only |t| <= w reaches below y < 0
}

}  // namespace

double disc_rect_area(double cx, double cy, double r, double x0, double y0, double x1, double y1) {
  if (r <= 0 || x1 <= x0 || y1 <= y0) return 0.0;
  x0 -= cx, x1 -= cx, y0 -= cy, y1 -= cy;
  const double area = disc_corner_area(x1, y1, r) - disc_corner_area(x0, y1, r) -
                      disc_corner_area(x1, y0, r) + disc_corner_area(x0, y0, r);
  return std::max(0.0, area);
}

void for_each_covered_pixel(double cx, double cy, double r, int width, int height,
                            const std::function<void(int, int, double)>& paint) {
  const int x0 = std::max(0, static_cast<int>(std::floor(cx - r + 0.5)));
  const int x1 = std::min(width - 1, static_cast<int>(std::ceil(cx + r - 0.5)));
  const int y0 = std::max(0, static_cast<int>(std::floor(cy - r + 0.5)));
  const int y1 = std::min(height - 1, static_cast<int>(std::ceil(cy + r - 0.5)));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double a = disc_rect_area(cx, cy, r, x - 0.5, y - 0.5, x + 0.5, y + 0.5);
      if (a > 0) paint(x, y, a);
    }
  }
}

}  // namespace syncap::sim
