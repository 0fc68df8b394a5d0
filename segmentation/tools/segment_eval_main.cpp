// syncap-segment-eval: scores a foreground method on a CDnet 2014 folder, or medi-picture on a
// scene rendered by syncap-sim.
//   syncap-segment-eval --cdnet DIR --method medipicture|mog2|knn [--train-frames N] ...
//   syncap-segment-eval --scene DIR [--thesis] [--regions FILE] [medi-picture options]
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "syncap/cli/options.hpp"
#include "syncap/segmentation/cdnet_eval.hpp"
#include "syncap/segmentation/masking_options.hpp"
#include "syncap/segmentation/scene_eval.hpp"

namespace {

namespace cli = syncap::cli;

constexpr int kExitUsage = cli::kExitUsage;  // bad arguments or bad input, as in every program

constexpr const char* kDescription =
    "usage: syncap segment-eval --cdnet DIR --method medipicture|mog2|knn [options]\n"
    "       syncap segment-eval --scene DIR [--thesis] [--regions FILE] [medi-picture options]\n"
    "Scores the method on a CDnet 2014 folder (frames of temporalROI.txt, pixels of\n"
    "ROI.bmp; ground truth 255 foreground, 0 and 50 background, 85 and 170 not scored),\n"
    "or medi-picture on a syncap-sim scene: per camera, trained on the room phase, IoU\n"
    "against the true masks of the person frames; with --regions, inside the host's regions\n"
    "(clip_polygon_t JSON lines as `syncap clip` and `syncap regions` print them).\n";

constexpr const char* kFooter =
    "Values out of range are refused (as syncap-edge's --mask-* options). Exit status: 0\n"
    "scored, 2 bad arguments or bad input (a missing, undecodable or truncated image).";

struct Arguments {
  std::string cdnet, scene_dir, method;
  std::string folder;
  bool scene = false;  // --scene DIR rather than --cdnet DIR
  bool thesis = false, no_shadows = false;
  std::map<std::string, std::string> masking;  // by name: applied after --thesis' base
  std::string regions;                         // --regions FILE
  syncap::segmentation::CdnetEvalOptions options;
};

void add_options(cli::App& app, Arguments& a) {
  auto* cdnet = app.add_option("--cdnet", a.cdnet, "a CDnet 2014 folder")->option_text("DIR");
  app.add_option("--scene", a.scene_dir, "a syncap-sim scene (medi-picture only)")
      ->option_text("DIR")
      ->excludes(cdnet);
  app.add_option("--method", a.method, "the foreground method (--cdnet)")
      ->option_text("medipicture|mog2|knn");
  app.add_flag("--thesis", a.thesis,
               "start from the thesis' parameters (k 3, correlation shadow test,\n"
               "closing 9, no hole filling, no illumination correction) instead of\n"
               "the defaults, which syncap-edge masks with too");
  cli::add_checked(app, "--train-frames", a.options.train_frames, "N", cli::whole_in(1, 1 << 24),
                   "medi-picture: train on the last N frames before the scored\n"
                   "range (default: all of them)");
  cli::add_checked(app, "--frame-step", a.options.frame_step, "N", cli::whole_in(1, 1 << 24),
                   "score every N-th frame (default 1)");
  // The medi-picture options, checked by apply_masking_option as syncap-edge's --mask-* are;
  // their defaults are medi-picture's own, syncap-edge's too (--thesis changes them).
  for (const auto& [name, metavar, meaning, old_name] : syncap::segmentation::kMaskingOptions) {
    const std::string fallback = syncap::segmentation::masking_option_value(
        syncap::segmentation::MediPictureOptions{}, name);
    app.add_option_function<std::string>(
           std::string("--") + name, [&a, name](const std::string& v) { a.masking[name] = v; },
           std::string(meaning) + " (default " + fallback + ")")
        ->option_text(metavar);
    if (old_name != nullptr)
      app.deprecated_name(std::string("--") + old_name, std::string("--") + name);
  }
  app.add_flag("--no-shadows", a.no_shadows, "skip the shadow test");
  app.add_option("--regions", a.regions,
                 "--scene: the host's regions per camera, JSON lines of clip_polygon_t\n"
                 "(clip, floor, search with its frames)")
      ->option_text("FILE");
}

// After parsing: --thesis is the base the medi-picture options change, wherever it stands.
void apply_options(Arguments& a) {
  auto& m = a.options.medi_picture;
  if (a.thesis) m = syncap::segmentation::thesis_masking_options();
  for (const auto& [name, value] : a.masking) {
    try {
      syncap::segmentation::apply_masking_option(m, name, value);
    } catch (const syncap::segmentation::BadValue& e) {
      throw CLI::ValidationError("--" + name, e.what());
    }
  }
  if (a.no_shadows) m.remove_shadows = false;
  a.scene = !a.scene_dir.empty();
  a.folder = a.scene ? a.scene_dir : a.cdnet;
  if (a.folder.empty()) throw CLI::ValidationError("--cdnet DIR or --scene DIR is required");
  if (a.method.empty()) {
    if (!a.scene) throw CLI::ValidationError("--method is required");
    return;
  }
  try {
    a.options.method = syncap::segmentation::parse_segmentation_method(a.method);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("--method", e.what());
  }
  if (a.scene && a.options.method != syncap::segmentation::SegmentationMethod::kMediPicture)
    throw CLI::ValidationError("--scene scores medi-picture only");
}

// FILE's lines, each a clip_polygon_t as syncap clip prints it; errors name FILE and the line.
std::vector<syncap::segmentation::SceneRegion> read_regions(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("--regions: cannot read " + path);
  std::vector<syncap::segmentation::SceneRegion> regions;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    try {
      const nlohmann::json j = nlohmann::json::parse(line);
      syncap::segmentation::SceneRegion r;
      r.camera = j.at("camera_id").get<int>();
      const std::string kind = j.value("region", "clip");
      if (kind != "clip" && kind != "floor" && kind != "search")
        throw std::runtime_error("region '" + kind + "' (clip, floor or search)");
      r.kind = kind == "floor"    ? syncap::segmentation::SceneRegion::Kind::kFloor
               : kind == "search" ? syncap::segmentation::SceneRegion::Kind::kSearch
                                  : syncap::segmentation::SceneRegion::Kind::kClip;
      r.first_frame = j.value("frame_number", int64_t{0});
      r.frames = j.value("valid_frames", 0);
      const auto x = j.at("x").get<std::vector<int>>();
      const auto y = j.at("y").get<std::vector<int>>();
      if (x.size() != y.size() || (!x.empty() && x.size() < 3))
        throw std::runtime_error("x and y need the same count, 0 or at least 3");
      for (std::size_t i = 0; i < x.size(); ++i) r.polygon.emplace_back(x[i], y[i]);
      regions.push_back(std::move(r));
    } catch (const std::exception& e) {
      throw std::runtime_error("--regions " + where + e.what());
    }
  }
  return regions;
}

void print_scores(const std::string& method, const syncap::segmentation::CdnetScores& scores) {
  std::printf("method %s frames %d\n", method.c_str(), scores.scored_frames);
  std::printf("precision %.4f recall %.4f f-measure %.4f\n", scores.precision(), scores.recall(),
              scores.f_measure());
  std::printf("tp %lld fp %lld fn %lld tn %lld\n", static_cast<long long>(scores.true_positives),
              static_cast<long long>(scores.false_positives),
              static_cast<long long>(scores.false_negatives),
              static_cast<long long>(scores.true_negatives));
}

void print_scene_scores(const std::vector<syncap::segmentation::SceneCameraScore>& scores) {
  std::printf("camera frames iou_mean iou_min fp_px fn_px truth_px searched\n");
  double sum = 0;
  for (const auto& s : scores) {
    std::printf("%6d %6d %8.4f %7.4f %5.0f %5.0f %8.0f %8d\n", s.camera, s.frames, s.iou_mean,
                s.iou_min, s.false_positives, s.false_negatives, s.truth_pixels, s.frames_searched);
    sum += s.iou_mean;
  }
  std::printf("all    %15.4f\n", sum / static_cast<double>(scores.size()));
}

}  // namespace

int main(int argc, char** argv) {
  Arguments arguments;
  cli::App app("syncap-segment-eval", kDescription, kFooter);
  add_options(app, arguments);
  if (const auto status = cli::parse_main(app, argc, argv, [&] { apply_options(arguments); }))
    return *status;
  try {
    if (arguments.scene) {
      const auto regions = arguments.regions.empty()
                               ? std::vector<syncap::segmentation::SceneRegion>{}
                               : read_regions(arguments.regions);
      print_scene_scores(syncap::segmentation::evaluate_scene(
          arguments.folder, arguments.options.medi_picture, regions));
      return cli::kExitOk;
    }
    const auto scores = syncap::segmentation::evaluate_cdnet(arguments.folder, arguments.options);
    print_scores(arguments.method, scores);
  } catch (const std::exception& e) {  // a missing or undecodable input file
    std::cerr << "syncap-segment-eval: " << e.what() << "\n";
    return kExitUsage;
  }
  return cli::kExitOk;
}
