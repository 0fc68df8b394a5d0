// write -> parse reproduces a network exactly; includes resolve relative to the including file
// and cycles are reported with the chain.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "estimators/bundle_adjustment_simulation.hpp"
#include "network_equality.hpp"
#include "sdl/sdl.hpp"

namespace syncap::sdl {
namespace {

using scene::ParameterPrior;
using testing::expect_same_network;

void expect_round_trip(const scene::Network& network) {
  const std::string text = write(network);
  const scene::Network parsed = parse_string(text, "written.sdl");
  expect_same_network(network, parsed);
  EXPECT_EQ(write(parsed), text);
}

TEST(SdlRoundTrip, SimulatedWandNetwork) {
  estimators::WandSimulation simulation;
  simulation.frames = 15;
  simulation.blunder_fraction = 0.05;
  const auto simulated = estimators::simulate_wand_network(simulation);
  ASSERT_GT(simulated.network.measurements.size(), 100u);
  expect_round_trip(simulated.network);

  // And with the truth as approximate values: every point and station carries values.
  scene::Network truth = simulated.network;
  for (size_t i = 0; i < truth.points.size(); ++i) {
    truth.points[i].has_approximation = true;
    for (int k = 0; k < 3; ++k) truth.points[i].xyz[k] = simulated.points[i][k];
  }
  for (size_t s = 0; s < truth.stations.size(); ++s) {
    truth.stations[s].exterior = simulated.cameras[s].exterior;
    truth.models[s].interior = simulated.cameras[s].interior;
  }
  expect_round_trip(truth);
}

// Values and names that are hard to print: extremes of double, signed zero, escapes, every
// prior, a station and a point with priors but no values, every design switch off its default.
TEST(SdlRoundTrip, HardValuesAndNames) {
  scene::Network n;
  auto& d = n.design;
  d.simulate = true;
  d.simulation_seed = std::numeric_limits<uint32_t>::max();
  d.unified_least_squares = d.residuals = d.calculate_covariance = d.statistical_tests = false;
  d.force_complete = d.ignore_approximates = d.sort = d.debug = d.wait = true;
  d.output_coefficient_matrix = d.output_misclosures = d.output_corrections = true;
  d.output_messages = false;
  d.output_iterations = d.output_iterations_inline = true;
  d.exact_iterations = 0;
  d.max_iterations = std::numeric_limits<int>::max();
  d.convergence_tolerance = 5e-324;
  d.covariance_stretches = 30;
  d.covariance_cells = std::numeric_limits<int>::max();

  scene::CameraModel model;
  model.name = "m \"0\" \\ \n\t\r\x01\x7f ü";
  model.sensor = {1, 2147483647, 1.7976931348623157e308, 2.2250738585072014e-308};
  model.interior = {0.1 + 0.2, -0.0, 1e-300, -1e300, 123456789.123456789, 1.0 / 3.0, 0, 0, 0, 0};
  model.priors[0] = ParameterPrior::observed(1e-12);
  model.priors[1] = ParameterPrior::fixed();
  n.models.push_back(model);

  scene::Station station;
  station.name = "";
  station.camera_id = -1;
  station.model = model.name;
  station.has_approximation = false;
  station.priors[4] = ParameterPrior::observed(0.25);
  station.priors[5] = ParameterPrior::fixed();
  n.stations.push_back(station);
  station.name = "s1";
  station.has_approximation = true;
  station.exterior = {-1, 2, -3, 4e-17, -5, 6};
  n.stations.push_back(station);

  scene::ObjectPoint point;
  point.name = "free, no value";
  n.points.push_back(point);
  point.name = "priors, no value";
  point.priors = {ParameterPrior::fixed(), ParameterPrior::free(), ParameterPrior::observed(2)};
  n.points.push_back(point);
  point.name = "mixed";
  point.has_approximation = true;
  point.xyz = {1, -2, 3};
  n.points.push_back(point);
  point.name = "control";
  point.priors.fill(ParameterPrior::observed(0.5));
  n.points.push_back(point);

  n.measurements.push_back({"s1", "mixed", -0.5, 1e6, 0.3, int64_t{1} << 53});
  n.measurements.push_back({"s1", "control", 0, 0, 0.3, -(int64_t{1} << 53)});
  n.measurements.push_back({"", "mixed", 1, 2, 1e-3, -1});
  n.distances.push_back({"mixed", "control", 1000.0000000001, 0});
  n.residual_test = {0.001, 0.2, 10, false, 0};
  expect_round_trip(n);
}

TEST(SdlRoundTrip, WriteRefusesNonFiniteValuesNamingThem) {
  scene::Network n;
  scene::ObjectPoint point;
  point.name = "p";
  point.has_approximation = true;
  point.xyz[1] = std::numeric_limits<double>::quiet_NaN();
  n.points.push_back(point);
  try {
    write(n);
    FAIL() << "no error";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "sdl::write: point \"p\" Y: the value is not finite");
  }
}

// A fresh folder for one test's files.
class SdlInclude : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("syncap-sdl-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_ / "parts");
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path file(const std::string& name, const std::string& text) {
    const auto path = dir_ / name;
    std::ofstream(path) << text;
    return path;
  }

  // The ParseError of parse_file(path), or an empty one.
  static ParseError error_of(const std::filesystem::path& path) {
    try {
      parse_file(path);
    } catch (const ParseError& error) {
      return error;
    }
    ADD_FAILURE() << "no ParseError for " << path;
    return ParseError("", 0, 0, "");
  }

  std::filesystem::path dir_;
};

TEST_F(SdlInclude, ResolvesRelativeToTheIncludingFile) {
  file("parts/constants.sdl", "declare f = 6.2\n");
  file("parts/models.sdl", "include \"constants.sdl\"\ncamera_model \"m\" { c = f + 0.01 }\n");
  const auto main = file("main.sdl",
                         "include \"parts/models.sdl\"\n"
                         "station \"s\" { model = \"m\" X0 = f }\n");
  const scene::Network n = parse_file(main);
  ASSERT_EQ(n.models.size(), 1u);
  EXPECT_EQ(n.models[0].interior.c, 6.2 + 0.01);
  ASSERT_EQ(n.stations.size(), 1u);
  EXPECT_EQ(n.stations[0].exterior.X0, 6.2);

  // parse_string resolves relative to the directory of its name.
  const scene::Network m =
      parse_string("include \"parts/models.sdl\"", (dir_ / "virtual.sdl").string());
  EXPECT_EQ(m.models.size(), 1u);
}

TEST_F(SdlInclude, AnIncludeWorksInsideABlock) {
  file("parts/tags.sdl", "SIMULATE SEED 9");
  const auto main = file("main.sdl", "design {\n  include \"parts/tags.sdl\"\n  SORT\n}\n");
  const scene::Network n = parse_file(main);
  EXPECT_TRUE(n.design.simulate);
  EXPECT_EQ(n.design.simulation_seed, 9u);
  EXPECT_TRUE(n.design.sort);
}

TEST_F(SdlInclude, ErrorsNameTheIncludedFile) {
  file("parts/bad.sdl", "declare a = 1\ndeclare b = a +\n");
  const auto main = file("main.sdl", "include \"parts/bad.sdl\"\n");
  const ParseError error = error_of(main);
  EXPECT_EQ(error.file(), (dir_ / "parts/bad.sdl").string());
  EXPECT_EQ(error.line(), 3);
  EXPECT_EQ(error.column(), 1);
  EXPECT_EQ(error.message(), "expected a number, a declared name or '(', found end of file");
}

TEST_F(SdlInclude, CyclesAreReportedWithTheChain) {
  const auto a = file("a.sdl", "declare x = 1\ninclude \"parts/b.sdl\"\n");
  file("parts/b.sdl", "  include \"../a.sdl\"\n");
  const ParseError error = error_of(a);
  EXPECT_EQ(error.file(), (dir_ / "parts/b.sdl").string());
  EXPECT_EQ(error.line(), 1);
  EXPECT_EQ(error.column(), 3);
  EXPECT_EQ(error.message(), "include cycle: " + a.string() + " -> " +
                                 (dir_ / "parts/b.sdl").string() + " -> " + a.string());

  const auto self = file("self.sdl", "include \"self.sdl\"");
  EXPECT_EQ(error_of(self).message(), "include cycle: " + self.string() + " -> " + self.string());
}

TEST_F(SdlInclude, TheSameFileTwiceIsNoCycle) {
  file("parts/point.sdl", "X = 1");
  const auto main = file("main.sdl",
                         "point \"a\" { include \"parts/point.sdl\" }\n"
                         "point \"b\" { include \"parts/point.sdl\" }\n");
  EXPECT_EQ(parse_file(main).points.size(), 2u);
}

TEST_F(SdlInclude, MissingFilesAndDirectoriesAreErrorsAtTheFileName) {
  const auto missing = file("missing.sdl", "\n  include \"parts/none.sdl\"");
  const ParseError error = error_of(missing);
  EXPECT_EQ(error.line(), 2);
  EXPECT_EQ(error.column(), 11);
  EXPECT_EQ(error.message().rfind(
                "include \"parts/none.sdl\": cannot open " + (dir_ / "parts/none.sdl").string(), 0),
            0u)
      << error.message();
  const auto directory = file("directory.sdl", "include \"parts\"");
  EXPECT_EQ(error_of(directory).message(),
            "include \"parts\": cannot read " + (dir_ / "parts").string() + ": not a regular file");
}

}  // namespace
}  // namespace syncap::sdl
