// Field-by-field equality of two scene::Networks for the SDL tests (doubles compared with ==, no
// tolerance): a failure names the field.
#pragma once

#include <gtest/gtest.h>

#include "scene/network.hpp"
#include "sensor/camera_parameters.hpp"

namespace syncap::sdl::testing {

inline void expect_same_prior(const scene::ParameterPrior& a, const scene::ParameterPrior& b,
                              const std::string& where) {
  EXPECT_EQ(static_cast<int>(a.mode), static_cast<int>(b.mode)) << where;
  EXPECT_EQ(a.sigma, b.sigma) << where;
}

inline void expect_same_design(const scene::DesignOptions& a, const scene::DesignOptions& b) {
  EXPECT_EQ(a.simulate, b.simulate);
  EXPECT_EQ(a.simulation_seed, b.simulation_seed);
  EXPECT_EQ(a.unified_least_squares, b.unified_least_squares);
  EXPECT_EQ(a.residuals, b.residuals);
  EXPECT_EQ(a.calculate_covariance, b.calculate_covariance);
  EXPECT_EQ(a.statistical_tests, b.statistical_tests);
  EXPECT_EQ(a.force_complete, b.force_complete);
  EXPECT_EQ(a.exact_iterations, b.exact_iterations);
  EXPECT_EQ(a.ignore_approximates, b.ignore_approximates);
  EXPECT_EQ(a.sort, b.sort);
  EXPECT_EQ(a.output_coefficient_matrix, b.output_coefficient_matrix);
  EXPECT_EQ(a.output_misclosures, b.output_misclosures);
  EXPECT_EQ(a.output_corrections, b.output_corrections);
  EXPECT_EQ(a.output_messages, b.output_messages);
  EXPECT_EQ(a.output_iterations, b.output_iterations);
  EXPECT_EQ(a.output_iterations_inline, b.output_iterations_inline);
  EXPECT_EQ(a.debug, b.debug);
  EXPECT_EQ(a.wait, b.wait);
  EXPECT_EQ(a.max_iterations, b.max_iterations);
  EXPECT_EQ(a.convergence_tolerance, b.convergence_tolerance);
}

inline void expect_same_network(const scene::Network& a, const scene::Network& b) {
  expect_same_design(a.design, b.design);
  ASSERT_EQ(a.models.size(), b.models.size());
  for (size_t i = 0; i < a.models.size(); ++i) {
    const auto& x = a.models[i];
    const auto& y = b.models[i];
    const std::string where = "model " + std::to_string(i);
    EXPECT_EQ(x.name, y.name) << where;
    EXPECT_EQ(x.sensor.width_px, y.sensor.width_px) << where;
    EXPECT_EQ(x.sensor.height_px, y.sensor.height_px) << where;
    EXPECT_EQ(x.sensor.pixel_width_mm, y.sensor.pixel_width_mm) << where;
    EXPECT_EQ(x.sensor.pixel_height_mm, y.sensor.pixel_height_mm) << where;
    EXPECT_EQ(sensor::interior_block(x.interior), sensor::interior_block(y.interior)) << where;
    for (size_t k = 0; k < x.priors.size(); ++k) {
      expect_same_prior(x.priors[k], y.priors[k], where + " prior " + std::to_string(k));
    }
  }
  ASSERT_EQ(a.stations.size(), b.stations.size());
  for (size_t i = 0; i < a.stations.size(); ++i) {
    const auto& x = a.stations[i];
    const auto& y = b.stations[i];
    const std::string where = "station " + std::to_string(i);
    EXPECT_EQ(x.name, y.name) << where;
    EXPECT_EQ(x.camera_id, y.camera_id) << where;
    EXPECT_EQ(x.model, y.model) << where;
    EXPECT_EQ(x.has_approximation, y.has_approximation) << where;
    EXPECT_EQ(sensor::exterior_block(x.exterior), sensor::exterior_block(y.exterior)) << where;
    for (size_t k = 0; k < x.priors.size(); ++k) {
      expect_same_prior(x.priors[k], y.priors[k], where + " prior " + std::to_string(k));
    }
  }
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i) {
    const auto& x = a.points[i];
    const auto& y = b.points[i];
    const std::string where = "point " + std::to_string(i);
    EXPECT_EQ(x.name, y.name) << where;
    EXPECT_EQ(x.xyz, y.xyz) << where;
    EXPECT_EQ(x.has_approximation, y.has_approximation) << where;
    for (size_t k = 0; k < 3; ++k) {
      expect_same_prior(x.priors[k], y.priors[k], where + " prior " + std::to_string(k));
    }
  }
  ASSERT_EQ(a.measurements.size(), b.measurements.size());
  for (size_t i = 0; i < a.measurements.size(); ++i) {
    const auto& x = a.measurements[i];
    const auto& y = b.measurements[i];
    const std::string where = "measurement " + std::to_string(i);
    EXPECT_EQ(x.station, y.station) << where;
    EXPECT_EQ(x.point, y.point) << where;
    EXPECT_EQ(x.u, y.u) << where;
    EXPECT_EQ(x.v, y.v) << where;
    EXPECT_EQ(x.sigma_px, y.sigma_px) << where;
    EXPECT_EQ(x.frame_number, y.frame_number) << where;
  }
  ASSERT_EQ(a.distances.size(), b.distances.size());
  for (size_t i = 0; i < a.distances.size(); ++i) {
    const auto& x = a.distances[i];
    const auto& y = b.distances[i];
    const std::string where = "distance " + std::to_string(i);
    EXPECT_EQ(x.point_a, y.point_a) << where;
    EXPECT_EQ(x.point_b, y.point_b) << where;
    EXPECT_EQ(x.distance, y.distance) << where;
    EXPECT_EQ(x.sigma, y.sigma) << where;
  }
  const auto& s = a.residual_test;
  const auto& t = b.residual_test;
  EXPECT_EQ(s.alpha_variance, t.alpha_variance);
  EXPECT_EQ(s.alpha_goodness, t.alpha_goodness);
  EXPECT_EQ(s.critical_snooping, t.critical_snooping);
  EXPECT_EQ(s.iterative_rejection, t.iterative_rejection);
  EXPECT_EQ(s.max_rejections, t.max_rejections);
  EXPECT_EQ(s.snoop_with_a_posteriori_sigma0, t.snoop_with_a_posteriori_sigma0);
}

}  // namespace syncap::sdl::testing
