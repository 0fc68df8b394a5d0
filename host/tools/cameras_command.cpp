#include "cameras_command.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "calibration/exports.hpp"
#include "io/atomic_file.hpp"
#include "sensor/camera_file.hpp"
#include "sensor/opencv_camera.hpp"
#include "sensor/toml_camera_file.hpp"
#include "subcommand.hpp"
#include "syncap/cli/options.hpp"
#include "util/file_extension.hpp"
#include "util/printf_string.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

constexpr const char* kErrorPrefix = "syncap cameras convert: ";

struct ConvertArgs {
  std::string in;
  std::string out;
  std::optional<double> toml_unit_mm;
};

constexpr const char* kDescription =
    "usage: syncap cameras convert IN OUT [--toml-unit-mm MM]\n"
    "Reads the cameras of IN (cameras.json; an OpenCV-style .yaml/.yml/.json with K, distortion,\n"
    "R or rvec, t; an anipose/Pose2Sim .toml) and writes them to OUT in the format its\n"
    "extension names: .json cameras.json, .yaml/.yml OpenCV, .toml anipose/Pose2Sim (metres).\n"
    "An OpenCV lens is carried exactly; a lens of the thesis' model written as OpenCV's is\n"
    "fitted, and the fit's largest miss in the image is printed per camera.\n";

constexpr const char* kFooter = "Exit status: 0 done, 2 usage error or an unreadable IN (named).";

std::optional<int> parse_convert_args(std::span<const std::string> args, ConvertArgs& a,
                                      std::ostream& out, std::ostream& err) {
  cli::App app("syncap cameras convert", kDescription, kFooter);
  app.add_option("IN", a.in, "the cameras to read")->required()->check(CLI::ExistingFile);
  app.add_option("OUT", a.out, "the file to write (.json, .yaml, .yml or .toml)")->required();
  app.add_option_function<double>(
         "--toml-unit-mm", [&a](double mm) { a.toml_unit_mm = mm; },
         "a TOML IN's length unit in mm (1000: metres, Pose2Sim; 1: mm); default: told from "
         "the rig's size (cameras within 100 units of the origin: metres)")
      ->check(cli::number_in(1e-6, 1e6));
  return cli::parse(app, args, out, err, [&a] {
    const std::string ext = util::lower_extension(a.out);
    if (ext != ".json" && ext != ".yaml" && ext != ".yml" && ext != ".toml")
      throw CLI::ValidationError("OUT", "'" + a.out +
                                            "': the extension must be .json, .yaml, "
                                            ".yml or .toml (it names the format)");
  });
}

// A TOML file read once, with the unit given or the one told from it said.
std::vector<sensor::CameraModel> read_input(const ConvertArgs& a, std::ostream& out) {
  if (!sensor::is_toml_camera_file(a.in)) return sensor::read_cameras(a.in);
  const sensor::TomlCameraFile toml = sensor::read_toml_camera_file(a.in, a.toml_unit_mm);
  if (toml.unit_inferred)
    out << util::printf_string(
        "%s: translations taken in %s (told from the rig's size; --toml-unit-mm to say "
        "otherwise)\n",
        a.in.c_str(), toml.length_unit_mm == 1.0 ? "mm" : "metres");
  return sensor::cameras_keeping_lenses(toml.cameras);
}

// Per camera, how closely OpenCV's model holds it (0 for a lens carried exactly).
void print_fits(const std::vector<sensor::CameraModel>& cameras, std::ostream& out) {
  for (const sensor::CameraModel& c : cameras) {
    sensor::ConversionResidual residual;
    sensor::opencv_from_camera(c, &residual);
    out << util::printf_string(
        "camera %d: %dx%d, f %.1f px, centre %.1f %.1f %.1f mm, %s\n", c.id, c.sensor.width_px,
        c.sensor.height_px, c.interior.c / c.sensor.pixel_width_mm, c.exterior.X0, c.exterior.Y0,
        c.exterior.Z0,
        c.opencv_lens ? "OpenCV lens (exact)"
        : c.has_distortion()
            ? util::printf_string("thesis lens (as OpenCV's: up to %.3f px)", residual.max_px)
                  .c_str()
            : "no distortion");
  }
}

int convert(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  ConvertArgs a;
  if (const auto status = parse_convert_args(args, a, out, err)) return *status;
  try {
    const std::vector<sensor::CameraModel> cameras = read_input(a, out);
    const std::string ext = util::lower_extension(a.out);
    std::string text;
    if (ext == ".json") {
      text = sensor::format_cameras(cameras);
    } else if (ext == ".toml") {
      text = calibration::format_calibration_toml(cameras, 0.0);
    } else {
      text = calibration::format_opencv_yaml(cameras);
    }
    io::write_file_atomically(a.out, [&text](std::ostream& file) { file << text; });
    print_fits(cameras, out);
    out << util::printf_string("%zu camera(s) written to %s\n", cameras.size(), a.out.c_str());
    return kExitOk;
  } catch (const sensor::CameraFileError& e) {
    err << kErrorPrefix << e.what() << '\n';
  } catch (const std::exception& e) {
    err << kErrorPrefix << a.out << ": " << e.what() << '\n';
  }
  return kExitUsage;
}

}  // namespace

int cameras_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  if (!args.empty() && args[0] == "convert") return convert(args.subspan(1), out, err);
  const bool help = !args.empty() && (args[0] == "--help" || args[0] == "-h");
  (help ? out : err) << "usage: syncap cameras convert IN OUT [--toml-unit-mm MM]\n"
                        "  convert  a camera file into another format (syncap cameras convert "
                        "--help)\n";
  return help ? kExitOk : kExitUsage;
}

}  // namespace syncap::tools
