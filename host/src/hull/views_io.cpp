#include "hull/views_io.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <set>

#include "sensor/camera_file.hpp"
#include "sensor/opencv_camera.hpp"
#include "util/file_extension.hpp"
#include "util/printf_string.hpp"

namespace syncap::hull {

namespace fs = std::filesystem;

namespace {

// A .pa matrix gives pixels only; any pixel pitch reproduces them (c scales with it).
constexpr double kPaPixelMm = 0.01;

std::vector<fs::path> files_with(const fs::path& folder, const std::set<std::string>& extensions) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    if (e.is_regular_file() && extensions.contains(util::lower_extension(e.path())))
      files.push_back(e.path());
  }
  if (ec) throw HullError(folder.string() + ": cannot read the folder: " + ec.message());
  std::ranges::sort(files);
  return files;
}

cv::Mat largest_component(const cv::Mat& mask) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  int best = 0;
  for (int i = 1; i < n; ++i) {
    if (best == 0 || stats.at<int>(i, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA))
      best = i;
  }
  return best == 0 ? cv::Mat::zeros(mask.size(), CV_8UC1) : cv::Mat(labels == best);
}

struct Cameras {
  std::vector<sensor::CameraModel> models;
  std::vector<std::string> sources;  // the file each camera came from
  bool sized_by_mask = false;        // .pa cameras take the mask's size
};

Cameras read_cameras(const fs::path& path) {
  Cameras c;
  if (!fs::is_directory(path)) {
    // OpenCV cameras keep their lens (CameraModel::opencv_lens): every method back-projects the
    // contours through it.
    try {
      c.models = sensor::read_cameras(path);
    } catch (const sensor::CameraFileError& e) {
      throw HullError(e.what());
    }
    c.sources.assign(c.models.size(), path.string());
    return c;
  }
  int id = 0;
  for (const fs::path& file : files_with(path, {".pa"})) {
    c.models.push_back(sensor::camera_from_projection_matrix(read_projection_matrix(file), {1, 1},
                                                             kPaPixelMm, kPaPixelMm, id++));
    c.sources.push_back(file.string());
  }
  if (c.models.empty()) throw HullError(path.string() + ": no cameras (*.pa files)");
  c.sized_by_mask = true;
  return c;
}

// The principal point moves with the image size in the model (it is measured from the sensor
// centre), so a .pa camera is rebuilt for the mask's size.
sensor::CameraModel sized(const fs::path& pa_file, cv::Size size, int id) {
  return sensor::camera_from_projection_matrix(read_projection_matrix(pa_file), size, kPaPixelMm,
                                               kPaPixelMm, id);
}

}  // namespace

cv::Mat read_mask(const fs::path& file, const ViewFiles& options) {
  const cv::Mat grey = cv::imread(file.string(), cv::IMREAD_GRAYSCALE);
  if (grey.empty()) throw HullError(file.string() + ": cannot read the image");
  cv::Mat mask = grey > options.threshold.value_or(0);
  return options.largest_only ? largest_component(mask) : mask;
}

std::vector<fs::path> mask_files(const fs::path& folder) {
  return files_with(folder, {".png", ".jpg", ".jpeg", ".pgm", ".ppm", ".bmp", ".tif", ".tiff"});
}

cv::Matx34d read_projection_matrix(const fs::path& file) {
  std::ifstream in(file);
  cv::Matx34d p;
  for (double& v : p.val) in >> v;
  if (!in) throw HullError(file.string() + ": expected 12 numbers (a 3x4 projection matrix)");
  return p;
}

namespace {

// The cameras with the file of each (one per image of `folder`, name order; an image sizes the
// camera of a *.pa file), named; `what` names the files in the count's error.
std::vector<HullView> camera_views(const fs::path& cameras, const fs::path& folder,
                                   const char* what, std::vector<fs::path>& files) {
  const Cameras c = read_cameras(cameras);
  files = mask_files(folder);
  if (files.size() != c.models.size()) {
    throw HullError(util::printf_string("%s: %zu %s for %zu camera(s) of %s",
                                        folder.string().c_str(), files.size(), what,
                                        c.models.size(), cameras.string().c_str()));
  }
  std::vector<HullView> views;
  for (std::size_t i = 0; i < files.size(); ++i) {
    HullView v;
    v.camera = c.models[i];
    if (c.sized_by_mask) {
      const cv::Mat image = cv::imread(files[i].string(), cv::IMREAD_UNCHANGED);
      if (image.empty()) throw HullError(files[i].string() + ": not a readable image");
      v.camera = sized(c.sources[i], image.size(), c.models[i].id);
    }
    v.name = util::printf_string("camera %d (%s, %s)", v.camera.id, c.sources[i].c_str(),
                                 files[i].string().c_str());
    views.push_back(std::move(v));
  }
  return views;
}

}  // namespace

std::vector<HullView> read_views(const fs::path& cameras, const fs::path& masks,
                                 const ViewFiles& options) {
  std::vector<fs::path> files;
  std::vector<HullView> views = camera_views(cameras, masks, "mask image(s)", files);
  for (std::size_t i = 0; i < views.size(); ++i) {
    HullView& v = views[i];
    v.mask = read_mask(files[i], options);
    if (v.mask.cols != v.camera.sensor.width_px || v.mask.rows != v.camera.sensor.height_px) {
      throw HullError(util::printf_string("%s: mask is %dx%d, the camera's image %dx%d",
                                          v.name.c_str(), v.mask.cols, v.mask.rows,
                                          v.camera.sensor.width_px, v.camera.sensor.height_px));
    }
    v.silhouette = silhouette_from_mask(v.mask, options.simplify_px);
    if (v.silhouette.empty()) throw HullError(v.name + ": empty mask (no foreground)");
  }
  return views;
}

std::vector<HullView> read_camera_views(const fs::path& cameras, const fs::path& images) {
  std::vector<fs::path> files;
  return camera_views(cameras, images, "image(s)", files);
}

}  // namespace syncap::hull
