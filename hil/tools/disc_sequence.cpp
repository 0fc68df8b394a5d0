// syncap-disc-sequence: the thinnest replay scene and its check.
//
//   syncap-disc-sequence render --out DIR [--frames N] [--width W] [--height H] [--radius R]
//                                [--noise SIGMA] [--seed S]
//     writes DIR/frame_000000.pgm ... : one bright disc (a wand target) moving on a Lissajous
//     path over a dark background, rendered with exact area coverage (16x16 samples a pixel),
//     and DIR/truth.csv (frame,x,y) with the disc centre in pixel coordinates.
//   syncap-disc-sequence check --truth DIR/truth.csv --groups FILE.jsonl --camera C
//                              [--max-error PX]
//     compares the first blob of camera C in each frame group the host wrote with the truth;
//     prints frames matched and centroid error (mean, max); exit 0 when every truth frame has a
//     blob within --max-error (default 0.1 px), 1 otherwise.
//
// The full scene generator (syncap sim) replaces this for multi-camera scenes.
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Args {
  std::map<std::string, std::string> values;
  std::string get(const std::string& key, const std::string& fallback = "") const {
    auto it = values.find(key);
    return it == values.end() ? fallback : it->second;
  }
  double number(const std::string& key, double fallback) const {
    auto it = values.find(key);
    if (it == values.end()) return fallback;
    double v = 0;
    auto [end, ec] = std::from_chars(it->second.data(), it->second.data() + it->second.size(), v);
    if (ec != std::errc() || end != it->second.data() + it->second.size()) {
      throw std::invalid_argument("--" + key + " '" + it->second + "' is not a number");
    }
    return v;
  }
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 2; i < argc; ++i) {
    std::string key = argv[i];
    if (!key.starts_with("--") || i + 1 >= argc) {
      throw std::invalid_argument("expected --option value at '" + key + "'");
    }
    a.values[key.substr(2)] = argv[++i];
  }
  return a;
}

// Fraction of pixel (px, py) covered by the disc, from 16x16 sample points.
double coverage(int px, int py, double cx, double cy, double r) {
  constexpr int kSamples = 16;
  int inside = 0;
  for (int sy = 0; sy < kSamples; ++sy) {
    for (int sx = 0; sx < kSamples; ++sx) {
      const double x = px - 0.5 + (sx + 0.5) / kSamples - cx;
      const double y = py - 0.5 + (sy + 0.5) / kSamples - cy;
      inside += x * x + y * y <= r * r;
    }
  }
  return static_cast<double>(inside) / (kSamples * kSamples);
}

cv::Mat render_frame(cv::Size size, double cx, double cy, double r, double noise, cv::RNG& rng) {
  cv::Mat image(size, CV_64F, cv::Scalar(20.0));
  const int x0 = std::max(0, static_cast<int>(cx - r - 2));
  const int x1 = std::min(size.width - 1, static_cast<int>(cx + r + 2));
  const int y0 = std::max(0, static_cast<int>(cy - r - 2));
  const int y1 = std::min(size.height - 1, static_cast<int>(cy + r + 2));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) image.at<double>(y, x) += 210.0 * coverage(x, y, cx, cy, r);
  }
  cv::Mat noise_image(size, CV_64F);
  rng.fill(noise_image, cv::RNG::NORMAL, 0.0, noise);
  cv::Mat out;
  cv::Mat(image + noise_image).convertTo(out, CV_8U);  // rounds and saturates
  return out;
}

int render(const Args& a) {
  const std::filesystem::path dir = a.get("out");
  if (dir.empty()) throw std::invalid_argument("render needs --out DIR");
  const int frames = static_cast<int>(a.number("frames", 30));
  const cv::Size size(static_cast<int>(a.number("width", 640)),
                      static_cast<int>(a.number("height", 480)));
  const double r = a.number("radius", 4.0);
  const double noise = a.number("noise", 2.0);
  cv::RNG rng(static_cast<uint64_t>(a.number("seed", 1)));
  std::filesystem::create_directories(dir);
  std::ofstream truth(dir / "truth.csv");
  truth << "frame,x,y\n";
  truth.precision(10);
  for (int k = 0; k < frames; ++k) {
    const double t = 2.0 * M_PI * k / std::max(frames, 1);
    const double cx = size.width * (0.5 + 0.35 * std::sin(t));
    const double cy = size.height * (0.5 + 0.35 * std::sin(2 * t + 0.3));
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.pgm", k);
    if (!cv::imwrite((dir / name).string(), render_frame(size, cx, cy, r, noise, rng))) {
      throw std::runtime_error("cannot write " + (dir / name).string());
    }
    truth << k << "," << cx << "," << cy << "\n";
  }
  std::cout << "rendered " << frames << " frames " << size.width << "x" << size.height
            << " (disc radius " << r << " px, noise sigma " << noise << ") into " << dir.string()
            << "\n";
  return 0;
}

std::map<long, cv::Point2d> read_truth(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read truth file " + path);
  std::map<long, cv::Point2d> truth;
  std::string line;
  std::getline(in, line);  // header
  for (int number = 2; std::getline(in, line); ++number) {
    long frame = 0;
    double x = 0, y = 0;
    char c1 = 0, c2 = 0;
    std::istringstream row(line);
    if (!(row >> frame >> c1 >> x >> c2 >> y) || c1 != ',' || c2 != ',') {
      throw std::runtime_error(path + ":" + std::to_string(number) + ": expected frame,x,y");
    }
    truth[frame] = {x, y};
  }
  return truth;
}

int check(const Args& a) {
  const auto truth = read_truth(a.get("truth"));
  const std::string camera = a.get("camera", "0");
  const double max_error = a.number("max-error", 0.1);
  std::ifstream groups(a.get("groups"));
  if (!groups) throw std::runtime_error("cannot read frame groups " + a.get("groups"));
  double sum = 0, worst = 0;
  long matched = 0;
  std::string line;
  for (int number = 1; std::getline(groups, line); ++number) {
    const auto g = nlohmann::json::parse(line, nullptr, false);
    if (g.is_discarded())
      throw std::runtime_error(a.get("groups") + ":" + std::to_string(number) + ": not JSON");
    auto t = truth.find(g.value("frame", -1L));
    if (t == truth.end() || !g["cameras"].contains(camera)) continue;
    const auto& blobs = g["cameras"][camera]["blobs"];
    if (blobs.empty()) continue;
    const double e = std::hypot(blobs[0]["x"].get<double>() - t->second.x,
                                blobs[0]["y"].get<double>() - t->second.y);
    sum += e;
    worst = std::max(worst, e);
    ++matched;
  }
  const bool pass = matched == static_cast<long>(truth.size()) && worst <= max_error;
  std::printf(
      "check camera %s: %ld/%zu truth frames matched, centroid error mean %.4f px, max %.4f px "
      "(limit %.3f): %s\n",
      camera.c_str(), matched, truth.size(), matched ? sum / matched : 0.0, worst, max_error,
      pass ? "PASS" : "FAIL");
  return pass ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string command = argc > 1 ? argv[1] : "";
  try {
    if (command == "render") return render(parse(argc, argv));
    if (command == "check") return check(parse(argc, argv));
  } catch (const std::exception& e) {
    std::cerr << "syncap-disc-sequence " << command << ": " << e.what() << "\n";
    return 2;
  }
  std::cerr << "usage: syncap-disc-sequence render --out DIR [--frames N] ...\n"
               "       syncap-disc-sequence check --truth CSV --groups JSONL --camera C\n";
  return 2;
}
