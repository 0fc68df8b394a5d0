// sdl::write: scene::Network as SDL text that parses back to the same network.
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "sdl/grammar.hpp"
#include "sdl/sdl.hpp"

namespace syncap::sdl {
namespace {

using detail::kExteriorNames;
using detail::kInteriorNames;
using detail::kPointNames;
using scene::ParameterMode;
using scene::ParameterPrior;

// The shortest decimal text that reads back to exactly `value` (std::to_chars' guarantee).
std::string number(double value, const std::string& owner) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument("sdl::write: " + owner + ": the value is not finite");
  }
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

std::string in_quotes(const std::string& name) {
  std::string out = "\"";
  for (const char c : name) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\x%02X", static_cast<unsigned char>(c));
      out += escape;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string prior_text(const ParameterPrior& prior, const std::string& owner) {
  switch (prior.mode) {
    case ParameterMode::kFree:
      return "";
    case ParameterMode::kFixed:
      return " fixed";
    case ParameterMode::kObserved:
      break;
  }
  return " sigma " + number(prior.sigma, owner + " sigma");
}

// NAME = value [prior]
std::string parameter(std::string_view name, double value, const ParameterPrior& prior,
                      const std::string& owner) {
  const std::string what = owner + " " + std::string(name);
  return std::string(name) + " = " + number(value, what) + prior_text(prior, what);
}

// NAME prior, for a parameter without an approximate value (nothing when free).
std::string prior_only(std::string_view name, const ParameterPrior& prior,
                       const std::string& owner) {
  if (prior.mode == ParameterMode::kFree) return "";
  return " " + std::string(name) + prior_text(prior, owner + " " + std::string(name));
}

void write_design(const scene::DesignOptions& d, std::string& out) {
  out += "design {\n";
  for (const detail::DesignTag& tag : detail::kDesignTags) {
    const std::string words(tag.words);
    switch (tag.kind) {
      case detail::TagKind::kFlag:
        out += std::string("  ") + (d.*(tag.flag) ? "" : "NO ") + words + "\n";
        break;
      case detail::TagKind::kOutputIterations:
        out += std::string("  ") + (d.output_iterations ? "" : "NO ") + words +
               (d.output_iterations && d.output_iterations_inline ? " INLINE" : "") + "\n";
        break;
      case detail::TagKind::kExactIterations:
        out += d.exact_iterations ? "  " + words + " " + std::to_string(*d.exact_iterations) + "\n"
                                  : "  NO " + words + "\n";
        break;
      case detail::TagKind::kMaxIterations:
        out += "  " + words + " " + std::to_string(d.max_iterations) + "\n";
        break;
      case detail::TagKind::kConvergenceTolerance:
        out += "  " + words + " " + number(d.convergence_tolerance, "design " + words) + "\n";
        break;
      case detail::TagKind::kSeed:
        out += "  " + words + " " + std::to_string(d.simulation_seed) + "\n";
        break;
      case detail::TagKind::kCount:
        out += "  " + words + " " + std::to_string(d.*(tag.count)) + "\n";
        break;
    }
  }
  out += "}\n";
}

void write_model(const scene::CameraModel& model, std::string& out) {
  const std::string owner = "camera_model " + in_quotes(model.name);
  const auto& s = model.sensor;
  out += "\ncamera_model " + in_quotes(model.name) + " {\n";
  out += "  sensor { width = " + std::to_string(s.width_px) +
         " height = " + std::to_string(s.height_px) +
         " pixel_width = " + number(s.pixel_width_mm, owner + " pixel_width") +
         " pixel_height = " + number(s.pixel_height_mm, owner + " pixel_height") + " }\n";
  const auto values = sensor::interior_block(model.interior);
  // c xp yp / k1 k2 k3 / p1 p2 / sc sh: one line per group of the camera model.
  constexpr std::array<size_t, 5> kLineStarts{0, 3, 6, 8, 10};
  for (size_t line = 0; line + 1 < kLineStarts.size(); ++line) {
    out += " ";
    for (size_t i = kLineStarts[line]; i < kLineStarts[line + 1]; ++i) {
      out += " " + parameter(kInteriorNames[i], values[i], model.priors[i], owner);
    }
    out += "\n";
  }
  out += "}\n";
}

void write_station(const scene::Station& station, std::string& out) {
  const std::string owner = "station " + in_quotes(station.name);
  out += "\nstation " + in_quotes(station.name) + " {\n";
  out += "  camera_id = " + std::to_string(station.camera_id) +
         " model = " + in_quotes(station.model) + "\n";
  const auto values = sensor::exterior_block(station.exterior);
  if (station.has_approximation) {
    for (size_t line = 0; line < 2; ++line) {
      out += " ";
      for (size_t i = 3 * line; i < 3 * line + 3; ++i) {
        out += " " + parameter(kExteriorNames[i], values[i], station.priors[i], owner);
      }
      out += "\n";
    }
  } else {
    std::string priors;
    for (size_t i = 0; i < values.size(); ++i) {
      priors += prior_only(kExteriorNames[i], station.priors[i], owner);
    }
    if (!priors.empty()) out += " " + priors + "\n";
  }
  out += "}\n";
}

bool same_prior(const ParameterPrior& a, const ParameterPrior& b) {
  return a.mode == b.mode && (a.mode != ParameterMode::kObserved || a.sigma == b.sigma);
}

void write_point(const scene::ObjectPoint& point, std::string& out) {
  const std::string owner = "point " + in_quotes(point.name);
  const auto& p = point.priors;
  const bool one_prior = same_prior(p[0], p[1]) && same_prior(p[0], p[2]);
  out += "point " + in_quotes(point.name) + " {";
  if (point.has_approximation && one_prior) {
    out += " xyz = <" + number(point.xyz[0], owner + " X") + ", " +
           number(point.xyz[1], owner + " Y") + ", " + number(point.xyz[2], owner + " Z") + ">" +
           prior_text(p[0], owner + " xyz");
  } else {
    for (size_t i = 0; i < 3; ++i) {
      out += point.has_approximation ? " " + parameter(kPointNames[i], point.xyz[i], p[i], owner)
                                     : prior_only(kPointNames[i], p[i], owner);
    }
  }
  out += " }\n";
}

void write_measurements(const std::vector<scene::ImageMeasurement>& measurements,
                        std::string& out) {
  out += "\nmeasurements {\n";
  const scene::ImageMeasurement defaults;
  double sigma_px = defaults.sigma_px;
  int64_t frame = -1;
  for (size_t i = 0; i < measurements.size(); ++i) {
    const auto& m = measurements[i];
    const std::string owner = "measurement " + std::to_string(i);
    // The block's settings change only where the measurements' values do.
    if (i == 0 || m.sigma_px != sigma_px) {
      sigma_px = m.sigma_px;
      out += "  sigma = " + number(sigma_px, owner + " sigma") + "\n";
    }
    if (i == 0 || m.frame_number != frame) {
      frame = m.frame_number;
      out += "  frame = " + std::to_string(frame) + "\n";
    }
    out += "  " + in_quotes(m.station) + " " + in_quotes(m.point) + " <" +
           number(m.u, owner + " u") + ", " + number(m.v, owner + " v") + ">\n";
  }
  out += "}\n";
}

void write_constraints(const std::vector<scene::DistanceConstraint>& distances, std::string& out) {
  out += "\nconstraints {\n";
  for (size_t i = 0; i < distances.size(); ++i) {
    const auto& d = distances[i];
    const std::string owner = "distance " + std::to_string(i);
    out += "  distance " + in_quotes(d.point_a) + " " + in_quotes(d.point_b) + " = " +
           number(d.distance, owner) + " sigma " + number(d.sigma, owner + " sigma") + "\n";
  }
  out += "}\n";
}

void write_residual_test(const scene::ResidualTest& t, std::string& out) {
  out += "\nresidual_test {\n";
  out += "  alpha_variance = " + number(t.alpha_variance, "alpha_variance") + "\n";
  out += "  alpha_goodness = " + number(t.alpha_goodness, "alpha_goodness") + "\n";
  out += "  critical_snooping = " + number(t.critical_snooping, "critical_snooping") + "\n";
  out +=
      std::string("  iterative_rejection = ") + (t.iterative_rejection ? "true" : "false") + "\n";
  out += "  max_rejections = " + std::to_string(t.max_rejections) + "\n";
  out += std::string("  snoop_with_a_posteriori_sigma0 = ") +
         (t.snoop_with_a_posteriori_sigma0 ? "true" : "false") + "\n";
  out += std::string("  reject_per_point = ") + (t.reject_per_point ? "true" : "false") + "\n";
  out += "}\n";
}

}  // namespace

std::string write(const scene::Network& network) {
  std::string out =
      "// A syncap scene (docs/reference/sdl.md). Units: mm, rad, pixels (u right, v down).\n\n";
  write_design(network.design, out);
  for (const auto& model : network.models) write_model(model, out);
  for (const auto& station : network.stations) write_station(station, out);
  if (!network.points.empty()) out += "\n";
  for (const auto& point : network.points) write_point(point, out);
  write_measurements(network.measurements, out);
  write_constraints(network.distances, out);
  write_residual_test(network.residual_test, out);
  return out;
}

void write_file(const scene::Network& network, const std::filesystem::path& path) {
  const std::string text = write(network);
  std::ofstream file(path, std::ios::binary);
  file << text;
  file.close();
  if (!file) throw std::runtime_error("sdl::write_file: cannot write " + path.string());
}

}  // namespace syncap::sdl
