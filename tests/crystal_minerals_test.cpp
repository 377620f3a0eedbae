// Mineral data, dispersion, optic angle, orientation helpers and input validation.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/base/units.h"
#include "core/crystal/crystal.h"
#include "core/base/input_error.h"

using namespace pmsim;

namespace {
constexpr double kDeg = kPi / 180.0;
}

TEST(GhoshDispersion, QuartzIndicesAtSodiumD) {
  const Crystal& q = find_mineral("quartz");
  const glm::dvec3 n = q.principal_indices(589.3);
  // Handbook values no = 1.5443, ne = 1.5534 (4 decimals); Ghosh's fit is within 1e-4 of them,
  // so 2e-4 allows the rounding of the reference and the fit residual.
  EXPECT_NEAR(n.x, 1.5443, 2e-4);
  EXPECT_NEAR(n.y, 1.5443, 2e-4);
  EXPECT_NEAR(n.z, 1.5534, 2e-4);
  EXPECT_EQ(q.symmetry(), CrystalSymmetry::Uniaxial);
  EXPECT_FALSE(q.is_constant());
}

TEST(GhoshDispersion, CalciteIndicesAtSodiumD) {
  const Crystal& c = find_mineral("calcite");
  const glm::dvec3 n = c.principal_indices(589.3);
  EXPECT_NEAR(n.x, 1.6584, 2e-4);  // handbook no, 4 decimals
  // Ghosh's five-coefficient fit gives ne = 1.48613 at 589.3 nm, 2.7e-4 below the handbook 1.4864:
  // the tolerance is widened to 3e-4 for that known fit residual (see calcite.json).
  EXPECT_NEAR(n.z, 1.4864, 3e-4);
  // Ghosh's own formula evaluated by refractiveindex.info: no(587.6 nm) = 1.65846 (5 decimals).
  EXPECT_NEAR(c.principal_indices(587.6).x, 1.65846, 1e-5);
}

TEST(GhoshDispersion, NormalDispersionIndexFallsWithWavelength) {
  for (const char* name : {"quartz", "calcite"}) {
    const Crystal& c = find_mineral(name);
    for (double wl = 400.0; wl < 780.0; wl += 20.0) {
      // Far from absorption bands both indices decrease with λ (normal dispersion).
      EXPECT_GT(c.principal_indices(wl).x, c.principal_indices(wl + 20.0).x) << name << " " << wl;
      EXPECT_GT(c.principal_indices(wl).z, c.principal_indices(wl + 20.0).z) << name << " " << wl;
    }
  }
}

TEST(MineralLibrary, HasTheRequiredMineralsWithSources) {
  const auto names = mineral_names();
  for (const char* m : {"quartz", "calcite", "muscovite", "biotite", "olivine", "gypsum", "plagioclase",
                        "orthoclase", "augite", "hornblende", "tourmaline"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), m), names.end()) << m;
    const Crystal& c = find_mineral(m);
    EXPECT_FALSE(c.source().empty()) << m;
    const glm::dvec3 n = c.principal_indices(550.0);
    EXPECT_GT(n.x, 1.3) << m;
    EXPECT_LT(n.z, 2.0) << m;
  }
}

TEST(MineralLibrary, LookupIsCaseInsensitiveAndUnknownNamesAreInputErrors) {
  EXPECT_EQ(&find_mineral("Quartz"), &find_mineral("QUARTZ"));
  try {
    find_mineral("unobtainium");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "");  // the crystal module knows no scene keys: callers add theirs
    EXPECT_EQ(e.value, "unobtainium");
  }
}

TEST(OpticAngle, MatchesTheTangentForm) {
  // Independent form of the optic-axis angle (Born & Wolf §15.3):
  // tan²Vz = (1/nα² − 1/nβ²) / (1/nβ² − 1/nγ²).
  const double sets[][3] = {
      {1.50, 1.51, 1.60}, {1.52, 1.55, 1.60}, {1.560, 1.595, 1.600}, {1.654, 1.671, 1.690}};
  for (const auto& s : sets) {
    const double t2 = (1 / (s[0] * s[0]) - 1 / (s[1] * s[1])) / (1 / (s[1] * s[1]) - 1 / (s[2] * s[2]));
    // Both are closed forms in double precision: 1e-12 rad.
    EXPECT_NEAR(optic_angle_2v_rad(s[0], s[1], s[2]), 2 * std::atan(std::sqrt(t2)), 1e-12);
  }
  EXPECT_NEAR(optic_angle_2v_rad(1.5, 1.5, 1.6), 0.0, 1e-12);  // uniaxial positive
  EXPECT_NEAR(optic_angle_2v_rad(1.5, 1.6, 1.6), kPi, 1e-12);  // uniaxial negative
  EXPECT_EQ(optic_angle_2v_rad(1.5, 1.5, 1.5), 0.0);           // isotropic, no NaN
}

TEST(OpticAngle, BiaxialMineralsAgreeWithTheirPublished2V) {
  const std::filesystem::path dir = std::filesystem::path(PMSIM_SOURCE_DIR) / "assets/minerals";
  int checked = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    std::ifstream in(e.path());
    const auto j = nlohmann::json::parse(in);
    if (!j.contains("symmetry") || j["symmetry"] != "biaxial") continue;  // aliases.json is no mineral
    ASSERT_TRUE(j.contains("optic_angle_2vz_deg")) << e.path();
    const Crystal c = load_mineral_file(e.path().string());
    const glm::dvec3 n = c.principal_indices(589.3);
    // Published 2V values are given to about a degree; the indices were chosen inside their
    // ranges to reproduce them, so 1° checks that the file is self-consistent.
    EXPECT_NEAR(optic_angle_2v_rad(n.x, n.y, n.z) / kDeg, j["optic_angle_2vz_deg"].get<double>(), 1.0)
        << e.path();
    ++checked;
  }
  EXPECT_GE(checked, 8);
}

TEST(Orientation, HelpersGiveRightHandedOrthonormalFrames) {
  const glm::dmat3 u = uniaxial_orientation({1, 2, 3});
  const glm::dmat3 b = biaxial_orientation({1, 0.3, 0.2}, {0.1, 0.2, 1});
  const glm::dmat3 r = rotate_stage(b, 0.7);
  for (const glm::dmat3& m : {u, b, r}) {
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(glm::dot(m[i], m[k]), i == k ? 1.0 : 0.0, 1e-14);
    EXPECT_NEAR(glm::dot(glm::cross(m[0], m[1]), m[2]), 1.0, 1e-14);
  }
  EXPECT_NEAR(glm::dot(u[2], glm::normalize(glm::dvec3(1, 2, 3))), 1.0, 1e-14);      // Z = optic axis
  EXPECT_NEAR(glm::dot(b[2], glm::normalize(glm::dvec3(0.1, 0.2, 1))), 1.0, 1e-14);  // z first
  // A stage turn of 90° counter-clockwise takes lab x to lab y.
  const glm::dmat3 q = rotate_stage(glm::dmat3(1.0), kPi / 2);
  EXPECT_NEAR(q[0].y, 1.0, 1e-15);
  EXPECT_THROW(uniaxial_orientation({0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(biaxial_orientation({0, 0, 0}, {0, 0, 1}), std::invalid_argument);
  EXPECT_THROW(biaxial_orientation({0, 0, 2}, {0, 0, 1}), std::invalid_argument);
  EXPECT_THROW(uniaxial_orientation({NAN, 0, 1}), std::invalid_argument);
}

TEST(CustomCrystal, ValidatesIndicesAndNamesTheKey) {
  CrystalIndices ci;
  ci.uniaxial = false;
  ci.nalpha = 1.6;
  ci.nbeta = 1.5;
  ci.ngamma = 1.7;
  EXPECT_THROW(crystal_from_indices(ci), InputError);
  ci.nalpha = NAN;
  try {
    crystal_from_indices(ci);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "nalpha");  // relative: the scene reader prefixes "sample.crystal"
  }
  CrystalIndices u;
  u.no = 0.9;
  EXPECT_THROW(crystal_from_indices(u), InputError);
  u.no = 1.658;
  u.ne = 1.486;
  const Crystal c = crystal_from_indices(u);
  EXPECT_TRUE(c.is_constant());
  EXPECT_EQ(c.principal_indices(500.0), glm::dvec3(1.658, 1.658, 1.486));
}

namespace {
std::string write_temp(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / ("pmsim_crystal_test_" + name + ".json");
  std::ofstream(p) << text;
  return p.string();
}
}  // namespace

TEST(MineralFile, BadInputNamesFileKeyAndValue) {
  struct Case {
    const char* text;
    const char* key;
    const char* value;
  };
  const Case cases[] = {
      {R"({"name":"x","symmetry":"uniaxial","indices":{"no":1.5,"ne":1.6}})", "source", ""},
      {R"({"name":"x","symmetry":"uniaxial","source":"s","indices":{"no":0.5,"ne":1.6}})", "indices.no",
       "0.5"},
      {R"({"name":"x","symmetry":"trigonal","source":"s","indices":{}})", "symmetry",
       "trigonal"},  // strings shown unquoted, as in every file type
      {R"({"name":"x","symmetry":"uniaxial","source":"s","indices":{"no":{"model":"magic"},"ne":1.6}})",
       "indices.no.model", "magic"},
      {R"({"name":"x","symmetry":"biaxial","source":"s","indices":{"nalpha":1.6,"nbeta":1.5,"ngamma":1.7}})",
       "indices", ""},
      {R"({"name":"x","symmetry":"uniaxial","source":"s","indices":{"no":1.5,"ne":1.6},
           "absorption":{"reference_thickness_um":30,"wavelength_nm":[400,500],
           "transmittance":{"o":[0.5,1.5],"e":[0.5,0.5]}}})",
       "absorption.transmittance.o", "[0.5,1.5]"},
  };
  int i = 0;
  for (const Case& c : cases) {
    const std::string path = write_temp(std::to_string(i++), c.text);
    try {
      load_mineral_file(path);
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file, path);
      EXPECT_EQ(e.key, c.key);
      if (*c.value) {
        EXPECT_EQ(e.value, c.value);
      }
    }
    std::filesystem::remove(path);
  }
  EXPECT_THROW(load_mineral_file("/nonexistent/mineral.json"), InputError);
}

TEST(RotatoryPower, QuartzMatchesTheClassicalValues) {
  const Crystal& q = find_mineral("quartz");
  ASSERT_TRUE(q.optically_active());
  // Tabulated rotatory power of quartz along c (CRC Handbook / Lowry): the one-term Drude fit
  // reproduces these within 0.1°/mm at 589 nm and 0.3°/mm at 405 nm.
  EXPECT_NEAR(q.rotatory_power_rad_per_um(589.3) / kDeg * 1000.0, 21.72, 0.1);
  EXPECT_NEAR(q.rotatory_power_rad_per_um(546.1) / kDeg * 1000.0, 25.54, 0.1);
  EXPECT_NEAR(q.rotatory_power_rad_per_um(404.7) / kDeg * 1000.0, 48.95, 0.3);
  EXPECT_EQ(find_mineral("calcite").rotatory_power_rad_per_um(589.3), 0.0);
}
