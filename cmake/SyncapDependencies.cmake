# Every library syncap builds on, found once, here (scripts/deps.sh installs them: Debian
# bookworm's packages). Subdirectories link the imported targets and never call find_package
# themselves. The board-only build (SYNCAP_BUILD_HOST=OFF: firmware, edge) needs neither CGAL
# nor Ceres; tests and benchmarks find theirs only when they are built.
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
pkg_check_modules(LCM REQUIRED IMPORTED_TARGET lcm)
pkg_check_modules(ARAVIS REQUIRED IMPORTED_TARGET aravis-0.8)
pkg_check_modules(SODIUM REQUIRED IMPORTED_TARGET libsodium)
pkg_check_modules(GPIOD REQUIRED IMPORTED_TARGET libgpiod>=1.6)
# libyaml (C): syncap-trigger reads its YAML config and the rig file
pkg_check_modules(YAML REQUIRED IMPORTED_TARGET yaml-0.1)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs calib3d video videoio aruco)
find_package(nlohmann_json 3 REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(CLI11 2 REQUIRED CONFIG)
find_program(LCM_GEN lcm-gen REQUIRED)

if(SYNCAP_BUILD_HOST)
  find_package(Ceres REQUIRED)
  find_package(CGAL REQUIRED)
  find_package(tomlplusplus 3 REQUIRED)  # anipose / Pose2Sim camera files (TOML)
endif()
if(SYNCAP_BUILD_TESTS)
  find_package(GTest REQUIRED)
  find_package(Python3 COMPONENTS Interpreter QUIET)  # the docs' link check
endif()
if(SYNCAP_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
