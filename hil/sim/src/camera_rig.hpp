// The cameras of a scenario as calibrated camera models (the host's sensor::CameraModel, the
// same model the calibration estimates), and each one's renderer view.
#pragma once

#include <vector>

#include "scenario.hpp"
#include "sensor/camera_model.hpp"
#include "view.hpp"

namespace syncap::sim {

// Places the cameras of the layout (ring, half circle or explicit poses), each looking at
// look_at_mm with its image x axis horizontal, and gives them the scenario's sensor and lens.
std::vector<sensor::CameraModel> build_rig(const Scenario& scenario);

// The renderer's view of a camera: projection, per-pixel rays, room background.
View make_view(const sensor::CameraModel& camera, const Scenario& scenario);

}  // namespace syncap::sim
