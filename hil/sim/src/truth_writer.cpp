#include "truth_writer.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

namespace syncap::sim {
namespace {

std::string numbered(const char* stem, int n, const char* ext) {
  char name[64];
  std::snprintf(name, sizeof name, "%s%06d.%s", stem, n, ext);
  return name;
}

std::string camera_dir(int camera) {
  return (camera < 10 ? "camera0" : "camera") + std::to_string(camera);
}

std::ofstream open_csv(const std::filesystem::path& path, const char* header) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path.string());
  out.precision(12);
  out << header << "\n";
  return out;
}

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

std::filesystem::path TruthWriter::image_path(const std::filesystem::path& out, int camera,
                                              int frame) {
  return out / camera_dir(camera) / numbered("frame_", frame, "pgm");
}

std::filesystem::path TruthWriter::mask_path(const std::filesystem::path& out, int camera,
                                             int frame) {
  return out / "truth" / "masks" / camera_dir(camera) / numbered("mask_", frame, "png");
}

TruthWriter::TruthWriter(const std::filesystem::path& out, int cameras) : out_(out) {
  std::error_code ec;
  for (int c = 0; c < cameras; ++c) {
    std::filesystem::create_directories(out / camera_dir(c), ec);
    if (!ec) std::filesystem::create_directories(out / "truth" / "masks" / camera_dir(c), ec);
    if (ec)
      throw std::runtime_error("cannot create " + (out / camera_dir(c)).string() + ": " +
                               ec.message());
  }
  frames_ = open_csv(out / "truth" / "frames.csv", "frame,time_s,phase,phase_type,led_on,gain");
  targets_ = open_csv(out / "truth" / "targets.csv", "frame,target,X_mm,Y_mm,Z_mm,radius_mm");
  projections_ = open_csv(out / "truth" / "projections.csv",
                          "frame,camera,target,x_px,y_px,radius_px,visible");
  body_.open(out / "truth" / "body.jsonl");
  if (!body_) throw std::runtime_error("cannot write " + (out / "truth" / "body.jsonl").string());
}

void TruthWriter::write_image(const std::filesystem::path& path, const cv::Mat& image) const {
  if (!cv::imwrite(path.string(), image)) throw std::runtime_error("cannot write " + path.string());
}

// The names of a mocap phase's targets, once per phase: phase,target,name.
void TruthWriter::write_names(const FrameState& st) {
  if (st.target_names == nullptr || st.phase_index == names_phase_) return;
  if (!names_.is_open())
    names_ = open_csv(out_ / "truth" / "marker_names.csv", "phase,target,name");
  for (std::size_t t = 0; t < st.target_names->size(); ++t)
    names_ << st.phase_index << "," << t << "," << (*st.target_names)[t] << "\n";
  names_phase_ = st.phase_index;
}

void TruthWriter::write(const FrameState& st, const std::vector<RenderedView>& views) {
  frames_ << st.frame << "," << st.time_s << "," << st.phase_index << "," << st.phase->type << ","
          << (st.led_on ? 1 : 0) << "," << st.content.gain << "\n";
  write_names(st);
  const auto target = [&st](std::size_t t) {
    return st.target_ids.empty() ? static_cast<int>(t) : st.target_ids.at(t);
  };
  for (std::size_t t = 0; t < st.content.spheres.size(); ++t) {
    const Sphere& s = st.content.spheres[t];
    targets_ << st.frame << "," << target(t) << "," << s.centre_mm.x() << "," << s.centre_mm.y()
             << "," << s.centre_mm.z() << "," << s.radius_mm << "\n";
  }
  for (std::size_t c = 0; c < views.size(); ++c) {
    const int camera = static_cast<int>(c);
    write_image(image_path(out_, camera, st.frame), views[c].image);
    for (std::size_t t = 0; t < views[c].spheres.size(); ++t) {
      const SphereTruth& p = views[c].spheres[t];
      projections_ << st.frame << "," << camera << "," << target(t) << "," << p.pixel.x() << ","
                   << p.pixel.y() << "," << p.radius_px << "," << (p.visible ? 1 : 0) << "\n";
    }
    if (!st.body.empty()) write_image(mask_path(out_, camera, st.frame), views[c].mask);
  }
  if (st.body.empty()) return;
  nlohmann::json line{{"frame", st.frame}};
  if (!st.body.subject.empty()) line["subject"] = st.body.subject;
  for (const auto& [name, p] : st.body.joints) line["joints"][name] = vec(p);
  for (std::size_t i = 0; i < st.body.ellipsoids.size(); ++i) {
    const Ellipsoid& e = st.body.ellipsoids[i];
    const Eigen::Matrix3d& a = e.axes;
    nlohmann::json ellipsoid{{"centre_mm", vec(e.centre_mm)},
                             {"axes", {vec(a.col(0)), vec(a.col(1)), vec(a.col(2))}},
                             {"radii_mm", vec(e.radii_mm)}};
    if (i < st.body.segments.size()) ellipsoid["segment"] = st.body.segments[i];
    line["ellipsoids"].push_back(std::move(ellipsoid));
  }
  body_ << line.dump() << "\n";
}

}  // namespace syncap::sim
