// syncap-segment-eval: scores a foreground method on a CDnet 2014 folder, or medi-picture on a
// scene rendered by syncap-sim.
//   syncap-segment-eval --cdnet DIR --method medipicture|mog2|knn [--train-frames N] ...
//   syncap-segment-eval --scene DIR [--person] [medi-picture options]
#include <cstdio>
#include <exception>
#include <iostream>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "segmentation/cdnet_eval.hpp"
#include "segmentation/masking_options.hpp"
#include "segmentation/scene_eval.hpp"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitUsage =
    2;  // bad arguments or bad input (a folder, an image), as in every program

void print_usage(std::ostream& out) {
  out << "usage: syncap segment-eval --cdnet DIR --method medipicture|mog2|knn [options]\n"
         "       syncap segment-eval --scene DIR [--person] [medi-picture options]\n"
         "Scores the method on a CDnet 2014 folder (frames of temporalROI.txt, pixels of\n"
         "ROI.bmp; ground truth 255 foreground, 0 and 50 background, 85 and 170 not scored),\n"
         "or medi-picture on a syncap-sim scene: per camera, trained on the room phase, IoU\n"
         "against the true masks of the person frames.\n"
         "  --person            start from the options syncap-edge masks with (k 1, common-\n"
         "                      ratio shadow test at 3 sigmas, closing 5, holes up to 100 px)\n"
         "  --train-frames N    medi-picture: train on the last N frames before the scored\n"
         "                      range (default: all of them)\n"
         "  --frame-step N      score every N-th frame (default 1)\n"
         "  --k K               interval width in units of d (default 3)\n"
         "  --min-difference D  floor of d, DN (default 6)\n"
         "  --ncc L             shadow threshold L_NCC (default 0.98)\n"
         "  --no-shadows        skip the shadow test\n"
         "  --shadow-test T     correlation (eqs 5.6-5.11, default) or common-ratio\n"
         "  --shadow-sigmas S   common-ratio tolerance in training sigmas (default 4)\n"
         "  --fill-holes A      fill holes of the mask up to A pixels (default 0)\n"
         "  --closing D         elliptical closing diameter, pixels, 0 = none (default 9)\n"
         "  --min-area A        smallest component kept, pixels (default 40)\n"
         "  --update-rate R     slow model update where background (default 0)\n"
         "Values out of range are refused (as syncap-edge's --mask-* options). Exit status: 0\n"
         "scored, 2 bad arguments or bad input (a missing, undecodable or truncated image).\n";
}

struct Arguments {
  std::string folder;
  bool scene = false;  // --scene DIR rather than --cdnet DIR
  syncap::edge::CdnetEvalOptions options;
};

// Parses argv into `arguments`; throws std::invalid_argument naming the bad argument.
Arguments parse_arguments(int argc, char** argv) {
  using syncap::edge::parse_number;
  Arguments arguments;
  bool have_method = false;
  // --person is the base the other options change, wherever it stands.
  for (int i = 1; i < argc; ++i) {
    if (std::string_view(argv[i]) == "--person") {
      arguments.options.medi_picture = syncap::edge::person_masking_options();
    }
  }
  static const std::set<std::string_view> kMediPictureOptions{
      "--k",          "--min-difference", "--ncc",      "--shadow-test", "--shadow-sigmas",
      "--fill-holes", "--closing",        "--min-area", "--update-rate"};
  static const std::set<std::string_view> kOtherOptions{"--cdnet", "--scene", "--method",
                                                        "--train-frames", "--frame-step"};
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--no-shadows") {
      arguments.options.medi_picture.remove_shadows = false;
      continue;
    }
    if (flag == "--person") continue;
    if (!kMediPictureOptions.contains(flag) && !kOtherOptions.contains(flag)) {
      throw std::invalid_argument("unknown option '" + flag + "'");
    }
    if (i + 1 >= argc) throw std::invalid_argument(flag + " needs a value");
    const std::string value = argv[++i];
    try {
      if (kMediPictureOptions.contains(flag)) {
        syncap::edge::apply_masking_option(arguments.options.medi_picture, flag.substr(2), value);
      } else if (flag == "--cdnet" || flag == "--scene") {
        arguments.folder = value;
        arguments.scene = flag == "--scene";
      } else if (flag == "--method") {
        arguments.options.method = syncap::edge::parse_segmentation_method(value);
        have_method = true;
      } else if (flag == "--train-frames") {
        arguments.options.train_frames = parse_number<int>(value, 1, 1 << 24);
      } else if (flag == "--frame-step") {
        arguments.options.frame_step = parse_number<int>(value, 1, 1 << 24);
      }
    } catch (const syncap::edge::BadValue& e) {
      throw std::invalid_argument(flag + " " + e.what());
    }
  }
  if (arguments.folder.empty())
    throw std::invalid_argument("--cdnet DIR or --scene DIR is required");
  if (arguments.scene && have_method &&
      arguments.options.method != syncap::edge::SegmentationMethod::kMediPicture) {
    throw std::invalid_argument("--scene scores medi-picture only");
  }
  if (!arguments.scene && !have_method) throw std::invalid_argument("--method is required");
  return arguments;
}

void print_scores(const std::string& method, const syncap::edge::CdnetScores& scores) {
  std::printf("method %s frames %d\n", method.c_str(), scores.scored_frames);
  std::printf("precision %.4f recall %.4f f-measure %.4f\n", scores.precision(), scores.recall(),
              scores.f_measure());
  std::printf("tp %lld fp %lld fn %lld tn %lld\n", static_cast<long long>(scores.true_positives),
              static_cast<long long>(scores.false_positives),
              static_cast<long long>(scores.false_negatives),
              static_cast<long long>(scores.true_negatives));
}

void print_scene_scores(const std::vector<syncap::edge::SceneCameraScore>& scores) {
  std::printf("camera frames iou_mean iou_min fp_px fn_px truth_px\n");
  double sum = 0;
  for (const auto& s : scores) {
    std::printf("%6d %6d %8.4f %7.4f %5.0f %5.0f %8.0f\n", s.camera, s.frames, s.iou_mean,
                s.iou_min, s.false_positives, s.false_negatives, s.truth_pixels);
    sum += s.iou_mean;
  }
  std::printf("all    %15.4f\n", sum / static_cast<double>(scores.size()));
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::string_view(argv[i]) == "--help" || std::string_view(argv[i]) == "-h") {
      print_usage(std::cout);
      return kExitOk;
    }
  }
  Arguments arguments;
  try {
    arguments = parse_arguments(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "syncap-segment-eval: " << e.what() << "\n";
    print_usage(std::cerr);
    return kExitUsage;
  }
  try {
    if (arguments.scene) {
      print_scene_scores(
          syncap::edge::evaluate_scene(arguments.folder, arguments.options.medi_picture));
      return kExitOk;
    }
    const auto scores = syncap::edge::evaluate_cdnet(arguments.folder, arguments.options);
    std::string method;
    for (int i = 1; i + 1 < argc; ++i) {
      if (std::string_view(argv[i]) == "--method") method = argv[i + 1];
    }
    print_scores(method, scores);
  } catch (const std::exception& e) {  // a missing or undecodable input file
    std::cerr << "syncap-segment-eval: " << e.what() << "\n";
    return kExitUsage;
  }
  return kExitOk;
}
