// The SDL grammar (docs/reference/sdl.md): what each statement sets, expressions, comments, design
// tags, and the errors with file, line and column.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "sdl/sdl.hpp"

namespace syncap::sdl {
namespace {

using scene::ParameterMode;

// A complete small scene, one of each statement.
constexpr const char* kScene = R"(// a small scene
declare f = 6.2      # camera constant [mm]
declare pitch = 0.0067
design {
  SIMULATE SEED 7
  NO CALCULATE COVARIANCE
  EXACT ITERATIONS 5
  OUTPUT ITERATIONS INLINE
  OUTPUT MISCLOSURES
  MAX ITERATIONS 20
  CONVERGENCE TOLERANCE 1e-12
  COVARIANCE STRETCHES 12
}
camera_model "m0" {
  sensor { width = 1280 height = 1024 pixel_width = pitch pixel_height = pitch }
  c = f + 0.01 sigma 0.1
  xp = 0.02  yp = -0.03 fixed
  k1 = 5.6e-3 k2 = 2e-5 k3 fixed
}
station "cam0" {
  camera_id = 3 model = "m0"
  X0 = 4200 Y0 = 0 Z0 = 2300 fixed
  omega = 90 * deg phi = 0 kappa = -pi / 2 sigma 0.001
}
point "P1" { xyz = <1, 2, 3> fixed }
point "P2" { X = 10 sigma 0.5 Z = -1 }
point "P3" { }
/* block
   comment */
measurements {
  "cam0" "P1" <640.5, 512.25>
  sigma = 0.2 frame = 17
  "cam0" "P2" <1, 2>
}
constraints {
  distance "P1" "P2" = 400 sigma 0.1
  distance "P2" "P3" = 1000
}
residual_test {
  alpha_variance = 0.01 alpha_goodness = 0.1 critical_snooping = 4.9
  iterative_rejection = false max_rejections = 12 snoop_with_a_posteriori_sigma0 = true
}
)";

TEST(SdlParser, ReadsEveryStatement) {
  const scene::Network n = parse_string(kScene);
  const auto& d = n.design;
  EXPECT_TRUE(d.simulate);
  EXPECT_EQ(d.simulation_seed, 7u);
  EXPECT_FALSE(d.calculate_covariance);
  EXPECT_TRUE(d.unified_least_squares);  // untouched: the default
  EXPECT_EQ(d.exact_iterations, 5);
  EXPECT_TRUE(d.output_iterations);
  EXPECT_TRUE(d.output_iterations_inline);
  EXPECT_TRUE(d.output_misclosures);
  EXPECT_EQ(d.max_iterations, 20);
  EXPECT_EQ(d.convergence_tolerance, 1e-12);
  EXPECT_EQ(d.covariance_stretches, 12);
  EXPECT_EQ(d.covariance_cells, 0);  // untouched: the default

  ASSERT_EQ(n.models.size(), 1u);
  const auto& m = n.models[0];
  EXPECT_EQ(m.name, "m0");
  EXPECT_EQ(m.sensor.width_px, 1280);
  EXPECT_EQ(m.sensor.height_px, 1024);
  EXPECT_EQ(m.sensor.pixel_width_mm, 0.0067);
  EXPECT_EQ(m.interior.c, 6.2 + 0.01);
  EXPECT_EQ(m.priors[0].mode, ParameterMode::kObserved);
  EXPECT_EQ(m.priors[0].sigma, 0.1);
  EXPECT_EQ(m.interior.yp, -0.03);
  EXPECT_EQ(m.priors[2].mode, ParameterMode::kFixed);
  EXPECT_EQ(m.priors[1].mode, ParameterMode::kFree);
  EXPECT_EQ(m.interior.k1, 5.6e-3);
  EXPECT_EQ(m.interior.k3, 0.0);
  EXPECT_EQ(m.priors[5].mode, ParameterMode::kFixed);

  ASSERT_EQ(n.stations.size(), 1u);
  const auto& s = n.stations[0];
  EXPECT_EQ(s.camera_id, 3);
  EXPECT_EQ(s.model, "m0");
  EXPECT_TRUE(s.has_approximation);
  EXPECT_EQ(s.exterior.X0, 4200.0);
  EXPECT_EQ(s.priors[2].mode, ParameterMode::kFixed);
  EXPECT_EQ(s.exterior.omega, 90 * std::numbers::pi / 180);
  EXPECT_EQ(s.exterior.kappa, -std::numbers::pi / 2);
  EXPECT_EQ(s.priors[5].mode, ParameterMode::kObserved);

  ASSERT_EQ(n.points.size(), 3u);
  EXPECT_EQ(n.points[0].xyz, (std::array<double, 3>{1, 2, 3}));
  for (const auto& prior : n.points[0].priors) EXPECT_EQ(prior.mode, ParameterMode::kFixed);
  EXPECT_EQ(n.points[1].xyz, (std::array<double, 3>{10, 0, -1}));
  EXPECT_EQ(n.points[1].priors[0].sigma, 0.5);
  EXPECT_EQ(n.points[1].priors[2].mode, ParameterMode::kFree);
  EXPECT_TRUE(n.points[1].has_approximation);
  EXPECT_FALSE(n.points[2].has_approximation);

  ASSERT_EQ(n.measurements.size(), 2u);
  EXPECT_EQ(n.measurements[0].u, 640.5);
  EXPECT_EQ(n.measurements[0].v, 512.25);
  EXPECT_EQ(n.measurements[0].sigma_px, 0.1);  // the default before `sigma =`
  EXPECT_EQ(n.measurements[0].frame_number, -1);
  EXPECT_EQ(n.measurements[1].sigma_px, 0.2);
  EXPECT_EQ(n.measurements[1].frame_number, 17);

  ASSERT_EQ(n.distances.size(), 2u);
  EXPECT_EQ(n.distances[0].distance, 400.0);
  EXPECT_EQ(n.distances[0].sigma, 0.1);
  EXPECT_EQ(n.distances[1].sigma, 0.0);

  EXPECT_EQ(n.residual_test.alpha_variance, 0.01);
  EXPECT_EQ(n.residual_test.critical_snooping, 4.9);
  EXPECT_FALSE(n.residual_test.iterative_rejection);
  EXPECT_EQ(n.residual_test.max_rejections, 12);
  EXPECT_TRUE(n.residual_test.snoop_with_a_posteriori_sigma0);
}

TEST(SdlParser, AnEmptySceneIsTheDefaultNetwork) {
  const scene::Network n = parse_string("  // nothing but a comment\n");
  EXPECT_TRUE(n.models.empty());
  EXPECT_FALSE(n.design.simulate);
  EXPECT_TRUE(n.design.calculate_covariance);
  EXPECT_EQ(n.residual_test.critical_snooping, scene::ResidualTest{}.critical_snooping);
}

double value_of(const std::string& expression) {
  const scene::Network n =
      parse_string("declare two = 2\ndeclare half = 0.5\npoint \"p\" { X = " + expression + " }");
  return n.points.at(0).xyz[0];
}

TEST(SdlParser, ExpressionsFollowArithmeticPrecedence) {
  EXPECT_EQ(value_of("1 + 2 * 3"), 7.0);
  EXPECT_EQ(value_of("(1 + 2) * 3"), 9.0);
  EXPECT_EQ(value_of("-(2 - 5) / 2"), 1.5);
  EXPECT_EQ(value_of("10 - 4 - 3"), 3.0);  // left to right
  EXPECT_EQ(value_of("8 / 4 / 2"), 1.0);
  EXPECT_EQ(value_of("--3"), 3.0);
  EXPECT_EQ(value_of("two * half + two"), 3.0);
  EXPECT_EQ(value_of("180 * deg"), std::numbers::pi);
  EXPECT_EQ(value_of(".5e1"), 5.0);
  EXPECT_EQ(value_of("1.E2"), 100.0);
  EXPECT_EQ(value_of("6.2 + 0.01"), 6.2 + 0.01);
}

TEST(SdlParser, DesignTagsSwitchOnAndOffInOrder) {
  const scene::Network n = parse_string(R"(
design { FORCE COMPLETE IGNORE APPROXIMATES SORT DEBUG WAIT OUTPUT COEFFICIENT MATRIX
         OUTPUT CORRECTIONS NO OUTPUT MESSAGES NO RESIDUALS NO STATISTICAL TESTS
         NO UNIFIED LEAST SQUARES OUTPUT ITERATIONS EXACT ITERATIONS 3 }
design { NO EXACT ITERATIONS NO WAIT })");
  const auto& d = n.design;
  EXPECT_TRUE(d.force_complete);
  EXPECT_TRUE(d.ignore_approximates);
  EXPECT_TRUE(d.sort);
  EXPECT_TRUE(d.debug);
  EXPECT_FALSE(d.wait);  // the second block switched it off again
  EXPECT_TRUE(d.output_coefficient_matrix);
  EXPECT_TRUE(d.output_corrections);
  EXPECT_FALSE(d.output_messages);
  EXPECT_FALSE(d.residuals);
  EXPECT_FALSE(d.statistical_tests);
  EXPECT_FALSE(d.unified_least_squares);
  EXPECT_TRUE(d.output_iterations);
  EXPECT_FALSE(d.output_iterations_inline);
  EXPECT_FALSE(d.exact_iterations.has_value());
}

TEST(SdlParser, StringsCarryEscapes) {
  const scene::Network n = parse_string(R"(point "a \"quoted\" \\ name\n\t\x01" { })");
  EXPECT_EQ(n.points.at(0).name, std::string("a \"quoted\" \\ name\n\t\x01"));
}

// What parse_string("<string>") throws for `text`: "LINE:COLUMN: MESSAGE".
std::string error_of(const std::string& text) {
  try {
    parse_string(text, "scene.sdl");
  } catch (const ParseError& error) {
    EXPECT_EQ(error.file(), "scene.sdl");
    EXPECT_EQ(std::string(error.what()), "scene.sdl:" + std::to_string(error.line()) + ":" +
                                             std::to_string(error.column()) + ": " +
                                             error.message());
    return std::to_string(error.line()) + ":" + std::to_string(error.column()) + ": " +
           error.message();
  }
  ADD_FAILURE() << "no ParseError for:\n" << text;
  return "";
}

TEST(SdlParser, ErrorsNameLineColumnAndWhatWasExpected) {
  struct Case {
    std::string text;
    std::string error;
  };
  const Case cases[] = {
      {"camera_modl \"m\" {}",
       "1:1: expected a statement (include, declare, design, camera_model, station, point, "
       "measurements, constraints, residual_test), found identifier 'camera_modl'"},
      {"point \"p\" {\n  X = 1 +\n}", "3:1: expected a number, a declared name or '(', found '}'"},
      {"point \"p\" { X = 1 / (2 - 2) }", "1:19: division by zero"},
      {"point \"p\" { X = 1e308 * 10 }", "1:23: the expression's value is not finite"},
      {"point \"p\" { X = 1e999 }", "1:17: number 1e999 is out of the range of a double"},
      {"point \"p\" { X = 1e+ }",
       "1:20: malformed number '1e+': expected the digits of the exponent"},
      {"point \"p\" { X = 12abc }", "1:19: malformed number: unexpected 'a' after '12'"},
      {"point \"p\" { X = f }",
       "1:17: unknown name 'f' in an expression: declare it first (declare f = ...)"},
      {"point \"p\" { W = 1 }",
       "1:13: expected X, Y, Z, xyz or '}' in point \"p\", found "
       "identifier 'W'"},
      {"point \"p\" { X 1 }",
       "1:15: expected '=' or free, fixed, sigma after X in point \"p\", found number 1"},
      {"point \"p\" {\n X = 1\n",
       "3:1: expected '}' to close point \"p\" (opened at scene.sdl:1:11)"},
      {"point \"p\" {}\npoint \"p\" {}", "2:7: point \"p\" is already defined at scene.sdl:1:7"},
      {"point p {}", "1:7: expected the point's name in quotes, found identifier 'p'"},
      {"point \"p\nq\" {}", "1:7: unterminated string: expected '\"' before the end of the line"},
      {"point \"p\\q\" {}",
       "1:9: unknown escape in a string: expected \\\" \\\\ \\n \\t \\r or \\xHH"},
      {"point \"p\" {} /* open", "1:14: unterminated comment: expected '*/'"},
      {"point \"p\" {} $", "1:14: unexpected character '$'"},
      {std::string("point \"p\" {} \x01", 15), "1:14: unexpected character '\\x01'"},
      {"design { SIMULATE OUTPUT FOO }",
       "1:26: expected one of COEFFICIENT, MISCLOSURES, CORRECTIONS, MESSAGES, ITERATIONS after "
       "'OUTPUT', found identifier 'FOO'"},
      {"design { simulate }",
       "1:10: expected a design tag (SIMULATE, SEED, UNIFIED, RESIDUALS, CALCULATE, STATISTICAL, "
       "FORCE, EXACT, MAX, CONVERGENCE, COVARIANCE, IGNORE, SORT, OUTPUT, DEBUG, WAIT) or '}', "
       "found "
       "identifier 'simulate'"},
      {"design { NO MAX ITERATIONS 3 }",
       "1:13: NO cannot precede MAX ITERATIONS (give it a value "
       "instead)"},
      {"design { EXACT ITERATIONS 2.5 }", "1:27: EXACT ITERATIONS must be an integer, found 2.5"},
      {"design { SEED -1 }", "1:15: SEED must be in [0, 4294967295], found -1"},
      {"declare pi = 3", "1:9: 'pi' is reserved and cannot be declared"},
      {"declare a = 1\ndeclare a = 2", "2:9: 'a' is already declared at scene.sdl:1:9"},
      {"station \"s\" { model = \"m\" }",
       "1:23: station \"s\": no camera_model \"m\" in the scene"},
      {"point \"p\" {} measurements { \"s\" \"p\" <1, 2> }",
       "1:29: measurement: no station \"s\" in the scene"},
      {"point \"p\" {} constraints { distance \"p\" \"q\" = 1 }",
       "1:41: distance: no point \"q\" in the scene"},
      {"camera_model \"m\" { sensor { width = 1 } }\nstation \"s\" { model = \"m\" }\npoint \"p\" "
       "{}\nmeasurements { \"s\" \"p\" }",
       "4:20: measurement without <u, v>: give the coordinates, or SIMULATE in the design block"},
      {"residual_test { iterative_rejection = 1 }",
       "1:39: expected true or false for iterative_rejection, found number 1"},
      {"include \"missing.sdl\"", "1:9: include \"missing.sdl\": cannot open missing.sdl: "},
      {"include missing",
       "1:9: expected a file name in quotes after 'include', found identifier "
       "'missing'"},
      {"point \"p\" { X = " + std::string(300, '(') + "1" + std::string(300, ')') + " }",
       "1:217: expression nested deeper than 200 levels"},
  };
  for (const Case& c : cases) {
    const std::string error = error_of(c.text);
    EXPECT_EQ(error.substr(0, c.error.size()), c.error) << "for:\n" << c.text;
  }
}

TEST(SdlParser, MeasurementsWithoutCoordinatesAreFineUnderSimulate) {
  const scene::Network n = parse_string(R"(
camera_model "m" { } station "s" { model = "m" } point "p" { }
measurements { "s" "p" }
design { SIMULATE })");
  ASSERT_EQ(n.measurements.size(), 1u);
  EXPECT_EQ(n.measurements[0].u, 0.0);
}

TEST(SdlParser, AnUnreadableFileIsAParseErrorNamingIt) {
  try {
    parse_file("/nonexistent/scene.sdl");
    FAIL() << "no error";
  } catch (const ParseError& error) {
    EXPECT_EQ(error.file(), "/nonexistent/scene.sdl");
    EXPECT_EQ(error.line(), 0);
    EXPECT_NE(std::string(error.what()).find("cannot open /nonexistent/scene.sdl"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace syncap::sdl

namespace syncap::sdl {
namespace {

// docs/reference/sdl.md's first example (its first fenced block without a language) is a valid
// scene.
TEST(SdlParser, TheDocumentationsFirstSceneParses) {
  std::ifstream doc(std::filesystem::path(SYNCAP_SOURCE_DIR) / "docs/reference/sdl.md");
  std::stringstream text;
  text << doc.rdbuf();
  const std::string markdown = text.str();
  const size_t start = markdown.find("\n```\n");
  ASSERT_NE(start, std::string::npos);
  const size_t end = markdown.find("\n```\n", start + 5);
  ASSERT_NE(end, std::string::npos);
  const scene::Network n = parse_string(markdown.substr(start + 5, end - start - 4), "sdl.md");
  EXPECT_EQ(n.models.size(), 1u);
  EXPECT_EQ(n.stations.size(), 1u);
  EXPECT_EQ(n.points.size(), 3u);
  EXPECT_EQ(n.measurements.size(), 2u);
  EXPECT_EQ(n.measurements[1].frame_number, 17);
  EXPECT_EQ(n.distances.size(), 1u);
  EXPECT_EQ(n.residual_test.critical_snooping, 4.9);
}

}  // namespace
}  // namespace syncap::sdl
