// syncap-sim (also `syncap sim`): renders a scenario into per-camera images and ground truth.
//
//   syncap-sim --scenario FILE --out DIR [--max-phase-frames N] [--quiet]
//
// Deterministic: the same scenario (and seed in it) gives the same bytes.
#include <charconv>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "body_source.hpp"
#include "camera_rig.hpp"
#include "scenario.hpp"
#include "sensor/camera_file.hpp"
#include "sequence.hpp"
#include "truth_writer.hpp"

namespace {

const char* kUsage =
    "usage: syncap-sim --scenario FILE --out DIR [--max-phase-frames N] [--quiet]\n"
    "  --scenario FILE         scenario (YAML, docs/scenario.md)\n"
    "  --out DIR               output folder: cameraNN/frame_*.pgm, cameras.json, truth/\n"
    "  --max-phase-frames N    render at most N frames of each phase (short runs, CI)\n"
    "  --quiet                 only errors\n"
    "A relative motion (bvh) path is looked for beside the scenario, then under $SYNCAP_DATA\n"
    "(default ../shared/data). Exit status: 0 rendered, 1 writing failed, 2 usage error or a\n"
    "bad scenario or motion file.\n";

struct Options {
  std::filesystem::path scenario, out;
  int max_phase_frames = 0;
  bool quiet = false;
};

[[noreturn]] void usage_error(const std::string& message) {
  std::cerr << "syncap-sim: " << message << "\n" << kUsage;
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (a == "--scenario") {
      o.scenario = value();
    } else if (a == "--out") {
      o.out = value();
    } else if (a == "--max-phase-frames") {
      const std::string v = value();
      auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), o.max_phase_frames);
      if (ec != std::errc() || end != v.data() + v.size() || o.max_phase_frames < 1) {
        usage_error("--max-phase-frames '" + v + "': expected a whole number >= 1");
      }
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      usage_error("unknown option '" + a + "'");
    }
  }
  if (o.scenario.empty()) usage_error("--scenario is required");
  if (o.out.empty()) usage_error("--out is required");
  return o;
}

uint64_t noise_seed(unsigned seed, int frame, int camera) {
  return (static_cast<uint64_t>(seed) << 40) ^ (static_cast<uint64_t>(frame) << 8) ^
         static_cast<uint64_t>(camera);
}

// `input_read` is set once the scenario and its motion are read: errors before are bad input.
int run(const Options& o, bool& input_read) {
  syncap::sim::Scenario scenario = syncap::sim::load_scenario(o.scenario);
  if (o.max_phase_frames > 0) {
    for (auto& phase : scenario.phases) phase.frames = std::min(phase.frames, o.max_phase_frames);
  }
  const auto start = std::chrono::steady_clock::now();
  const auto rig = syncap::sim::build_rig(scenario);
  std::vector<syncap::sim::View> views;
  for (const auto& camera : rig) views.push_back(syncap::sim::make_view(camera, scenario));
  syncap::sim::Sequence sequence(scenario, syncap::sim::open_bvh_body);
  input_read = true;
  syncap::sim::TruthWriter writer(o.out, static_cast<int>(rig.size()));
  syncap::sensor::write_cameras(o.out / "cameras.json", rig);
  std::filesystem::copy_file(o.scenario, o.out / "scenario.yaml",
                             std::filesystem::copy_options::overwrite_existing);

  std::vector<syncap::sim::RenderedView> rendered(views.size());
  for (int frame = 0; frame < sequence.frames(); ++frame) {
    const syncap::sim::FrameState state = sequence.at(frame);
    for (std::size_t c = 0; c < views.size(); ++c) {
      rendered[c] = syncap::sim::render_view(views[c], state.content, scenario.image,
                                             noise_seed(scenario.seed, frame, static_cast<int>(c)));
    }
    writer.write(state, rendered);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!o.quiet) {
    std::cout << "syncap-sim: " << scenario.name << ": " << sequence.frames() << " frames x "
              << rig.size() << " cameras (" << scenario.cameras.width_px << "x"
              << scenario.cameras.height_px << ") in " << seconds << " s, written to "
              << o.out.string() << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  bool input_read = false;
  try {
    return run(options, input_read);
  } catch (const std::exception& e) {
    std::cerr << "syncap-sim: " << e.what() << "\n";
    return input_read ? 1 : 2;  // 2: a bad scenario or motion file, as usage errors everywhere
  }
}
