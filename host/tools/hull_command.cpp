#include "hull_command.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <optional>

#include "app/host_options.hpp"
#include "hull/polyhedral_hull.hpp"
#include "hull/reprojection.hpp"
#include "hull/views_io.hpp"
#include "hull/visual_hull.hpp"
#include "hull/voxel_hull.hpp"
#include "subcommand.hpp"
#include "syncap/cli/options.hpp"
#include "util/printf_string.hpp"

namespace syncap::tools {
namespace {

constexpr const char* kErrorPrefix = "syncap hull: ";

struct HullArgs {
  std::string cameras;
  std::string masks;
  std::string out;
  std::string method = "polyhedral";
  double simplify_px = hull::kDefaultSimplifyPx;
  int threshold = -1;  // none: any non-zero pixel
  int resolution = hull::VoxelOptions{}.resolution;
  bool largest = false;
  std::vector<double> volume;  // --volume: the capture volume, empty: none
  hull::HullOptions options;   // the capture volume and margin, after the parse
};

constexpr const char* kDescription =
    "usage: syncap hull --calibration FILE|DIR --masks DIR --out-dir DIR [options]\n"
    "The visual hull of one mask per camera: the exact intersection of the silhouettes' viewing\n"
    "cones (CGAL corefinement, or the polyhedral method: the same solid face by face, fast) or\n"
    "the voxel baseline. Cameras: cameras.json (its cameras in file order), an OpenCV-style\n"
    "YAML or JSON file (a sequence 'cameras', each with K, distortion k1 k2 p1 p2 [k3], R or\n"
    "rvec, t, image_size; docs/design/visual-hull.md) or a folder of 3x4 projection matrices "
    "(*.pa,\n"
    "name order, no distortion). Masks: the\n"
    "image files of DIR in name order, one per camera; foreground is any non-zero pixel, or grey\n"
    "> N with --threshold N. Writes DIR/hull.ply and DIR/hull.obj; prints each view's IoU of the\n"
    "hull's reprojection against its mask, the mesh's checks, volume, area and time.\n";

constexpr const char* kFooter =
    "Exit status: 0 done, 1 the mesh failed a check (printed), 2 usage error or bad input\n"
    "(named: file, camera).";

void add_hull_options(CLI::App& app, HullArgs& a) {
  app.add_option("--calibration", a.cameras,
                 "cameras.json, an OpenCV-style .yaml/.yml/.json, or a folder of *.pa projection "
                 "matrices")
      ->option_text("FILE|DIR")
      ->required();
  app.add_option("--masks", a.masks, "the folder of mask images, one per camera in name order")
      ->option_text("DIR")
      ->required();
  app.add_option("--out-dir", a.out, "the folder for hull.ply and hull.obj (created)")
      ->option_text("DIR")
      ->required();
  cli::add_checked(app, "--method", a.method, "exact|polyhedral|voxel",
                   cli::one_of({"exact", "polyhedral", "voxel"}),
                   "polyhedral (default): the viewing cones' exact intersection, cone face by\n"
                   "cone face (milliseconds); exact: the same solid by CGAL corefinement\n"
                   "(seconds, a reference); voxel: octree carving and marching tetrahedra");
  cli::add_checked(app, "--simplify-px", a.simplify_px, "PX", cli::number_in(0, 100),
                   "contour simplification, cv::approxPolyDP's epsilon in pixels (default " +
                       cli::number_text(a.simplify_px) + ")");
  cli::add_checked(app, "--threshold", a.threshold, "N", cli::whole_in<int>(0, 254),
                   "foreground is grey > N (for grey images, e.g. 120 for silhouettes/david);\n"
                   "default: any non-zero pixel");
  app.add_flag("--largest", a.largest,
               "keep only each mask's largest connected foreground component (one object)");
  host_app::add_volume_option(app, a.volume);
  cli::add_checked(app, "--margin", a.options.volume_margin, "F", cli::number_in(1, 100),
                   "the working ball the cones are cut to: the ball around the silhouettes'\n"
                   "rays, its radius times F (default " +
                       cli::number_text(a.options.volume_margin) +
                       "); larger when the hull reaches it");
  cli::add_checked(app, "--resolution", a.resolution, "N", cli::whole_in<int>(8, 1024),
                   "voxel method: grid cells along the hull's longest side (default " +
                       std::to_string(a.resolution) + ")");
}

std::optional<int> parse_hull_args(std::span<const std::string> args, HullArgs& a,
                                   std::ostream& out, std::ostream& err) {
  cli::App app("syncap hull", kDescription, kFooter);
  app.deprecated_name("--cameras", "--calibration");
  app.deprecated_name("--out", "--out-dir");
  app.deprecated_name("--simplify", "--simplify-px");
  add_hull_options(app, a);
  return cli::parse(app, args, out, err, [&a] {
    if (!a.volume.empty()) a.options.capture_volume = host_app::parse_volume(a.volume);
  });
}

hull::Mesh build(const std::vector<hull::HullView>& views, const HullArgs& a, std::ostream& out) {
  if (a.method == "voxel") {
    hull::VoxelStats s;
    hull::Mesh mesh = hull::voxel_visual_hull(views, {a.resolution}, a.options, &s);
    out << util::printf_string(
        "voxel: %dx%dx%d cells of %.4g, %zu points tested one by one, "
        "carving %.3f s, marching tetrahedra %.3f s\n",
        s.cells.x(), s.cells.y(), s.cells.z(), s.cell, s.point_tests, s.carve_seconds,
        s.mesh_seconds);
    return mesh;
  }
  if (a.method == "polyhedral") {
    hull::PolyhedralStats s;
    hull::Mesh mesh = hull::polyhedral_visual_hull(views, a.options, &s);
    out << util::printf_string(
        "polyhedral: %zu cone faces, %zu boundary candidates, %zu vertices, %zu triangles, "
        "%u retries, %.3f s\n",
        s.cone_faces, s.candidates, s.vertices, s.triangles, s.failed_attempts, s.seconds);
    if (s.failed_attempts > 0) out << "polyhedral: retried after: " << s.last_failure << '\n';
    return mesh;
  }
  hull::HullStats s;
  hull::Mesh mesh = hull::exact_visual_hull(views, a.options, &s);
  out << util::printf_string("exact: %zu cone triangles, cones %.3f s, intersection %.3f s\n",
                             s.cone_faces, s.cones_seconds, s.intersect_seconds);
  return mesh;
}

void print_ious(const std::vector<hull::HullView>& views, const hull::Mesh& mesh,
                std::ostream& out) {
  std::vector<double> ious;
  for (const hull::HullView& v : views) {
    ious.push_back(hull::mask_iou(hull::render_mask(mesh, v.camera), v.mask));
    out << util::printf_string("view %s: reprojection IoU %.4f\n", v.name.c_str(), ious.back());
  }
  std::ranges::sort(ious);
  out << util::printf_string("reprojection IoU: min %.4f, median %.4f over %zu views\n",
                             ious.front(), ious[ious.size() / 2], ious.size());
}

// The hull's box and size in the cameras' units (mm for cameras.json and OpenCV files in mm), and
// where it stands against the floor of --volume.
void print_extent(const hull::Mesh& mesh, const hull::MeshReport& r, const HullArgs& a,
                  std::ostream& out) {
  Eigen::AlignedBox3d box;
  for (const hull::Point3& p : mesh.points()) box.extend(Eigen::Vector3d(p.x(), p.y(), p.z()));
  if (box.isEmpty()) return;
  out << util::printf_string(
      "extent: x %.1f..%.1f, y %.1f..%.1f, z %.1f..%.1f mm (%.1f x %.1f x %.1f mm); volume %.4g "
      "L, area %.4g m^2\n",
      box.min().x(), box.max().x(), box.min().y(), box.max().y(), box.min().z(), box.max().z(),
      box.sizes().x(), box.sizes().y(), box.sizes().z(), r.volume * 1e-6, r.area * 1e-6);
  if (a.options.capture_volume)
    out << util::printf_string("floor: the hull's lowest point %.1f mm above z = %.1f\n",
                               box.min().z() - a.options.capture_volume->min().z(),
                               a.options.capture_volume->min().z());
}

}  // namespace

int hull_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  HullArgs a;
  if (const auto status = parse_hull_args(args, a, out, err)) return *status;
  using Clock = std::chrono::steady_clock;
  try {
    hull::ViewFiles files;
    files.simplify_px = a.simplify_px;
    if (a.threshold >= 0) files.threshold = a.threshold;
    files.largest_only = a.largest;
    const std::vector<hull::HullView> views = hull::read_views(a.cameras, a.masks, files);
    const Clock::time_point start = Clock::now();
    hull::Mesh mesh = build(views, a, out);
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::filesystem::create_directories(a.out);
    hull::write_mesh(std::filesystem::path(a.out) / "hull.ply", mesh);
    hull::write_mesh(std::filesystem::path(a.out) / "hull.obj", mesh);
    print_ious(views, mesh, out);
    const hull::MeshReport report = hull::check_mesh(mesh);
    out << "mesh: " << report.summary() << '\n';
    print_extent(mesh, report, a, out);
    out << util::printf_string("time: %.3f s for %zu views (%s)\n", seconds, views.size(),
                               a.method.c_str());
    if (!report.good()) {
      err << kErrorPrefix << "the mesh failed a check: " << report.summary() << '\n';
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
