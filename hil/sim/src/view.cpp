#include "view.hpp"

#include <cmath>
#include <limits>

namespace syncap::sim {
namespace {

// A fixed integer hash: textures must not change between runs or machines.
uint32_t hash3(int32_t a, int32_t b, uint32_t seed) {
  uint32_t h = seed * 0x9E3779B1u ^ static_cast<uint32_t>(a) * 0x85EBCA77u ^
               static_cast<uint32_t>(b) * 0xC2B2AE3Du;
  h ^= h >> 15;
  h *= 0x2C1B3C6Du;
  h ^= h >> 12;
  return h;
}

double unit_hash(int32_t a, int32_t b, uint32_t seed) {
  return (hash3(a, b, seed) & 0xffff) / 65535.0;
}

// Floor: 600 mm tiles of random grey with a fine grain; walls: 1 m panels and a dark skirting.
float texture_on_plane(double u, double v, uint32_t seed, bool floor) {
  const double tile = floor ? 600.0 : 1000.0;
  const int32_t iu = static_cast<int32_t>(std::floor(u / tile));
  const int32_t iv = static_cast<int32_t>(std::floor(v / tile));
  double grey =
      floor ? 80.0 + 60.0 * unit_hash(iu, iv, seed) : 120.0 + 40.0 * unit_hash(iu, 7, seed);
  grey += 12.0 * std::sin(u * 0.031) * std::sin(v * 0.027);  // grain: texture for matching
  const double du = u - iu * tile, dv = v - iv * tile;
  if (du < 15 || (floor && dv < 15)) grey *= 0.6;  // joints between tiles and panels
  if (!floor && v < 120) grey = 55.0;              // skirting board
  return static_cast<float>(grey);
}

}  // namespace

float room_texture(const Eigen::Vector3d& p, const Scenario& sc) {
  const uint32_t seed = sc.seed;
  const double hx = sc.room_size_mm.x() / 2, hy = sc.room_size_mm.y() / 2;
  if (std::abs(p.z()) < 1e-6) return texture_on_plane(p.x(), p.y(), seed, true);
  if (std::abs(std::abs(p.x()) - hx) < 1e-6)
    return texture_on_plane(p.y() + 3 * hy, p.z(), seed + 1, false);
  return texture_on_plane(p.x() + hx, p.z(), seed + 2, false);
}

void build_view_tables(View& view, const Scenario& sc,
                       const std::function<Eigen::Vector3d(double, double)>& ray_of) {
  const double hx = sc.room_size_mm.x() / 2, hy = sc.room_size_mm.y() / 2,
               top = sc.room_size_mm.z();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  view.rays.resize(static_cast<std::size_t>(view.width) * view.height);
  view.room.create(view.height, view.width, CV_32F);
  view.floor_xy.create(view.height, view.width, CV_32FC2);
  const Eigen::Vector3d& c = view.centre_mm;
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      const Eigen::Vector3d d = ray_of(x, y);
      view.rays[static_cast<std::size_t>(y) * view.width + x] = d.cast<float>();
      // Nearest of floor, ceiling and the four walls along the ray.
      double t = std::numeric_limits<double>::infinity();
      auto consider = [&](double tt) {
        if (tt > 1e-6 && tt < t) t = tt;
      };
      if (d.z() != 0) consider(-c.z() / d.z()), consider((top - c.z()) / d.z());
      if (d.x() != 0) consider((hx - c.x()) / d.x()), consider((-hx - c.x()) / d.x());
      if (d.y() != 0) consider((hy - c.y()) / d.y()), consider((-hy - c.y()) / d.y());
      Eigen::Vector3d p = c + t * d;
      float grey = 30.0f;  // ceiling, or outside a camera placed outside the room
      cv::Vec2f floor_point(nan, nan);
      if (std::isfinite(t) && std::abs(p.z()) < 1e-3 * std::max(1.0, t)) {
        p.z() = 0;
        grey = room_texture(p, sc);
        floor_point = {static_cast<float>(p.x()), static_cast<float>(p.y())};
      } else if (std::isfinite(t) && p.z() < top - 1e-3) {
        if (std::abs(std::abs(p.x()) - hx) < 1e-3)
          p.x() = std::copysign(hx, p.x());
        else
          p.y() = std::copysign(hy, p.y());
        grey = room_texture(p, sc);
      }
      view.room.at<float>(y, x) = grey;
      view.floor_xy.at<cv::Vec2f>(y, x) = floor_point;
    }
  }
}

}  // namespace syncap::sim
