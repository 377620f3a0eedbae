// Opaque minerals (issue 22): magnetite and ilmenite absorb by their complex index n + ik
// (mineral files' "extinction_coefficient_k", μ = 4πk/λ). A thin slab follows Beer–Lambert's
// closed form; a 30 µm section passes exactly nothing (past the opaque cut-off of
// beer_lambert.h at every wavelength: no NaN, no subnormal); the loader refuses bad k blocks naming file, key and value.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/base/input_error.h"
#include "core/base/units.h"
#include "core/crystal/crystal.h"
#include "core/crystal/opacity.h"
#include "core/crystal/plate.h"

using namespace pmsim;

namespace {

// |J·x|² of a plate of `mineral` at normal incidence, faces without reflection loss (fresnel off),
// so only the bulk absorption acts.
double slab_transmittance(const Crystal& c, double thickness_um, double wavelength_nm, bool fresnel = false) {
  PlateSpec p;
  p.crystal = &c;
  p.thickness_um = thickness_um;
  p.fresnel = fresnel;
  const JonesMatrix J = plate_jones(p, glm::dvec3(0, 0, 1), wavelength_nm);
  return std::norm(J.xx) + std::norm(J.yx);
}

}  // namespace

// Querry (1985): k = 0.105 at 550 nm, so μ = 4π·0.105/0.55 µm = 2.399 µm⁻¹. Through 0.1 µm the
// slab passes e^(−0.2399) = 0.787: measurable, and the plate model must give exactly Beer–Lambert
// (isotropic, normal incidence: the path is the thickness; fresnel off: no face losses).
TEST(OpaqueMinerals, ThinMagnetiteSlabFollowsBeerLambert) {
  const Crystal& m = find_mineral("magnetite");
  ASSERT_TRUE(m.absorbing());
  for (const auto& [lambda, k] : {std::pair{550.0, 0.105}, std::pair{440.0, 0.026}, std::pair{630.0, 0.148}}) {
    const double mu = 4.0 * kPi * k / (lambda * 1e-3);
    EXPECT_NEAR(m.principal_absorption_per_um(lambda).x, mu, 1e-12) << lambda;
    for (double d : {0.02, 0.1, 0.5}) {
      // Both sides are the same exponential: agreement to rounding (1e-12 relative).
      const double expected = std::exp(-mu * d);
      EXPECT_NEAR(slab_transmittance(m, d, lambda), expected, 1e-12 * expected) << lambda << " nm, " << d << " µm";
    }
  }
  // The measured number the report quotes: 0.1 µm at 550 nm.
  EXPECT_NEAR(slab_transmittance(m, 0.1, 550.0), 0.7867, 1e-4);
}

// 30 µm: the amplitude exponent is past the opaque cut-off (e^(−9.2), beer_lambert.h) at every
// wavelength (magnetite's least, 430–440 nm with k = 0.026, is 11.1; ilmenite's 24), so the plate
// passes exactly 0 — never NaN, and no tiny intensity that would be a subnormal float (I < FLT_MIN)
// once an image holds it — for a normal and a tilted wave.
TEST(OpaqueMinerals, ThirtyMicronSectionsPassExactlyNothing) {
  for (const char* name : {"magnetite", "ilmenite"}) {
    const Crystal& c = find_mineral(name);
    EXPECT_TRUE(is_opaque(c)) << name;
    for (double l = 380.0; l <= 780.0; l += 5.0) {
      PlateSpec p;
      p.crystal = &c;
      p.crystal_to_lab = uniaxial_orientation(glm::dvec3(1, 0, 1));
      for (const glm::dvec3 k : {glm::dvec3(0, 0, 1), glm::normalize(glm::dvec3(0.2, 0.1, 1.0))}) {
        const JonesMatrix J = plate_jones(p, k, l);
        for (const complexd v : {J.xx, J.xy, J.yx, J.yy}) EXPECT_EQ(v, complexd(0.0)) << name << " " << l << " nm";
      }
    }
  }
  // Thinner, the same law: 3 µm of magnetite at 550 nm passes e^(−7.2) = 7.5e-4 (not cut off).
  const Crystal& m = find_mineral("magnetite");
  EXPECT_NEAR(slab_transmittance(m, 3.0, 550.0), std::exp(-4.0 * kPi * 0.105 / 0.55 * 3.0), 1e-15);
  // Ilmenite is uniaxial negative (no > ne, from its reflectances) and its thin edge is not black:
  // 0.05 µm passes e^(−4π·0.1·0.05/0.55) = 0.892 per vibration (550 nm is a table wavelength: exact).
  const Crystal& i = find_mineral("ilmenite");
  EXPECT_EQ(i.symmetry(), CrystalSymmetry::Uniaxial);
  EXPECT_GT(i.principal_indices(589.3).x, i.principal_indices(589.3).z);
  EXPECT_NEAR(slab_transmittance(i, 0.05, 550.0), std::exp(-4.0 * kPi * 0.1 * 0.05 / 0.55), 1e-12);
}

// Transparent minerals stay transparent (biotite's dark Y = Z passes 8 % at 550 nm: coloured,
// not opaque), and the cut-off leaves them untouched.
TEST(OpaqueMinerals, ColouredMineralsAreNotOpaque) {
  for (const char* name : {"biotite", "hornblende", "quartz", "almandine", "tourmaline"})
    EXPECT_FALSE(is_opaque(find_mineral(name))) << name;
  const Crystal& b = find_mineral("biotite");
  const double mu_y = b.principal_absorption_per_um(550.0).y;
  PlateSpec p;
  p.crystal = &b;
  p.fresnel = false;
  p.crystal_to_lab = glm::dmat3(glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0));  // Y along lab x
  const JonesMatrix J = plate_jones(p, glm::dvec3(0, 0, 1), 550.0);
  EXPECT_NEAR(std::norm(J.xx), std::exp(-mu_y * 30.0), 1e-9);
  EXPECT_NEAR(std::norm(J.xx), 0.08, 1e-3);
}

// The k block: either form, not both; k in [0, 10]; errors name the file, the key and the value.
TEST(OpaqueMinerals, LoaderRefusesBadExtinctionCoefficients) {
  const auto dir = std::filesystem::temp_directory_path() / ("pmsim_opaque_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& absorption) {
    const auto path = (dir / "m.json").string();
    std::ofstream(path) << R"({"name": "m", "symmetry": "isotropic", "source": "test", "indices": {"n": 2.3},
                              "absorption": )" << absorption << "}";
    return path;
  };
  const auto refused = [&](const std::string& absorption, const std::string& key, const std::string& value) {
    const std::string path = write(absorption);
    try {
      load_mineral_file(path);
      ADD_FAILURE() << "accepted " << absorption;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find(key), std::string::npos) << what;
      EXPECT_NE(what.find(value), std::string::npos) << what;
    }
  };
  refused(R"({"source": "s", "wavelength_nm": [400, 700], "extinction_coefficient_k": {"n": [0.1, -0.2]}})",
          "absorption.extinction_coefficient_k.n", "-0.2");
  refused(R"({"source": "s", "wavelength_nm": [400, 700], "extinction_coefficient_k": {"n": [0.1]}})",
          "absorption.extinction_coefficient_k.n", "0.1");
  refused(R"({"source": "s", "wavelength_nm": [400, 700], "extinction_coefficient_k": {"o": [0.1, 0.1]}})",
          "absorption.extinction_coefficient_k.o", "0.1");
  refused(R"({"source": "s", "reference_thickness_um": 30, "wavelength_nm": [400, 700],
              "extinction_coefficient_k": {"n": [0.1, 0.1]}})",
          "absorption.reference_thickness_um", "30");
  refused(R"({"source": "s", "reference_thickness_um": 30, "wavelength_nm": [400, 700],
              "transmittance": {"n": [0.5, 0.5]}, "extinction_coefficient_k": {"n": [0.1, 0.1]}})",
          "absorption", "either");
  // A good block loads: μ = 4πk/λ at the table's wavelengths, linear between.
  const Crystal c = load_mineral_file(
      write(R"({"source": "s", "wavelength_nm": [400, 700], "extinction_coefficient_k": {"n": [0.1, 0.2]}})"));
  EXPECT_NEAR(c.principal_absorption_per_um(400.0).x, 4.0 * kPi * 0.1 / 0.4, 1e-12);
  EXPECT_NEAR(c.principal_absorption_per_um(700.0).z, 4.0 * kPi * 0.2 / 0.7, 1e-12);
  std::filesystem::remove_all(dir);
}
