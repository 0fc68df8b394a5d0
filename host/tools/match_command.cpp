#include "match_command.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "hull/polyhedral_hull.hpp"
#include "hull/views_io.hpp"
#include "subcommand.hpp"
#include "surface/hull_consistency.hpp"
#include "surface/point_files.hpp"
#include "surface/surface_matcher.hpp"
#include "surface/surface_mesh.hpp"
#include "syncap/cli/options.hpp"
#include "util/printf_string.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;
namespace ms = surface;

constexpr const char* kErrorPrefix = "syncap match: ";

struct MatchArgs {
  std::string cameras;
  std::string images;
  std::string masks;
  std::string hull;
  std::string out;
  int threshold = -1;
  bool largest = false;
  bool sweep_only = false;
  bool no_mesh = false;
  ms::SurfaceMatchingOptions options;
};

constexpr const char* kDescription =
    "usage: syncap match --calibration FILE|DIR --images DIR --masks DIR|--hull FILE --out-dir "
    "DIR\n"
    "The surface of the object the cameras see, by geometrically constrained cross-correlation\n"
    "(GC3) along each seed's 3D scan line and multi-image least-squares matching constrained\n"
    "to one 3D point (docs/design/matching.md). Seeds: a grid in each image on the visual hull "
    "(built\n"
    "from the masks with the polyhedral method, or read from --hull), each matched from the\n"
    "view that faces it best in the views whose facet-ID image sees it. Cameras as for\n"
    "`syncap hull`; images: the image files of DIR in name order, one per camera (8-bit grey\n"
    "or colour). Writes DIR/points.ply (x y z, normal, sigma along the normal),\n"
    "DIR/points.csv (every point with its ray, sigmas, SNCC, sigma0, views) and\n"
    "DIR/surface.ply (the points meshed by CGAL's advancing front, the hull's surface filling\n"
    "the gaps matching left); prints the\n"
    "seeds, the rejections by reason, the time, each camera's points and, with masks, how many\n"
    "points lie inside the visual hull (a warning on stderr for those that do not).\n";

constexpr const char* kFooter =
    "Exit status: 0 done, 1 no point matched, 2 usage error or bad input (named: file, camera).";

void add_match_options(CLI::App& app, MatchArgs& a) {
  ms::SurfaceMatchingOptions& o = a.options;
  app.add_option("--calibration", a.cameras,
                 "cameras.json, an OpenCV-style .yaml/.yml/.json, or a folder of *.pa projection "
                 "matrices")
      ->option_text("FILE|DIR")
      ->required();
  app.add_option("--images", a.images, "the folder of images, one per camera in name order")
      ->option_text("DIR")
      ->required();
  auto* masks = app.add_option("--masks", a.masks,
                               "the folder of masks, one per camera in name order (the hull)")
                    ->option_text("DIR");
  auto* hull = app.add_option("--hull", a.hull, "the object's hull mesh (PLY or OBJ) instead")
                   ->option_text("FILE");
  masks->excludes(hull);
  app.add_option("--out-dir", a.out, "the folder for points.ply and points.csv (created)")
      ->option_text("DIR")
      ->required();
  cli::add_checked(app, "--threshold", a.threshold, "N", cli::whole_in<int>(0, 254),
                   "mask foreground is grey > N; default: any non-zero pixel");
  app.add_flag("--largest", a.largest, "keep only each mask's largest foreground component");
  cli::add_checked(
      app, "--spacing", o.seed_spacing_px, "PX", cli::number_in(1, 100),
      "seed grid spacing in each image (default " + cli::number_text(o.seed_spacing_px) + ")");
  cli::add_checked(
      app, "--half-window", o.half_window, "N", cli::whole_in<int>(1, 15),
      "the window is 2N+1 pixels square (default " + std::to_string(o.half_window) + ")");
  cli::add_checked(app, "--search-depth", o.search_depth, "LENGTH", cli::number_in(0, 1e6),
                   "the scan line reaches this far behind the hull, in object units (default:\n"
                   "6 % of the hull's bounding-box diagonal, 120 mm for a person of 2 m)");
  cli::add_checked(app, "--search-front", o.search_front, "LENGTH", cli::number_in(0, 1e6),
                   "and starts this far in front of it (default: 0.75 % of the diagonal)");
  cli::add_checked(
      app, "--min-sncc", o.min_sncc, "R", cli::number_in(-1, 1),
      "the best SNCC peak's least value (default " + cli::number_text(o.min_sncc) + ")");
  cli::add_checked(app, "--min-views", o.min_search_views, "N", cli::whole_in<int>(1, 99),
                   "search images a seed needs besides its reference (default " +
                       std::to_string(o.min_search_views) + ")");
  cli::add_checked(app, "--max-angle", o.max_view_angle_deg, "DEG", cli::number_in(1, 89),
                   "largest angle between the surface normal and a view's direction (default " +
                       cli::number_text(o.max_view_angle_deg) + ")");
  app.add_flag("--no-mesh", a.no_mesh, "write no surface.ply (the points only)");
  app.add_flag("--sweep-only", a.sweep_only,
               "no least squares: each point is the GC3 peak (the NCC sweep baseline)");
}

std::optional<int> parse_match_args(std::span<const std::string> args, MatchArgs& a,
                                    std::ostream& out, std::ostream& err) {
  cli::App app("syncap match", kDescription, kFooter);
  app.deprecated_name("--cameras", "--calibration");
  app.deprecated_name("--out", "--out-dir");
  add_match_options(app, a);
  if (const auto status = cli::parse(app, args, out, err)) return status;
  if (a.masks.empty() && a.hull.empty()) {
    err << kErrorPrefix << "give --masks DIR (the hull is built from them) or --hull FILE\n";
    return kExitUsage;
  }
  a.options.least_squares = !a.sweep_only;
  return std::nullopt;
}

// The views' cameras (and masks, when given) as the hull reads them.
std::vector<hull::HullView> read_hull_views(const MatchArgs& a) {
  hull::ViewFiles files;
  if (a.threshold >= 0) files.threshold = a.threshold;
  files.largest_only = a.largest;
  if (a.masks.empty()) return hull::read_camera_views(a.cameras, a.images);  // the hull's a file
  return hull::read_views(a.cameras, a.masks, files);
}

// An image resampled into the pixels of the camera without its OpenCV lens.
cv::Mat ideal_image(const sensor::OpenCvLens& lens, const cv::Mat& image, int interpolation) {
  cv::Matx33d k;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) k(r, c) = lens.camera_matrix(r, c);
  }
  const cv::Vec<double, 5> d(lens.distortion.data());
  cv::Mat map_x, map_y, ideal;
  cv::initUndistortRectifyMap(k, d, cv::noArray(), k, image.size(), CV_32FC1, map_x, map_y);
  cv::remap(image, ideal, map_x, map_y, interpolation);
  return ideal;
}

std::vector<ms::MatchingView> read_images(const MatchArgs& a,
                                          const std::vector<hull::HullView>& cameras) {
  const std::vector<fs::path> files = hull::mask_files(a.images);
  if (files.size() != cameras.size())
    throw hull::HullError(util::printf_string("%s: %zu image(s) for %zu camera(s)",
                                              a.images.c_str(), files.size(), cameras.size()));
  std::vector<ms::MatchingView> views;
  for (std::size_t i = 0; i < files.size(); ++i) {
    cv::Mat image = cv::imread(files[i].string(), cv::IMREAD_UNCHANGED);
    if (image.empty() || image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
      throw hull::HullError(files[i].string() + ": not a readable 8-bit grey or colour image");
    sensor::CameraModel camera = cameras[i].camera;
    if (image.cols != camera.sensor.width_px || image.rows != camera.sensor.height_px)
      throw hull::HullError(util::printf_string(
          "%s: image is %dx%d, camera %d's %dx%d", files[i].string().c_str(), image.cols,
          image.rows, camera.id, camera.sensor.width_px, camera.sensor.height_px));
    cv::Mat mask = a.masks.empty() ? cv::Mat() : cameras[i].mask;
    if (camera.opencv_lens) {  // the matcher's scan lines are straight: the ideal camera's pixels
      image = ideal_image(*camera.opencv_lens, image, cv::INTER_LINEAR);
      if (!mask.empty()) mask = ideal_image(*camera.opencv_lens, mask, cv::INTER_NEAREST);
      camera.opencv_lens.reset();
    }
    views.push_back(ms::make_matching_view(camera, image, mask));
  }
  return views;
}

// Each reference view's points and their median sigma.
void print_views(const ms::SurfaceMatchingResult& r, const std::vector<ms::MatchingView>& views,
                 std::ostream& out) {
  std::vector<std::vector<double>> sigmas(views.size());
  for (const auto& p : r.points)
    sigmas[static_cast<std::size_t>(p.reference)].push_back(p.sigma_normal_mm);
  for (std::size_t i = 0; i < views.size(); ++i) {
    auto& s = sigmas[i];
    std::ranges::sort(s);
    out << util::printf_string("camera %d: %zu points, median sigma %.4g\n", views[i].camera.id,
                               s.size(), s.empty() ? 0.0 : s[s.size() / 2]);
  }
}

// The plausibility check against the masks (the visual hull); false when points fall outside.
bool print_consistency(const ms::SurfaceMatchingResult& r,
                       const std::vector<hull::HullView>& hull_views, std::ostream& out) {
  std::vector<sensor::CameraModel> cameras;
  std::vector<cv::Mat> masks;
  for (const auto& v : hull_views) cameras.push_back(v.camera), masks.push_back(v.mask);
  const ms::HullConsistency c = ms::check_against_masks(r.points, cameras, masks);
  out << util::printf_string(
      "inside the visual hull (every mask) within 3 sigma and 0.71 px: %zu of %zu",
      c.points - c.outside, c.points);
  if (c.outside > 0) out << util::printf_string(" (worst %.2f px beyond)", c.worst_excess_px);
  out << '\n';
  return c.outside == 0;
}

// The matched points meshed with the hull filling the gaps (surface.ply).
void write_surface(const ms::SurfaceMatchingResult& r, const hull::Mesh& hull_mesh,
                   const fs::path& file, std::ostream& out) {
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : r.points) points.push_back(p.point);
  ms::SurfaceMeshStats stats;
  const hull::Mesh surface = ms::mesh_surface(points, hull_mesh, {}, &stats);
  hull::write_mesh(file, surface);
  const hull::MeshReport report = hull::check_mesh(surface, false);
  out << util::printf_string(
      "surface mesh: %zu vertices (%zu matched, %zu from the hull), %zu triangles, spacing "
      "%.4g, %.3f s; %s\n",
      stats.matched + stats.from_hull, stats.matched, stats.from_hull, report.faces, stats.spacing,
      stats.seconds, report.summary().c_str());
}

void print_result(const ms::SurfaceMatchingResult& r, double seconds, std::ostream& out) {
  out << util::printf_string(
      "scan line: %.4g in front of the hull to %.4g behind it; visibility tolerance %.4g\n",
      r.search_front, r.search_depth, r.visibility_tolerance);
  out << util::printf_string("seeds: %zu, points: %zu\n", r.seeds, r.points.size());
  for (std::size_t i = 0; i < r.rejected.size(); ++i) {
    out << util::printf_string("rejected, %s: %zu\n",
                               ms::rejection_name(static_cast<ms::Rejection>(i)), r.rejected[i]);
  }
  std::vector<double> sigmas;
  for (const auto& p : r.points) sigmas.push_back(p.sigma_normal_mm);
  if (!sigmas.empty()) {
    std::ranges::sort(sigmas);
    out << util::printf_string("sigma along the normal: median %.4g, 90 %% %.4g\n",
                               sigmas[sigmas.size() / 2], sigmas[sigmas.size() * 9 / 10]);
  }
  out << util::printf_string(
      "time: %.3f s (facet-ID images and seeds %.3f s, GC3 %.3f s, least squares %.3f s); "
      "%.0f points/s\n",
      seconds, r.visibility_seconds, r.sweep_seconds, r.lsm_seconds,
      seconds > 0 ? static_cast<double>(r.points.size()) / seconds : 0.0);
}

}  // namespace

int match_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  MatchArgs a;
  if (const auto status = parse_match_args(args, a, out, err)) return *status;
  using Clock = std::chrono::steady_clock;
  try {
    const std::vector<hull::HullView> hull_views = read_hull_views(a);
    const std::vector<ms::MatchingView> views = read_images(a, hull_views);
    const hull::Mesh mesh =
        a.hull.empty() ? hull::polyhedral_visual_hull(hull_views) : hull::read_mesh(a.hull);
    const Clock::time_point start = Clock::now();
    const ms::SurfaceMatchingResult result =
        ms::match_surface(views, ms::facets_of(hull::triangles_of(mesh)), a.options);
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    fs::create_directories(a.out);
    ms::write_points_ply(fs::path(a.out) / "points.ply", result.points);
    ms::write_points_csv(fs::path(a.out) / "points.csv", result.points, ms::camera_ids(views));
    print_result(result, seconds, out);
    if (!a.no_mesh) write_surface(result, mesh, fs::path(a.out) / "surface.ply", out);
    print_views(result, views, out);
    if (!a.masks.empty() && !print_consistency(result, hull_views, out))
      err << kErrorPrefix
          << "warning: points outside the visual hull (implausible matches, or "
             "cameras that disagree with the images)\n";
    if (result.points.empty()) {
      err << kErrorPrefix << "no point matched\n";
      return kExitReportedErrors;
    }
    return kExitOk;
  } catch (const hull::HullError& e) {
    err << kErrorPrefix << e.what() << '\n';
  } catch (const std::exception& e) {
    err << kErrorPrefix << a.out << ": " << e.what() << '\n';
  }
  return kExitUsage;
}

}  // namespace syncap::tools
