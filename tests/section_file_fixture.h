#pragma once
// Thin-section files written for a test: a scratch folder of the test program's own (removed when
// the program ends) and small sections of a few grains in it, as the section reader takes them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

namespace section_test {

inline std::filesystem::path scratch_dir() {
  return std::filesystem::temp_directory_path() / ("pmsim_sections_" + std::to_string(::getpid()));
}

struct RemoveScratch : ::testing::Environment {
  void TearDown() override { std::filesystem::remove_all(scratch_dir()); }
};
inline const auto* const kRemoveScratch = ::testing::AddGlobalTestEnvironment(new RemoveScratch);

// A grain with its optic axis (or c axis) in the section plane at axis_deg from east.
inline nlohmann::json grain_with_axis_in_plane(const char* mineral, double x_mm, double y_mm, double size_mm,
                                               double axis_deg) {
  const double a = axis_deg * M_PI / 180.0;
  return {{"mineral", mineral},
          {"centre_mm", {x_mm, y_mm}},
          {"size_mm", size_mm},
          {"optic_axis", {std::cos(a), std::sin(a), 0.0}}};
}

// A square section side_mm across of `grains`, thickness_um thick, written as scratch_dir()/file;
// its path.
inline std::string write_section(const std::string& file, const std::vector<nlohmann::json>& grains,
                                 double side_mm, double thickness_um = 30.0) {
  std::filesystem::create_directories(scratch_dir());
  const nlohmann::json j = {{"type", "section"},
                            {"name", file},
                            {"thickness_um", thickness_um},
                            {"size_mm", {side_mm, side_mm}},
                            {"source", "test section"},
                            {"grains", nlohmann::json(grains)}};
  const std::filesystem::path p = scratch_dir() / file;
  std::ofstream(p) << j.dump();
  return p.string();
}

}  // namespace section_test
