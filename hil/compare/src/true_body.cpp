#include "true_body.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include "input_error.hpp"

namespace syncap::compare {
namespace {

Eigen::Vector3d vector_at(const nlohmann::json& v) {
  return {v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>()};
}

TrueEllipsoid ellipsoid_of(const nlohmann::json& e) {
  TrueEllipsoid ellipsoid{e.value("segment", ""), vector_at(e.at("centre_mm")),
                          Eigen::Matrix3d::Zero(), vector_at(e.at("radii_mm"))};
  for (int c = 0; c < 3; ++c) ellipsoid.axes.col(c) = vector_at(e.at("axes").at(c));
  return ellipsoid;
}

}  // namespace

std::map<long, TrueBody> read_true_bodies(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot read");
  std::map<long, TrueBody> bodies;
  std::string line;
  for (long number = 1; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    try {
      const nlohmann::json j = nlohmann::json::parse(line);
      TrueBody& body = bodies[j.at("frame").get<long>()];
      if (j.contains("ellipsoids")) {
        for (const nlohmann::json& e : j.at("ellipsoids"))
          body.ellipsoids.push_back(ellipsoid_of(e));
      }
      if (j.contains("joints")) {
        for (const auto& [name, p] : j.at("joints").items()) body.joints_mm[name] = vector_at(p);
      }
    } catch (const nlohmann::json::exception& e) {
      fail_at(file.string(), number, e.what());
    }
  }
  return bodies;
}

}  // namespace syncap::compare
