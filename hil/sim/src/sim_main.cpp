// syncap-sim (also `syncap sim`): renders a scenario into per-camera images and ground truth.
//
//   syncap-sim --scenario FILE --out DIR [--max-phase-frames N] [--quiet]
//
// Deterministic: the same scenario (and seed in it) gives the same bytes.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "body_source.hpp"
#include "camera_rig.hpp"
#include "scenario.hpp"
#include "sensor/camera_file.hpp"
#include "sequence.hpp"
#include "syncap/cli/options.hpp"
#include "truth_writer.hpp"

namespace {

namespace cli = syncap::cli;

struct Options {
  std::filesystem::path scenario, out;
  int max_phase_frames = 0;
  std::string subject;  // non-empty: every person is this skinned subject
  bool quiet = false;
};

// Parses into `o`; the exit status when the run is over already (help, usage error).
std::optional<int> parse(int argc, char** argv, Options& o) {
  cli::App app(
      "syncap-sim",
      "Renders a scenario into per-camera images and ground truth (docs/design/scenario.md).",
      "A relative motion (bvh) or marker trajectory (trajectories: .c3d, .trc) path is looked\n"
      "for beside the scenario, then under $SYNCAP_DATA (default ../shared/data).\n"
      "Exit status: 0 rendered, 1 writing failed, 2 usage error or a bad scenario, motion or\n"
      "marker file.");
  app.add_option("--scenario", o.scenario, "scenario (YAML, docs/design/scenario.md)")
      ->option_text("FILE")
      ->required();
  app.add_option("--out", o.out, "output folder: cameraNN/frame_*.pgm, cameras.json, truth/")
      ->option_text("DIR")
      ->required();
  cli::add_checked(app, "--max-phase-frames", o.max_phase_frames, "N",
                   cli::whole_in(1, 1'000'000'000),
                   "render at most N frames of each phase (short runs, CI; default all)");
  app.add_option("--subject", o.subject,
                 "draw every person phase as the skinned human of subject NAME, as\n"
                 "person: {model: mesh, subject: NAME} would (hil/assets/makehuman/README.md)")
      ->option_text("NAME");
  app.add_flag("--quiet", o.quiet, "only errors");
  return cli::parse_main(app, argc, argv);
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
  if (!o.subject.empty()) {
    for (auto& phase : scenario.phases) {
      if (phase.type != "person") continue;
      if (!phase.person.markers.empty())
        throw std::runtime_error(o.scenario.string() + ":" + std::to_string(phase.line) +
                                 ": --subject: this person's markers sit on the ellipsoids");
      phase.person.model = "mesh";
      phase.person.subject = o.subject;
    }
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
  Options options;
  if (const auto status = parse(argc, argv, options)) return *status;
  bool input_read = false;
  try {
    return run(options, input_read);
  } catch (const std::exception& e) {
    std::cerr << "syncap-sim: " << e.what() << "\n";
    return input_read ? 1 : 2;  // 2: a bad scenario or motion file, as usage errors everywhere
  }
}
