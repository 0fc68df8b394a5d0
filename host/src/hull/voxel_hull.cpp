#include "hull/voxel_hull.hpp"

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "hull/capture_volume.hpp"
#include "sensor/opencv_camera.hpp"

namespace syncap::hull {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Pixels around a block's projected corners that still count: the rasterized outline is within
// a pixel of the silhouette's.
constexpr double kBlockMarginPx = 2.0;

// The camera's projection without distortion, a 3x4 matrix into ideal pixels.
Eigen::Matrix<double, 3, 4> linear_projection(const sensor::CameraModel& camera) {
  const sensor::OpenCvCamera cv_camera = sensor::opencv_from_camera(camera);
  cv::Matx33d r;
  cv::Rodrigues(cv_camera.rvec, r);
  Eigen::Matrix<double, 3, 4> rt;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) rt(i, j) = r(i, j);
    rt(i, 3) = cv_camera.tvec[i];
  }
  return Eigen::Matrix3d(Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
             cv_camera.camera_matrix.val)) *
         rt;
}

// One view's mask in ideal (distortion-free) pixels with its integral image, so that every
// sample projects through a 3x4 matrix. A camera with distortion gets its silhouette's vertices
// corrected into ideal pixels (the explicit direction of the camera model: back_project) and
// rasterized on a canvas a margin larger than the image, since correcting moves the outline
// outwards (barrel) or inwards; projecting every sample through the model instead inverts the
// distortion by Newton's method, and made the hull of 6 distorted views 5x slower.
class ViewSampler {
 public:
  explicit ViewSampler(const HullView& view) : rt_(linear_projection(view.camera)) {
    const cv::Size image(view.camera.sensor.width_px, view.camera.sensor.height_px);
    if (!view.camera.has_distortion()) {
      mask_ = view.mask.empty() ? rasterize(view.silhouette, image) : view.mask;
    } else {
      offset_ = std::max(image.width, image.height) / 8;
      mask_ = rasterize(ideal_silhouette(view),
                        {image.width + 2 * offset_, image.height + 2 * offset_});
    }
    cv::integral(mask_ != 0, integral_, CV_32S);  // counts 255s: divide by 255 below
  }

  // Canvas pixel of a point in front of the camera.
  bool pixel(const Eigen::Vector3d& x, Eigen::Vector2d* out) const {
    const Eigen::Vector3d h = rt_ * x.homogeneous();
    if (h.z() <= 0.0) return false;
    *out = h.head<2>() / h.z() + Eigen::Vector2d::Constant(offset_);
    return true;
  }

  bool foreground(const Eigen::Vector3d& x) const {
    Eigen::Vector2d p;
    if (!pixel(x, &p)) return false;
    const int u = static_cast<int>(std::lround(p.x())), v = static_cast<int>(std::lround(p.y()));
    return u >= 0 && v >= 0 && u < mask_.cols && v < mask_.rows && mask_.at<uint8_t>(v, u) != 0;
  }

  // Of the box [lo, hi]: -1 wholly background, 1 wholly foreground, 0 mixed or unknown.
  int classify(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
    Eigen::Vector2d min = Eigen::Vector2d::Constant(1e300), max = -min;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d x((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(),
                              (c & 4) ? hi.z() : lo.z());
      Eigen::Vector2d p;
      if (!pixel(x, &p)) return 0;
      min = min.cwiseMin(p);
      max = max.cwiseMax(p);
    }
    const int x0 = static_cast<int>(std::floor(min.x() - kBlockMarginPx));
    const int y0 = static_cast<int>(std::floor(min.y() - kBlockMarginPx));
    const int x1 = static_cast<int>(std::ceil(max.x() + kBlockMarginPx));
    const int y1 = static_cast<int>(std::ceil(max.y() + kBlockMarginPx));
    const int cx0 = std::max(x0, 0), cy0 = std::max(y0, 0);
    const int cx1 = std::min(x1, mask_.cols - 1), cy1 = std::min(y1, mask_.rows - 1);
    if (cx0 > cx1 || cy0 > cy1) return -1;
    const long count = static_cast<long>(integral_.at<int>(cy1 + 1, cx1 + 1)) -
                       integral_.at<int>(cy0, cx1 + 1) - integral_.at<int>(cy1 + 1, cx0) +
                       integral_.at<int>(cy0, cx0);
    if (count == 0) return -1;
    const bool clipped = cx0 != x0 || cy0 != y0 || cx1 != x1 || cy1 != y1;
    const long area = 255L * (cx1 - cx0 + 1) * (cy1 - cy0 + 1);
    return !clipped && count == area ? 1 : 0;
  }

 private:
  // The silhouette with every vertex moved to its ideal pixel on the canvas.
  Silhouette ideal_silhouette(const HullView& view) const {
    Silhouette ideal = view.silhouette;
    for (Contour& contour : ideal.contours) {
      for (Eigen::Vector2d& p : contour.points) {
        const sensor::Ray ray = view.camera.back_project(p);
        Eigen::Vector2d q;
        if (pixel(ray.origin + ray.direction, &q)) p = q;
      }
    }
    return ideal;
  }

  Eigen::Matrix<double, 3, 4> rt_;
  int offset_ = 0;  // the canvas' margin around the image [px]
  cv::Mat mask_, integral_;
};

// Grid points grid.min + cell * (i, j, k), i in [0, cells.x()], ...; 1 = inside every mask.
struct Grid {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  double cell = 1.0;
  Eigen::Vector3i cells = Eigen::Vector3i::Zero();
  std::vector<uint8_t> inside;

  Eigen::Vector3i nodes() const { return cells + Eigen::Vector3i::Ones(); }
  std::size_t index(int i, int j, int k) const {
    const Eigen::Vector3i n = nodes();
    return (static_cast<std::size_t>(k) * n.y() + j) * n.x() + i;
  }
  Eigen::Vector3d point(const Eigen::Vector3i& ijk) const {
    return min + cell * ijk.cast<double>();
  }
};

class Carver {
 public:
  Carver(const std::vector<ViewSampler>& views, Grid& grid) : views_(views), grid_(grid) {}

  void carve(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi) {
    bool all_inside = true;
    for (const ViewSampler& v : views_) {
      const int c = v.classify(grid_.point(lo), grid_.point(hi));
      if (c < 0) return;  // every point of the block is background in this view
      all_inside = all_inside && c > 0;
    }
    if (all_inside) return fill(lo, hi);
    const Eigen::Vector3i size = hi - lo;
    if (size.maxCoeff() <= 1) return test_points(lo, hi);
    const Eigen::Vector3i mid = lo + size / 2;
    for (int c = 0; c < 8; ++c) {
      Eigen::Vector3i a = lo, b = hi;
      for (int axis = 0; axis < 3; ++axis) {
        if (size[axis] == 0) {
          if (c & (1 << axis)) a[axis] = hi[axis] + 1;  // no second half on this axis
          continue;
        }
        if (c & (1 << axis)) {
          a[axis] = mid[axis] + 1;
        } else {
          b[axis] = mid[axis];
        }
      }
      if ((a.array() <= b.array()).all()) carve(a, b);
    }
  }

  std::size_t point_tests() const { return point_tests_; }

 private:
  void fill(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi) {
    for (int k = lo.z(); k <= hi.z(); ++k)
      for (int j = lo.y(); j <= hi.y(); ++j)
        for (int i = lo.x(); i <= hi.x(); ++i) grid_.inside[grid_.index(i, j, k)] = 1;
  }

  void test_points(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi) {
    for (int k = lo.z(); k <= hi.z(); ++k)
      for (int j = lo.y(); j <= hi.y(); ++j)
        for (int i = lo.x(); i <= hi.x(); ++i) {
          ++point_tests_;
          const Eigen::Vector3d x = grid_.point({i, j, k});
          const bool in =
              std::ranges::all_of(views_, [&](const auto& v) { return v.foreground(x); });
          grid_.inside[grid_.index(i, j, k)] = in ? 1 : 0;
        }
  }

  const std::vector<ViewSampler>& views_;
  Grid& grid_;
  std::size_t point_tests_ = 0;
};

// A grid over [min, max] with `resolution` cells along its longest side and one more cell of
// margin all round, so that the border points stay outside and the surface closes.
Grid make_grid(const Eigen::Vector3d& min, const Eigen::Vector3d& max, int resolution) {
  Grid g;
  g.cell = (max - min).maxCoeff() / resolution;
  g.min = min - Eigen::Vector3d::Constant(g.cell);
  for (int a = 0; a < 3; ++a) {
    g.cells[a] = static_cast<int>(std::ceil((max[a] - min[a]) / g.cell)) + 2;
  }
  const Eigen::Vector3i n = g.nodes();
  g.inside.assign(static_cast<std::size_t>(n.x()) * n.y() * n.z(), 0);
  return g;
}

std::size_t carve_grid(const std::vector<ViewSampler>& views, Grid& grid) {
  Carver carver(views, grid);
  carver.carve(Eigen::Vector3i::Ones(), grid.cells - Eigen::Vector3i::Ones());
  return carver.point_tests();
}

// The bounding box of the inside points, grown by one cell; false when there are none.
// The box of the coarse grid's cells that no view sees wholly as background (classify() is
// conservative: a block touching a foreground pixel, or not seen whole, counts), grown by a cell:
// a bound of the hull however thin its parts are. Sampling the coarse grid's points instead
// missed a person's legs between them, and the fine grid then cut them off.
bool occupied_bounds(const std::vector<ViewSampler>& views, const Grid& g, Eigen::Vector3d* min,
                     Eigen::Vector3d* max) {
  Eigen::Vector3i lo = g.nodes(), hi = -Eigen::Vector3i::Ones();
  for (int k = 0; k < g.cells.z(); ++k)
    for (int j = 0; j < g.cells.y(); ++j)
      for (int i = 0; i < g.cells.x(); ++i) {
        const Eigen::Vector3i ijk(i, j, k);
        const Eigen::Vector3d a = g.point(ijk), b = g.point(ijk + Eigen::Vector3i::Ones());
        if (std::ranges::any_of(views, [&](const ViewSampler& v) { return v.classify(a, b) < 0; }))
          continue;
        lo = lo.cwiseMin(ijk);
        hi = hi.cwiseMax(ijk + Eigen::Vector3i::Ones());
      }
  if (hi.x() < 0) return false;
  *min = g.point(lo - Eigen::Vector3i::Ones());
  *max = g.point(hi + Eigen::Vector3i::Ones());
  return true;
}

// Marching tetrahedra: each cell splits into the six tetrahedra around its main diagonal (the
// same split in every cell, so neighbouring cells' faces match and the surface has no cracks
// and no ambiguous cases); a tetrahedron with inside and outside corners gets a triangle or a
// quad through its crossing edges, facing the outside corners. Each vertex is where its edge
// leaves the hull, found by bisection against the masks (kRefineSteps halvings): the middle of
// the edge was up to half a cell off, which cost 0.05-0.1 of the reprojection IoU at 64 cells.
class Mesher {
 public:
  Mesher(const Grid& g, const std::vector<ViewSampler>& views) : g_(g), views_(views) {}

  Mesh run() {
    const Eigen::Vector3i c = g_.cells;
    for (int k = 0; k < c.z(); ++k)
      for (int j = 0; j < c.y(); ++j)
        for (int i = 0; i < c.x(); ++i) cell(i, j, k);
    return std::move(mesh_);
  }

 private:
  static constexpr std::array<std::array<int, 4>, 6> kTets = {
      {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}}};

  void cell(int i, int j, int k) {
    std::array<std::size_t, 8> id;
    int count = 0;
    for (int c = 0; c < 8; ++c) {
      id[c] = g_.index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
      count += g_.inside[id[c]];
    }
    if (count == 0 || count == 8) return;
    for (const auto& t : kTets) tet({id[t[0]], id[t[1]], id[t[2]], id[t[3]]});
  }

  void tet(const std::array<std::size_t, 4>& v) {
    std::array<std::size_t, 4> in, out;
    int n_in = 0, n_out = 0;
    for (std::size_t x : v) (g_.inside[x] ? in[n_in++] : out[n_out++]) = x;
    if (n_in == 0 || n_out == 0) return;
    Eigen::Vector3d in_centre = Eigen::Vector3d::Zero();
    for (int a = 0; a < n_in; ++a) in_centre += position(in[a]);
    in_centre /= n_in;
    if (n_in == 1 || n_out == 1) {
      const std::size_t lone = n_in == 1 ? in[0] : out[0];
      const auto& others = n_in == 1 ? out : in;
      face({vertex(lone, others[0]), vertex(lone, others[1]), vertex(lone, others[2])}, in_centre);
      return;
    }
    const Mesh::Vertex_index a = vertex(in[0], out[0]), b = vertex(in[0], out[1]),
                             c = vertex(in[1], out[1]), d = vertex(in[1], out[0]);
    face({a, b, c}, in_centre);
    face({a, c, d}, in_centre);
  }

  Eigen::Vector3d position(std::size_t node) const {
    const Eigen::Vector3i n = g_.nodes();
    const int i = static_cast<int>(node % n.x());
    const int j = static_cast<int>((node / n.x()) % n.y());
    const int k = static_cast<int>(node / (static_cast<std::size_t>(n.x()) * n.y()));
    return g_.point({i, j, k});
  }

  static constexpr int kRefineSteps = 5;
  // Kept off the grid points, so that no triangle collapses onto one.
  static constexpr double kMinFraction = 0.02;

  // The crossing of the edge from an inside point to an outside one.
  Eigen::Vector3d crossing(const Eigen::Vector3d& in, const Eigen::Vector3d& out) const {
    double lo = 0.0, hi = 1.0;  // fractions from `in`: lo inside, hi outside
    for (int step = 0; step < kRefineSteps; ++step) {
      const double mid = 0.5 * (lo + hi);
      const Eigen::Vector3d x = in + mid * (out - in);
      const bool inside =
          std::ranges::all_of(views_, [&](const ViewSampler& v) { return v.foreground(x); });
      (inside ? lo : hi) = mid;
    }
    const double t = std::clamp(0.5 * (lo + hi), kMinFraction, 1.0 - kMinFraction);
    return in + t * (out - in);
  }

  Mesh::Vertex_index vertex(std::size_t a, std::size_t b) {
    const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
    auto [it, added] = edges_.try_emplace(key);
    if (added) {
      const Eigen::Vector3d m =
          g_.inside[a] ? crossing(position(a), position(b)) : crossing(position(b), position(a));
      it->second = mesh_.add_vertex(Point3(m.x(), m.y(), m.z()));
    }
    return it->second;
  }

  void face(std::array<Mesh::Vertex_index, 3> f, const Eigen::Vector3d& in_centre) {
    const auto p = [&](int i) {
      const Point3& q = mesh_.point(f[i]);
      return Eigen::Vector3d(q.x(), q.y(), q.z());
    };
    if ((p(1) - p(0)).cross(p(2) - p(0)).dot(p(0) - in_centre) < 0) std::swap(f[1], f[2]);
    if (mesh_.add_face(f[0], f[1], f[2]) == Mesh::null_face())
      throw std::logic_error("marching tetrahedra: a non-manifold face");
  }

  const Grid& g_;
  const std::vector<ViewSampler>& views_;
  Mesh mesh_;
  std::unordered_map<std::uint64_t, Mesh::Vertex_index> edges_;
};

}  // namespace

Mesh voxel_visual_hull(const std::vector<HullView>& views, const VoxelOptions& voxel,
                       const HullOptions& options, VoxelStats* stats) {
  VoxelStats local;
  VoxelStats& s = stats != nullptr ? *stats : local;
  if (voxel.resolution < 2) throw std::invalid_argument("voxel resolution below 2");
  s.volume = checked_working_volume(views, options);
  const Clock::time_point start = Clock::now();
  std::vector<ViewSampler> samplers;
  for (const HullView& v : views) samplers.emplace_back(v);
  const Eigen::Vector3d r = Eigen::Vector3d::Constant(s.volume.radius);
  Eigen::Vector3d min = s.volume.centre - r, max = s.volume.centre + r;
  // Twice: the first box is a coarse cell too large all round, the second a 32nd of it.
  for (const int cells : {std::max(16, voxel.resolution / 8), 32}) {
    if (!occupied_bounds(samplers, make_grid(min, max, cells), &min, &max)) {
      throw EmptyHullError(
          "no part of the working volume is foreground in every view (empty hull; do the "
          "cameras and masks agree?)");
    }
  }
  Grid grid = make_grid(min, max, voxel.resolution);
  s.point_tests = carve_grid(samplers, grid);
  s.grid_min = grid.min;
  s.cell = grid.cell;
  s.cells = grid.cells;
  s.inside_points = static_cast<std::size_t>(std::ranges::count(grid.inside, 1));
  s.carve_seconds = seconds_since(start);
  if (s.inside_points == 0) {
    throw EmptyHullError(
        "no grid point is foreground in every view (empty hull; do the cameras and "
        "masks agree?)");
  }
  const Clock::time_point mesh_start = Clock::now();
  Mesh mesh = finished(Mesher(grid, samplers).run(), options);
  s.mesh_seconds = seconds_since(mesh_start);
  return mesh;
}

}  // namespace syncap::hull
