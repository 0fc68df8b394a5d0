#include "render.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "disc_coverage.hpp"
#include "mesh_raster.hpp"
#include "reflections.hpp"

namespace syncap::sim {
namespace {

// Pixel rectangle (inclusive) an ellipsoid can cover: projection of its bounding box corners.
// A corner behind the camera makes the box the whole image.
cv::Rect ellipsoid_box(const View& view, const Ellipsoid& e) {
  double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
  for (int i = 0; i < 8; ++i) {
    Eigen::Vector3d corner = e.centre_mm;
    for (int a = 0; a < 3; ++a)
      corner += ((i >> a) & 1 ? 1.0 : -1.0) * e.radii_mm[a] * e.axes.col(a);
    const auto p = view.project(corner);
    if (!p) return {0, 0, view.width, view.height};
    x0 = std::min(x0, p->x()), x1 = std::max(x1, p->x());
    y0 = std::min(y0, p->y()), y1 = std::max(y1, p->y());
  }
  // A margin of 2 px covers distortion between corners.
  const cv::Rect box(
      cv::Point(static_cast<int>(std::floor(x0)) - 2, static_cast<int>(std::floor(y0)) - 2),
      cv::Point(static_cast<int>(std::ceil(x1)) + 3, static_cast<int>(std::ceil(y1)) + 3));
  return box & cv::Rect(0, 0, view.width, view.height);
}

// The clothes' pattern, in [0, 1]: three plane waves through the segment's own frame (a solid
// texture, so it varies in both directions on the surface and a matched patch is located along
// and across a limb; the stripes it replaced, along the axis only, were not). Three different
// wavelengths (60, 85, 120 mm: 10-20 px at the ring's 6 mm a pixel) make the pattern repeat
// rarely along a scan line, and are smooth at the pixel, so sampling each pixel at its centre
// does not alias.
double clothes_pattern(const Eigen::Vector3d& local, int index) {
  static const Eigen::Vector3d waves[3] = {
      {0.081, 0.027, 0.061}, {-0.030, 0.055, -0.040}, {0.017, -0.034, -0.037}};  // rad/mm
  double sum = 0.0;
  for (int w = 0; w < 3; ++w) sum += std::sin(waves[w].dot(local) + index * (1.7 + 0.9 * w));
  return std::clamp(0.5 + sum / 4.0, 0.0, 1.0);
}

// The clothes' pattern and Lambert shading: texture for matching, shape for the eye.
float body_shade(const Ellipsoid& e, const Eigen::Vector3d& hit, const Eigen::Vector3d& light_dir,
                 int index) {
  const Eigen::Vector3d local = e.axes.transpose() * (hit - e.centre_mm);
  const Eigen::Vector3d normal =
      (e.axes * local.cwiseQuotient(e.radii_mm.cwiseProduct(e.radii_mm))).normalized();
  const double lambert = std::max(0.0, -normal.dot(light_dir));
  // 20-100 DN before shading (a typical swing of +-24 DN: printed cloth, 2.4 times the stripes'
  // contrast); at most 120 DN lit, below the marker threshold (128 DN), or the pattern's bright
  // round spots would be taken for markers.
  return static_cast<float>((5.0 + 95.0 * clothes_pattern(local, index)) * (0.45 + 0.75 * lambert));
}

// An ellipsoid in the frame that makes it a unit sphere: rays from a fixed origin (the camera
// centre) or in a fixed direction (towards the light) then cost a 3x3 product and a quadratic.
struct UnitFrame {
  Eigen::Matrix3d to_unit;  // diag(1/r) A^T
  Eigen::Vector3d centre;

  explicit UnitFrame(const Ellipsoid& e)
      : to_unit(e.radii_mm.cwiseInverse().asDiagonal() * e.axes.transpose()), centre(e.centre_mm) {}

  // Nearest t > 0 with |o + t d| = 1, for o, d already in the unit frame.
  static std::optional<double> hit(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double c) {
    const double a = d.squaredNorm(), b = o.dot(d);
    const double disc = b * b - a * c;
    if (disc < 0) return std::nullopt;
    const double root = std::sqrt(disc);
    double t = (-b - root) / a;
    if (t <= 1e-9) t = (-b + root) / a;
    if (t <= 1e-9) return std::nullopt;
    return t;
  }
};

// Rays from one origin (the camera centre) against one ellipsoid: the origin's part of the
// quadratic is computed once, not once a pixel.
struct RaysFromOrigin {
  UnitFrame unit;
  Eigen::Vector3d o;  // the origin in the unit frame
  double c;           // |o|^2 - 1

  RaysFromOrigin(const Ellipsoid& e, const Eigen::Vector3d& origin)
      : unit(e), o(unit.to_unit * (origin - unit.centre)), c(o.squaredNorm() - 1.0) {}
  std::optional<double> hit(const Eigen::Vector3d& dir) const {
    return UnitFrame::hit(o, unit.to_unit * dir, c);
  }
};

// Returns the distance to the body along each pixel's ray (infinity where it misses).
cv::Mat paint_body(const View& view, const FrameContent& content, cv::Mat& radiance,
                   cv::Mat& mask) {
  cv::Mat depth(view.height, view.width, CV_32F,
                cv::Scalar(std::numeric_limits<float>::infinity()));
  for (std::size_t i = 0; i < content.body.size(); ++i) {
    const Ellipsoid& e = content.body[i];
    const cv::Rect box = ellipsoid_box(view, e);
    const RaysFromOrigin rays(e, view.centre_mm);
    for (int y = box.y; y < box.y + box.height; ++y) {
      for (int x = box.x; x < box.x + box.width; ++x) {
        const Eigen::Vector3d dir =
            view.rays[static_cast<std::size_t>(y) * view.width + x].cast<double>();
        const auto t = rays.hit(dir);
        if (!t || *t >= depth.at<float>(y, x)) continue;
        depth.at<float>(y, x) = static_cast<float>(*t);
        radiance.at<float>(y, x) =
            static_cast<float>(content.body_brightness) *
            body_shade(e, view.centre_mm + *t * dir, content.light_dir, static_cast<int>(i));
        mask.at<uint8_t>(y, x) = 255;
      }
    }
  }
  return depth;
}

// The skinned person over what is painted (nearer than `depth`): the clothes' pattern at the
// hit's rest place on the skin, Lambert on the interpolated normal. Returns the merged depth.
cv::Mat paint_mesh(const View& view, const FrameContent& content, cv::Mat depth, cv::Mat& radiance,
                   cv::Mat& mask) {
  const Mesh& mesh = content.body_mesh;
  MeshFragments hits = rasterize_mesh(view, mesh, depth);
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      const int k = hits.triangle.at<int>(y, x);
      if (k < 0) continue;
      const Eigen::Vector3d dir =
          view.rays[static_cast<std::size_t>(y) * view.width + x].cast<double>();
      const Eigen::Vector3d w =
          barycentric(mesh, k, view.centre_mm + double(hits.depth.at<float>(y, x)) * dir);
      const Eigen::Vector3i& t = mesh.triangles[static_cast<std::size_t>(k)];
      Eigen::Vector3d normal = Eigen::Vector3d::Zero(), rest = Eigen::Vector3d::Zero();
      for (int i = 0; i < 3; ++i) {
        normal += w[i] * mesh.normals[size_t(t[i])];
        rest += w[i] * mesh.texture_mm[size_t(t[i])];
      }
      const double lambert = std::max(0.0, -normal.normalized().dot(content.light_dir));
      const double pattern = clothes_pattern(rest, mesh.triangle_part[static_cast<std::size_t>(k)]);
      radiance.at<float>(y, x) = static_cast<float>(
          content.body_brightness * (5.0 + 95.0 * pattern) * (0.45 + 0.75 * lambert));
      mask.at<uint8_t>(y, x) = 255;
    }
  }
  return hits.depth;
}

// Floor pixels in the skinned person's shadow are darkened (not those the person covers).
void paint_mesh_shadow(const View& view, const FrameContent& content, cv::Mat& radiance,
                       const cv::Mat& mask) {
  if (!view.floor_xy.data) return;
  const FloorShadow shadow = mesh_floor_shadow(content.body_mesh, content.light_dir);
  if (shadow.cells.empty()) return;
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      const cv::Vec2f f = view.floor_xy.at<cv::Vec2f>(y, x);
      if (std::isnan(f[0]) || mask.at<uint8_t>(y, x) || !shadow.shadowed(f[0], f[1])) continue;
      radiance.at<float>(y, x) *= static_cast<float>(1.0 - content.shadow_darkening);
    }
  }
}

// Takes away the coverage of pixels where the body is nearer than the sphere's front; returns the
// share of the coverage left.
double hide_behind_body(const View& view, const Sphere& s, const cv::Rect& box,
                        const cv::Mat& body_depth, cv::Mat& coverage) {
  if (body_depth.empty()) return 1.0;
  const double front = (s.centre_mm - view.centre_mm).norm() - s.radius_mm;
  double before = 0, after = 0;
  for (int y = 0; y < box.height; ++y) {
    for (int x = 0; x < box.width; ++x) {
      float& c = coverage.at<float>(y, x);
      before += c;
      if (body_depth.at<float>(box.y + y, box.x + x) < front) c = 0;
      after += c;
    }
  }
  return before > 0 ? after / before : 1.0;
}

// Floor points whose path to the light is blocked by the body are darkened.
void paint_shadow(const View& view, const FrameContent& content, cv::Mat& radiance,
                  const cv::Mat& mask) {
  if (content.body.empty() || !view.floor_xy.data) return;
  const Eigen::Vector3d to_light = -content.light_dir.normalized();
  // Floor rectangle the shadow can fall in: every ellipsoid's box corners cast along the light.
  double fx0 = 1e18, fy0 = 1e18, fx1 = -1e18, fy1 = -1e18;
  for (const auto& e : content.body) {
    const double reach = e.radii_mm.maxCoeff();
    const double t = e.centre_mm.z() / to_light.z();
    const Eigen::Vector3d foot = e.centre_mm - t * to_light;
    const double spread = reach * (1 + std::abs(1 / to_light.z()));
    fx0 = std::min(fx0, foot.x() - spread), fx1 = std::max(fx1, foot.x() + spread);
    fy0 = std::min(fy0, foot.y() - spread), fy1 = std::max(fy1, foot.y() + spread);
  }
  double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
  for (int i = 0; i < 4; ++i) {
    const auto p = view.project({i & 1 ? fx1 : fx0, i & 2 ? fy1 : fy0, 0.0});
    if (!p) {  // a corner this camera cannot project: look at the whole image
      x0 = y0 = 0, x1 = view.width, y1 = view.height;
      break;
    }
    x0 = std::min(x0, p->x()), x1 = std::max(x1, p->x()), y0 = std::min(y0, p->y()),
    y1 = std::max(y1, p->y());
  }
  const cv::Rect box = cv::Rect(cv::Point(static_cast<int>(x0) - 2, static_cast<int>(y0) - 2),
                                cv::Point(static_cast<int>(x1) + 3, static_cast<int>(y1) + 3)) &
                       cv::Rect(0, 0, view.width, view.height);
  // Rays towards the light share their direction: per ellipsoid, the floor point enters linearly.
  struct ShadowCaster {
    Eigen::Vector3d d, along_x, along_y, offset;
  };
  std::vector<ShadowCaster> casters;
  for (const auto& e : content.body) {
    const UnitFrame unit(e);
    casters.push_back({unit.to_unit * to_light, unit.to_unit.col(0), unit.to_unit.col(1),
                       -(unit.to_unit * unit.centre)});
  }
  for (int y = box.y; y < box.y + box.height; ++y) {
    for (int x = box.x; x < box.x + box.width; ++x) {
      const cv::Vec2f f = view.floor_xy.at<cv::Vec2f>(y, x);
      if (std::isnan(f[0]) || mask.at<uint8_t>(y, x)) continue;
      for (const auto& caster : casters) {
        const Eigen::Vector3d o = f[0] * caster.along_x + f[1] * caster.along_y + caster.offset;
        if (UnitFrame::hit(o, caster.d, o.squaredNorm() - 1.0)) {
          radiance.at<float>(y, x) *= static_cast<float>(1.0 - content.shadow_darkening);
          break;
        }
      }
    }
  }
}

// Paints a sphere as a disc of exactly covered pixels, averaged over its exposure path.
SphereTruth paint_sphere(const View& view, const Sphere& s, const cv::Mat& body_depth,
                         cv::Mat& radiance) {
  SphereTruth truth;
  const auto centre = view.project(s.centre_mm);
  if (!centre) return truth;
  const double depth = (s.centre_mm - view.centre_mm).dot(view.axis);
  truth.pixel = *centre;
  truth.radius_px = view.focal_px * s.radius_mm / depth;
  truth.visible = centre->x() >= -0.5 && centre->y() >= -0.5 && centre->x() < view.width - 0.5 &&
                  centre->y() < view.height - 0.5;
  std::vector<Eigen::Vector2d> positions;
  for (const auto& p : s.exposure_path_mm) {
    if (auto px = view.project(p)) positions.push_back(*px);
  }
  if (positions.empty()) positions.push_back(*centre);
  // Only the rectangle the disc can touch is worked on.
  double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
  for (const auto& p : positions) {
    x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x()), y0 = std::min(y0, p.y()),
    y1 = std::max(y1, p.y());
  }
  const double r = truth.radius_px + 1;
  const cv::Rect box = cv::Rect(cv::Point(static_cast<int>(std::floor(x0 - r)),
                                          static_cast<int>(std::floor(y0 - r))),
                                cv::Point(static_cast<int>(std::ceil(x1 + r)) + 1,
                                          static_cast<int>(std::ceil(y1 + r)) + 1)) &
                       cv::Rect(0, 0, view.width, view.height);
  if (box.empty()) return truth;
  const double share = 1.0 / static_cast<double>(positions.size());
  cv::Mat coverage(box.size(), CV_32F, cv::Scalar(0));
  for (const auto& p : positions) {
    for_each_covered_pixel(
        p.x() - box.x, p.y() - box.y, truth.radius_px, box.width, box.height,
        [&](int x, int y, double a) { coverage.at<float>(y, x) += static_cast<float>(a * share); });
  }
  if (hide_behind_body(view, s, box, body_depth, coverage) < kVisibleShare) truth.visible = false;
  // The target hides what is behind it: blend towards its brightness by coverage.
  cv::Mat patch = radiance(box);
  patch += coverage.mul(cv::Scalar(s.brightness_dn) - patch);
  return truth;
}

// Sensor noise: a window of a fixed pool of standard normal samples at a random offset per
// camera and frame. Drawing 300 000 fresh samples a frame per camera was a fifth of the render
// time; a window of a 16 MB pool keeps each frame's noise white and Gaussian, and a pixel's
// values over frames independent (different pool elements) unless two offsets coincide.
void add_noise(cv::Mat& radiance, double sigma, uint64_t seed) {
  static const cv::Mat pool = [] {
    cv::Mat p(1, 1 << 22, CV_32F);
    cv::RNG(0x5eedf00d).fill(p, cv::RNG::NORMAL, 0.0, 1.0);
    return p;
  }();
  const int n = static_cast<int>(radiance.total());
  CV_Assert(radiance.isContinuous() && n < pool.cols);
  cv::RNG rng(seed);
  const int offset = rng.uniform(0, pool.cols - n);
  const cv::Mat window = pool.colRange(offset, offset + n).reshape(1, radiance.rows);
  cv::scaleAdd(window, sigma, radiance, radiance);
}

}  // namespace

std::optional<double> ray_ellipsoid(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                    const Ellipsoid& e) {
  return RaysFromOrigin(e, origin).hit(dir);
}

RenderedView render_view(const View& view, const FrameContent& content, const ImageSpec& image,
                         uint64_t noise_seed) {
  RenderedView out;
  cv::Mat radiance = content.room_background
                         ? view.room.clone()
                         : cv::Mat(view.height, view.width, CV_32F, cv::Scalar(image.dark_dn));
  out.mask = cv::Mat(view.height, view.width, CV_8UC1, cv::Scalar(0));
  cv::Mat body_depth;
  if (!content.body.empty()) {
    body_depth = paint_body(view, content, radiance, out.mask);
    paint_shadow(view, content, radiance, out.mask);
  }
  if (!content.body_mesh.empty()) {
    body_depth = paint_mesh(view, content, body_depth, radiance, out.mask);
    paint_mesh_shadow(view, content, radiance, out.mask);
  }
  for (const auto& s : content.spheres)
    out.spheres.push_back(paint_sphere(view, s, body_depth, radiance));
  paint_discs(reflection_discs(content.reflections, content.reflection_seed, view.camera,
                               view.width, view.height),
              radiance);
  radiance *= content.gain;
  if (image.noise_sigma_dn > 0) add_noise(radiance, image.noise_sigma_dn, noise_seed);
  radiance.convertTo(out.image, CV_8U);  // rounds to nearest and saturates at 0 and 255
  return out;
}

cv::Mat silhouette_brute_force(const View& view, const std::vector<Ellipsoid>& body) {
  cv::Mat mask(view.height, view.width, CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      const Eigen::Vector3d dir =
          view.rays[static_cast<std::size_t>(y) * view.width + x].cast<double>();
      for (const auto& e : body) {
        if (ray_ellipsoid(view.centre_mm, dir, e)) {
          mask.at<uint8_t>(y, x) = 255;
          break;
        }
      }
    }
  }
  return mask;
}

}  // namespace syncap::sim
