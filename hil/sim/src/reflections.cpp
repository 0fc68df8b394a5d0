#include "reflections.hpp"

#include <algorithm>
#include <cstdint>
#include <random>

#include "disc_coverage.hpp"

namespace syncap::sim {

std::vector<ImageDisc> reflection_discs(const ReflectionSpec& spec, unsigned seed, int camera,
                                        int width, int height) {
  std::mt19937_64 rng(static_cast<uint64_t>(seed) * 1'000'003u + static_cast<uint64_t>(camera) +
                      0x7e11ec7u);
  const double margin = spec.radius_px + 1;
  std::uniform_real_distribution<double> x(margin, std::max(margin, width - 1 - margin));
  std::uniform_real_distribution<double> y(margin, std::max(margin, height - 1 - margin));
  std::vector<ImageDisc> discs;
  for (int i = 0; i < spec.count; ++i) {
    const double cx = x(rng), cy = y(rng);
    discs.push_back({{cx, cy}, spec.radius_px, spec.brightness_dn});
  }
  return discs;
}

void paint_discs(const std::vector<ImageDisc>& discs, cv::Mat& radiance) {
  for (const ImageDisc& d : discs) {
    for_each_covered_pixel(d.centre_px.x(), d.centre_px.y(), d.radius_px, radiance.cols,
                           radiance.rows, [&](int x, int y, double a) {
                             float& v = radiance.at<float>(y, x);
                             v += static_cast<float>(a * (d.brightness_dn - v));
                           });
  }
}

}  // namespace syncap::sim
