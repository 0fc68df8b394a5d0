// What both exports refuse, and that a refused or failed export leaves no file behind.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

#include "export_test_paths.hpp"
#include "io/atomic_file.hpp"
#include "io/c3d_writer.hpp"
#include "io/export_checks.hpp"
#include "io/export_error.hpp"
#include "io/trc_writer.hpp"
#include "synthetic_trajectories.hpp"

namespace syncap::io {
namespace {

using testing::fresh_path;
using testing::synthetic_trajectories;
using Writer = std::function<void(const std::string&, const tracking::MarkerTrajectories&)>;

const std::vector<std::pair<std::string, Writer>> kWriters = {{".c3d", write_c3d},
                                                              {".trc", write_trc}};

// Each writer refuses `t` with an ExportError naming the file and saying `problem`, and writes
// nothing.
void expect_refused(const tracking::MarkerTrajectories& t, const std::string& problem) {
  for (const auto& [extension, write] : kWriters) {
    const auto path = fresh_path(extension);
    try {
      write(path, t);
      ADD_FAILURE() << extension << " accepted input with: " << problem;
    } catch (const ExportError& e) {
      EXPECT_EQ(e.path(), path);
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(e.problem().find(problem), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(path)) << extension;
  }
}

tracking::MarkerTrajectories valid() { return synthetic_trajectories(5, 3, 100.0, 0); }

TEST(ExportChecks, RefusesRowsOfTheWrongWidth) {
  auto t = valid();
  t.samples[2].pop_back();
  expect_refused(t, "frame 2 has 2 samples for 3 labels");
}

TEST(ExportChecks, RefusesRatesThatAreNotPositive) {
  for (double rate : {0.0, -100.0, std::numeric_limits<double>::quiet_NaN()}) {
    auto t = valid();
    t.rate_hz = rate;
    expect_refused(t, "is not a positive number");
  }
}

TEST(ExportChecks, RefusesNonFinitePositionsAndBadResiduals) {
  auto t = valid();
  t.samples[1][1] = tracking::MarkerSample{{1, std::numeric_limits<double>::infinity(), 3}, 0.1, 1};
  expect_refused(t, "frame 1, marker 1: position is not finite");
  t = valid();
  t.samples[4][0] = tracking::MarkerSample{{1, 2, 3}, -0.5, 1};
  expect_refused(t, "frame 4, marker 0: residual is negative or not finite");
}

TEST(ExportChecks, RefusesLabelsBothFormatsCannotHold) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "is empty"},
      {"M\t1", "not printable ASCII"},
      {"M1 ", "starts or ends with a space"},
      {std::string(kMaxLabelLength + 1, 'L'), "is longer than 127 characters"},
      {"M002", "names two markers"}};
  for (const auto& [label, problem] : cases) {
    auto t = valid();
    t.labels[0] = label;
    expect_refused(t, problem);
  }
}

TEST(ExportChecks, RefusesNothingToExport) {
  auto no_frames = valid();
  no_frames.samples.clear();
  expect_refused(no_frames, "no frame");
  expect_refused(synthetic_trajectories(5, 0, 100.0, 0), "no marker");
}

TEST(ExportChecks, UnwritableFolderThrowsNamingTheFile) {
  for (const auto& [extension, write] : kWriters) {
    const std::string path = "/nonexistent-syncap-folder/trajectories" + extension;
    try {
      write(path, valid());
      ADD_FAILURE() << extension << " wrote into a missing folder";
    } catch (const ExportError& e) {
      EXPECT_EQ(e.path(), path);
      EXPECT_NE(std::string(e.what()).find("cannot create a file"), std::string::npos) << e.what();
    }
  }
}

TEST(ExportChecks, FailedWriteKeepsTheOldFileAndLeavesNoTemporary) {
  const auto path = fresh_path(".c3d");
  { std::ofstream(path) << "previous export"; }
  EXPECT_THROW(write_file_atomically(path,
                                     [](std::ostream& out) {
                                       out << "half";
                                       throw std::runtime_error("interrupted");
                                     }),
               std::runtime_error);
  std::ifstream in(path);
  std::string content;
  std::getline(in, content);
  EXPECT_EQ(content, "previous export");
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(path).parent_path())) {
    EXPECT_EQ(entry.path().string().find(".partial-"), std::string::npos) << entry.path();
  }
}

TEST(ExportChecks, SuccessfulExportReplacesTheOldFile) {
  for (const auto& [extension, write] : kWriters) {
    const auto path = fresh_path(extension);
    { std::ofstream(path) << "previous export"; }
    write(path, valid());
    EXPECT_GT(std::filesystem::file_size(path), 100u) << extension;
  }
}

}  // namespace
}  // namespace syncap::io
