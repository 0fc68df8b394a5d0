// syncap-mask: the edge's masking of any recording, written as images.
//   syncap-mask --input VIDEO|DIR --background VIDEO|DIR --out-dir DIR [options]
// The model is trained on the empty scene's clip as syncap-edge --background trains it, with the
// same defaults and --mask-* options; every frame's mask goes to DIR/mask_NNNNNN.png (255 where
// the person is), numbered as the input's frames.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include "syncap/cli/options.hpp"
#include "syncap/segmentation/background_clip.hpp"
#include "syncap/segmentation/image_sequence.hpp"
#include "syncap/segmentation/mask_images.hpp"
#include "syncap/segmentation/mask_options.hpp"
#include "syncap/segmentation/medi_picture.hpp"
#include "syncap/segmentation/model_alignment.hpp"

namespace {

namespace cli = syncap::cli;
namespace seg = syncap::segmentation;

constexpr const char* kDescription =
    "usage: syncap mask --input VIDEO|DIR --background VIDEO|DIR --out-dir DIR [options]\n"
    "Masks every frame of a recording as syncap-edge does, the model trained on a recording of\n"
    "the empty scene (--background, as syncap-edge --background), and writes each frame's mask\n"
    "as DIR/mask_NNNNNN.png (255 foreground, 0 background; NNNNNN the frame's number: a video's\n"
    "from 0, a folder's from its file names).\n";

constexpr const char* kFooter =
    "Exit status: 0 masks written, 2 bad arguments or an input that cannot be read (named).";

struct Arguments {
  std::string input, background, out_dir;
  int train_frames = seg::kBackgroundClipFrames;
  int64_t first_frame = 0;
  int64_t frames = 0;  // 0: to the end
  int every = 1;
  seg::MediPictureOptions options;
};

void add_options(cli::App& app, Arguments& a) {
  app.add_option("--input", a.input,
                 "the recording to mask: a video file or a folder of numbered "
                 "images")
      ->option_text("VIDEO|DIR")
      ->required();
  app.add_option("--background", a.background, "a recording of the empty scene, likewise")
      ->option_text("VIDEO|DIR")
      ->required();
  app.add_option("--out-dir", a.out_dir, "the folder the masks go to (created)")->required();
  cli::add_checked(app, "--train-frames", a.train_frames, "N", cli::whole_in<int>(2, 10000),
                   "frames of the background clip the model trains on, spread over it "
                   "(default " +
                       std::to_string(seg::kBackgroundClipFrames) + ")");
  cli::add_checked(app, "--first-frame", a.first_frame, "F",
                   cli::whole_in<int64_t>(0, int64_t{1} << 40),
                   "the first frame masked (default 0: a video's first, a folder's lowest number)");
  cli::add_checked(app, "--frames", a.frames, "N", cli::whole_in<int64_t>(1, int64_t{1} << 40),
                   "mask N frames (default: to the end)");
  cli::add_checked(app, "--every", a.every, "N", cli::whole_in<int>(1, 100000),
                   "every Nth frame (default 1)");
  // The medi-picture options with syncap-edge's names and checks.
  seg::add_mask_options(app, a.options, "");
  app.add_flag_callback(
      "--mask-no-shadows", [&a] { a.options.remove_shadows = false; }, "skip the shadow test");
}

struct Tally {
  int64_t masks = 0;
  double foreground = 0;  // share of the pixels, summed over the masks
  double mask_ms = 0;     // masking alone, summed
};

// Masks the frames the arguments ask for: a folder's numbers it lacks are passed over, a video
// cut short ends where its frames do (said once).
Tally mask_all(const Arguments& a, seg::ImageSequence& in, seg::MediPicture& masking) {
  Tally t;
  const std::filesystem::path out(a.out_dir);
  const int64_t start = std::max(in.first_frame(), a.first_frame);
  for (int64_t k = start; a.frames == 0 || k < start + a.frames; k += a.every) {
    if (k > in.last_frame()) break;
    const std::optional<cv::Mat> image = in.read(k);
    if (!image) continue;
    const cv::Size model_size = masking.model().median.size();
    if (image->size() != model_size)
      throw seg::ImageSequenceError(
          "--input frame " + std::to_string(k) + " is " + std::to_string(image->cols) + "x" +
          std::to_string(image->rows) + " pixels, the --background clip's " +
          std::to_string(model_size.width) + "x" + std::to_string(model_size.height));
    const auto begin = std::chrono::steady_clock::now();
    const cv::Mat mask = masking.apply(*image);
    t.mask_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
    seg::write_mask_image(out, k, mask);
    t.foreground += static_cast<double>(cv::countNonZero(mask)) / static_cast<double>(mask.total());
    ++t.masks;
  }
  if (!in.note().empty()) std::cerr << "syncap-mask: " << in.note() << '\n';
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  Arguments a;
  cli::App app("syncap-mask", kDescription, kFooter);
  add_options(app, a);
  if (const auto status = cli::parse_main(app, argc, argv)) return *status;
  try {
    const std::vector<cv::Mat> clip = seg::read_background_clip(a.background, a.train_frames);
    seg::MediPictureModel model = seg::train_medi_picture(clip, a.options);
    const std::unique_ptr<seg::ImageSequence> in = seg::open_image_sequence(a.input);
    // As the edge does with a clip of another time: the model moved onto the first frame where
    // the camera stands shifted against the clip (segmentation/model_alignment.hpp).
    if (const std::optional<cv::Mat> first = in->read(std::max(in->first_frame(), a.first_frame));
        first && first->size() == model.median.size()) {
      std::printf("syncap-mask: %s\n", seg::align_model(model, *first).text().c_str());
    }
    seg::MediPicture masking(model, a.options);
    std::filesystem::create_directories(a.out_dir);
    const Tally t = mask_all(a, *in, masking);
    if (t.masks == 0) {
      std::cerr << "syncap-mask: --input " << a.input << ": no frame to mask\n";
      return cli::kExitUsage;
    }
    std::printf(
        "syncap-mask: %lld masks in %s (trained on %zu frames of %s); foreground %.1f %% "
        "of the pixels on average; masking %.1f ms a frame\n",
        static_cast<long long>(t.masks), a.out_dir.c_str(), clip.size(), a.background.c_str(),
        100.0 * t.foreground / static_cast<double>(t.masks),
        t.mask_ms / static_cast<double>(t.masks));
  } catch (const std::exception& e) {  // a clip or input that cannot be read, a size mismatch
    std::cerr << "syncap-mask: " << e.what() << "\n";
    return cli::kExitUsage;
  }
  return cli::kExitOk;
}
