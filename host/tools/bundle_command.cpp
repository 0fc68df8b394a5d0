#include "bundle_command.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>

#include "estimators/bootstrap.hpp"
#include "estimators/bundle_adjustment.hpp"
#include "sdl/sdl.hpp"
#include "sensor/camera_model.hpp"
#include "subcommand.hpp"
#include "syncap/cli/options.hpp"
#include "util/printf_string.hpp"

namespace syncap::tools {
namespace {

constexpr const char* kErrorPrefix = "syncap bundle: ";
constexpr const char* kInteriorNames[] = {"c",  "xp", "yp", "k1", "k2",
                                          "k3", "p1", "p2", "sc", "sh"};
constexpr const char* kExteriorNames[] = {"X0", "Y0", "Z0", "omega", "phi", "kappa"};
constexpr const char* kPointNames[] = {"X", "Y", "Z"};

struct BundleArgs {
  std::string file;
  std::optional<std::filesystem::path> out_dir;
};

// What the scene's design block asks for, above the options in --help.
constexpr const char* kDescription =
    "Reads the scene FILE.sdl (docs/reference/sdl.md), adjusts it (self-calibrating bundle "
    "adjustment,\n"
    "docs/design/calibration.md) as its design block says and prints the summary. Design tags:\n"
    "  SIMULATE            measurements and distances generated from the approximate values\n"
    "                      with noise of their sigmas (seed: SEED n) before adjusting\n"
    "  SORT                models, stations and points sorted by name\n"
    "  OUTPUT MESSAGES     the adjustment's messages before the summary\n"
    "  OUTPUT MISCLOSURES  per measurement: approximate projection - measured [px]\n"
    "  OUTPUT CORRECTIONS  per parameter: adjusted - approximate value\n"
    "  OUTPUT COEFFICIENT MATRIX  d(u, v)/d(parameters) at the adjusted values, as triplets\n"
    "  RESIDUALS           per measurement residuals and w (DIR/residuals.tsv, with --out)\n"
    "  DEBUG               the network's size and the design as read\n"
    "The OUTPUT tables go to DIR/NAME.tsv with --out, else to stdout after the summary.\n";

// The exit statuses, below the options in --help.
constexpr const char* kFooter =
    "Exit status: 0 adjusted and converged, 1 not converged, 2 usage error or a scene that does\n"
    "not parse or cannot be adjusted (the message names file, line and column or the element).";

// Parses into `parsed`; an exit status when the run is over already (help, usage error).
std::optional<int> parse_bundle_args(std::span<const std::string> args, BundleArgs& parsed,
                                     std::ostream& out, std::ostream& err) {
  cli::App app("syncap bundle", kDescription, kFooter);
  app.add_option("FILE", parsed.file, "the scene, FILE.sdl")->required();
  app.add_option_function<std::string>(
         "--out", [&parsed](const std::string& dir) { parsed.out_dir = dir; },
         "writes DIR/adjusted.sdl (the adjusted network), DIR/summary.txt and the tables")
      ->option_text("DIR");
  return cli::parse(app, args, out, err);
}

using util::printf_string;

template <typename Item>
std::map<std::string, const Item*> by_name(const std::vector<Item>& items) {
  std::map<std::string, const Item*> index;
  for (const Item& item : items) index.emplace(item.name, &item);
  return index;
}

// The camera of a station with its model's values, or nothing when a name is unknown.
std::optional<sensor::CameraModel> camera_of(const scene::Network& network,
                                             const std::string& station_name) {
  const auto station = std::find_if(network.stations.begin(), network.stations.end(),
                                    [&](const auto& s) { return s.name == station_name; });
  if (station == network.stations.end()) return std::nullopt;
  const auto model = std::find_if(network.models.begin(), network.models.end(),
                                  [&](const auto& m) { return m.name == station->model; });
  if (model == network.models.end()) return std::nullopt;
  sensor::CameraModel camera;
  camera.id = station->camera_id;
  camera.sensor = model->sensor;
  camera.interior = model->interior;
  camera.exterior = station->exterior;
  return camera;
}

Eigen::Vector3d xyz_of(const scene::ObjectPoint& point) {
  return {point.xyz[0], point.xyz[1], point.xyz[2]};
}

void sort_by_name(scene::Network& network) {
  const auto by = [](const auto& a, const auto& b) { return a.name < b.name; };
  std::stable_sort(network.models.begin(), network.models.end(), by);
  std::stable_sort(network.stations.begin(), network.stations.end(), by);
  std::stable_sort(network.points.begin(), network.points.end(), by);
}

// OUTPUT MISCLOSURES: approximate projection - measured, before the adjustment.
std::string misclosures_table(const scene::Network& network) {
  std::string table = "# station\tpoint\tframe\tmisclosure_u_px\tmisclosure_v_px\n";
  const auto points = by_name(network.points);
  for (const auto& m : network.measurements) {
    const auto camera = camera_of(network, m.station);
    const auto point = points.find(m.point);
    std::string values = "-\t-";
    if (camera && point != points.end() && point->second->has_approximation) {
      const auto projection = camera->project(xyz_of(*point->second));
      if (projection.ok()) {
        values =
            printf_string("%.6f\t%.6f", projection.pixel.x() - m.u, projection.pixel.y() - m.v);
      }
    }
    table +=
        m.station + "\t" + m.point + "\t" + std::to_string(m.frame_number) + "\t" + values + "\n";
  }
  return table;
}

void add_corrections(std::string& table, const std::string& kind, const std::string& name,
                     const char* const* names, const double* before, const double* after,
                     const double* sigma, size_t count) {
  for (size_t i = 0; i < count; ++i) {
    table += kind + "\t" + name + "\t" + names[i] +
             printf_string("\t%.10g\t%.10g\t%.6g\t%.6g\n", before[i], after[i],
                           after[i] - before[i], sigma[i]);
  }
}

// OUTPUT CORRECTIONS: adjusted - approximate value of every camera parameter and point.
std::string corrections_table(const scene::Network& input, const scene::Network& adjusted,
                              const estimators::BundleAdjustmentResult& result) {
  std::string table = "# kind\tname\tparameter\tapproximate\tadjusted\tcorrection\tsigma\n";
  for (size_t i = 0; i < input.models.size() && i < result.models.size(); ++i) {
    const auto before = sensor::interior_block(input.models[i].interior);
    const auto after = sensor::interior_block(adjusted.models[i].interior);
    add_corrections(table, "model", input.models[i].name, kInteriorNames, before.data(),
                    after.data(), result.models[i].interior_sigma.data(), before.size());
  }
  for (size_t i = 0; i < input.stations.size() && i < result.stations.size(); ++i) {
    const auto before = sensor::exterior_block(input.stations[i].exterior);
    const auto after = sensor::exterior_block(adjusted.stations[i].exterior);
    add_corrections(table, "station", input.stations[i].name, kExteriorNames, before.data(),
                    after.data(), result.stations[i].exterior_sigma.data(), before.size());
  }
  for (size_t i = 0; i < input.points.size() && i < result.points.size(); ++i) {
    if (!input.points[i].has_approximation || !result.points[i].adjusted) continue;
    add_corrections(table, "point", input.points[i].name, kPointNames, input.points[i].xyz.data(),
                    adjusted.points[i].xyz.data(), result.points[i].sigma.data(), 3);
  }
  return table;
}

// RESIDUALS: per measurement, after the adjustment.
std::string residuals_table(const scene::Network& network,
                            const estimators::BundleAdjustmentResult& result) {
  std::string table =
      "# station\tpoint\tframe\tresidual_u_px\tresidual_v_px\tw_u\tw_v\tredundancy_u\t"
      "redundancy_v\tstatus\n";
  constexpr const char* kStatus[] = {"accepted", "blunder", "undetermined"};
  for (size_t i = 0; i < network.measurements.size() && i < result.measurements.size(); ++i) {
    const auto& m = network.measurements[i];
    const auto& r = result.measurements[i];
    table += m.station + "\t" + m.point + "\t" + std::to_string(m.frame_number) +
             printf_string("\t%.6f\t%.6f\t%.4f\t%.4f\t%.4f\t%.4f\t", r.residual_u, r.residual_v,
                           r.w_u, r.w_v, r.redundancy_u, r.redundancy_v) +
             kStatus[static_cast<int>(r.status)] + "\n";
  }
  return table;
}

// OUTPUT COEFFICIENT MATRIX: the image measurements' rows of the design matrix A at the
// adjusted values (unweighted, pixel per parameter unit), as row, column, value triplets.
std::string coefficient_matrix_table(const scene::Network& adjusted) {
  const size_t models = adjusted.models.size();
  const size_t stations = adjusted.stations.size();
  std::map<std::string, size_t> model_column, station_column, point_column;
  std::string table =
      "# the design matrix A of the image measurements at the adjusted values: row 2 m (u) and\n"
      "# 2 m + 1 (v) of measurement m, columns below; unweighted, [px / parameter unit]\n";
  for (size_t i = 0; i < models; ++i) {
    model_column[adjusted.models[i].name] = 10 * i;
    table += printf_string("# columns %zu-%zu: model ", 10 * i, 10 * i + 9) +
             adjusted.models[i].name + " c xp yp k1 k2 k3 p1 p2 sc sh\n";
  }
  for (size_t i = 0; i < stations; ++i) {
    const size_t first = 10 * models + 6 * i;
    station_column[adjusted.stations[i].name] = first;
    table += printf_string("# columns %zu-%zu: station ", first, first + 5) +
             adjusted.stations[i].name + " X0 Y0 Z0 omega phi kappa\n";
  }
  for (size_t i = 0; i < adjusted.points.size(); ++i) {
    point_column[adjusted.points[i].name] = 10 * models + 6 * stations + 3 * i;
  }
  table +=
      printf_string("# columns %zu-: points X Y Z in the network's order\n# row\tcolumn\tvalue\n",
                    10 * models + 6 * stations);
  const auto points = by_name(adjusted.points);
  for (size_t m = 0; m < adjusted.measurements.size(); ++m) {
    const auto& meas = adjusted.measurements[m];
    const auto camera = camera_of(adjusted, meas.station);
    const auto point = points.find(meas.point);
    if (!camera || point == points.end() || !point->second->has_approximation) continue;
    const auto j = camera->project_with_jacobians(xyz_of(*point->second));
    if (!j.projection.ok()) continue;
    const std::string& model =
        std::find_if(adjusted.stations.begin(), adjusted.stations.end(), [&](const auto& s) {
          return s.name == meas.station;
        })->model;
    for (int row = 0; row < 2; ++row) {
      const auto add = [&](size_t column, double value) {
        if (value != 0.0) table += printf_string("%zu\t%zu\t%.10g\n", 2 * m + row, column, value);
      };
      for (int k = 0; k < 10; ++k) add(model_column[model] + k, j.d_interior(row, k));
      for (int k = 0; k < 6; ++k) add(station_column[meas.station] + k, j.d_exterior(row, k));
      for (int k = 0; k < 3; ++k) add(point_column[meas.point] + k, j.d_point(row, k));
    }
  }
  return table;
}

std::string debug_text(const scene::Network& network) {
  const auto& d = network.design;
  return printf_string(
      "debug: %zu camera models, %zu stations, %zu points, %zu measurements, %zu distances\n"
      "debug: design: simulate %d (seed %u), unified %d, covariance %d, tests %d, force complete "
      "%d, exact iterations %d, max iterations %d, tolerance %g, ignore approximates %d, sort "
      "%d\n",
      network.models.size(), network.stations.size(), network.points.size(),
      network.measurements.size(), network.distances.size(), d.simulate, d.simulation_seed,
      d.unified_least_squares, d.calculate_covariance, d.statistical_tests, d.force_complete,
      d.exact_iterations.value_or(-1), d.max_iterations, d.convergence_tolerance,
      d.ignore_approximates, d.sort);
}

bool write_text(const std::filesystem::path& path, const std::string& text, std::ostream& err) {
  std::ofstream file(path, std::ios::binary);
  file << text;
  file.close();
  if (!file) err << kErrorPrefix << "cannot write " << path.string() << '\n';
  return static_cast<bool>(file);
}

// An OUTPUT table: to DIR/NAME.tsv with --out, else to stdout under a heading.
bool emit_table(const BundleArgs& args, const std::string& name, const std::string& table,
                std::ostream& out, std::ostream& err) {
  if (!args.out_dir) {
    out << "\n# " << name << '\n' << table;
    return true;
  }
  return write_text(*args.out_dir / (name + ".tsv"), table, err);
}

int run_bundle(const BundleArgs& args, std::ostream& out, std::ostream& err) {
  scene::Network network = sdl::parse_file(args.file);
  if (network.stations.empty() && network.points.empty()) {
    // An empty (or comment-only) file parses as the default network: nothing was adjusted.
    err << kErrorPrefix << args.file
        << ": the scene has no station and no point: nothing to adjust\n";
    return kExitUsage;
  }
  const auto& design = network.design;
  if (design.sort) sort_by_name(network);
  if (design.simulate) simulate_observations(network);
  if (design.debug) out << debug_text(network);
  if (design.wait) err << kErrorPrefix << "WAIT is accepted and ignored (no pauses here)\n";

  estimators::BundleOptions options;
  options.log_iterations = design.output_iterations;  // Ceres prints them, one line each
  const estimators::BundleAdjustmentResult result = estimators::adjust(network, options);
  scene::Network adjusted = estimators::with_adjusted_values(network, result);
  adjusted.design.simulate = false;

  if (design.output_messages) {
    for (const std::string& message : result.messages) out << message << '\n';
  }
  const std::string summary = estimators::format_summary(result);
  out << summary;
  bool written = true;
  if (args.out_dir) {
    std::error_code error;
    std::filesystem::create_directories(*args.out_dir, error);
    if (error) {
      err << kErrorPrefix << "cannot create " << args.out_dir->string() << ": " << error.message()
          << '\n';
      return kExitUsage;
    }
    written &= write_text(*args.out_dir / "adjusted.sdl", sdl::write(adjusted), err);
    written &= write_text(*args.out_dir / "summary.txt", summary, err);
    if (design.residuals) {
      written &= write_text(*args.out_dir / "residuals.tsv", residuals_table(network, result), err);
    }
  }
  if (design.output_misclosures) {
    written &= emit_table(args, "misclosures", misclosures_table(network), out, err);
  }
  if (design.output_corrections) {
    written &=
        emit_table(args, "corrections", corrections_table(network, adjusted, result), out, err);
  }
  if (design.output_coefficient_matrix) {
    written &= emit_table(args, "coefficient-matrix", coefficient_matrix_table(adjusted), out, err);
  }
  if (!written) return kExitUsage;
  if (!result.converged) {
    err << kErrorPrefix << "the adjustment did not converge: " << result.termination << '\n';
    return kExitReportedErrors;
  }
  return kExitOk;
}

}  // namespace

void simulate_observations(scene::Network& network) {
  std::mt19937 rng(network.design.simulation_seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const auto points = by_name(network.points);
  const auto approximate_point = [&](const std::string& name, const std::string& place) {
    const auto point = points.find(name);
    if (point == points.end()) throw std::invalid_argument(place + ": unknown point " + name);
    if (!point->second->has_approximation) {
      throw std::invalid_argument(place + ": point " + name +
                                  " has no coordinates to simulate from");
    }
    return xyz_of(*point->second);
  };
  for (size_t i = 0; i < network.measurements.size(); ++i) {
    auto& m = network.measurements[i];
    const std::string place = "SIMULATE: measurement " + std::to_string(i) + " (station " +
                              m.station + ", point " + m.point + ")";
    const auto camera = camera_of(network, m.station);
    if (!camera) throw std::invalid_argument(place + ": unknown station or camera model");
    const auto projection = camera->project(approximate_point(m.point, place));
    if (!projection.ok()) {
      throw std::invalid_argument(place + ": the point does not project into the camera");
    }
    m.u = projection.pixel.x() + m.sigma_px * gauss(rng);
    m.v = projection.pixel.y() + m.sigma_px * gauss(rng);
  }
  for (size_t i = 0; i < network.distances.size(); ++i) {
    auto& d = network.distances[i];
    const std::string place =
        "SIMULATE: distance " + std::to_string(i) + " (" + d.point_a + ", " + d.point_b + ")";
    const Eigen::Vector3d a = approximate_point(d.point_a, place);
    const Eigen::Vector3d b = approximate_point(d.point_b, place);
    d.distance = (a - b).norm() + d.sigma * gauss(rng);
  }
}

int bundle_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  BundleArgs parsed;
  if (const auto status = parse_bundle_args(args, parsed, out, err)) return *status;
  try {
    return run_bundle(parsed, out, err);
  } catch (const sdl::ParseError& error) {
    err << kErrorPrefix << error.what() << '\n';
  } catch (const estimators::NetworkError& error) {
    err << kErrorPrefix << parsed.file << ": " << error.what() << '\n';
  } catch (const std::invalid_argument& error) {
    err << kErrorPrefix << parsed.file << ": " << error.what() << '\n';
  }
  return kExitUsage;
}

}  // namespace syncap::tools
