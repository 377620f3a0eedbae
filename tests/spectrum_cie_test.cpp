// CIE tables, illuminants and the observer weights.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/spectrum/cie.h"
#include "core/spectrum/cie_tables.h"
#include "core/spectrum/illuminant.h"

namespace pmsim {
namespace {

// Rows of numbers of a CSV file in assets/spectra (comment lines '#' and the header skipped).
std::vector<std::vector<double>> read_csv(const std::string& name) {
  std::ifstream in(std::string(PMSIM_SOURCE_DIR) + "/assets/spectra/" + name);
  EXPECT_TRUE(in.good()) << name;
  std::vector<std::vector<double>> rows;
  std::string line;
  bool seen_source = false;
  while (std::getline(in, line)) {
    if (line.rfind("# source:", 0) == 0) seen_source = true;
    if (line.empty() || line[0] == '#' || !std::isdigit(static_cast<unsigned char>(line[0]))) continue;
    std::vector<double> row;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  EXPECT_TRUE(seen_source) << name << " must name its source";
  return rows;
}

TEST(CieTables, CompiledTableEqualsShippedCsvExactly) {
  // The .cpp table is generated from the same decimal text, so the doubles must be identical.
  const auto cmf = read_csv("cie1931_2deg_xyz.csv");
  const auto d65 = read_csv("cie_illuminant_d65.csv");
  const auto a = read_csv("cie_illuminant_a.csv");
  ASSERT_EQ(cmf.size(), 81u);
  ASSERT_EQ(d65.size(), 81u);
  ASSERT_EQ(a.size(), 81u);
  for (int i = 0; i < cie_tables::kCount; ++i) {
    const double nm = 380.0 + 5.0 * i;
    ASSERT_EQ(cmf[i].size(), 4u);
    EXPECT_EQ(cmf[i][0], nm);
    EXPECT_EQ(cmf[i][1], cie_tables::kXBar[i]) << nm;
    EXPECT_EQ(cmf[i][2], cie_tables::kYBar[i]) << nm;
    EXPECT_EQ(cmf[i][3], cie_tables::kZBar[i]) << nm;
    EXPECT_EQ(d65[i][0], nm);
    EXPECT_EQ(d65[i][1], cie_tables::kD65[i]) << nm;
    EXPECT_EQ(a[i][0], nm);
    EXPECT_EQ(a[i][1], cie_tables::kA[i]) << nm;
  }
}

TEST(CieTables, PublishedAnchorValues) {
  // CIE 15:2004 Table T.4: ȳ(555 nm) = 1.0 exactly (the photopic peak), x̄(600) = 1.0622,
  // z̄(450) = 1.77211; Table T.1: S(560) = 100 for both illuminants, S_A(780) = 241.675.
  EXPECT_EQ(cie1931_xyz_bar(555.0).y, 1.0);
  EXPECT_EQ(cie1931_xyz_bar(600.0).x, 1.0622);
  EXPECT_EQ(cie1931_xyz_bar(450.0).z, 1.77211);
  EXPECT_EQ(illuminant_spd(Illuminant::D65, 560.0), 100.0);
  EXPECT_EQ(illuminant_spd(Illuminant::A, 560.0), 100.0);
  EXPECT_EQ(illuminant_spd(Illuminant::A, 780.0), 241.675);
}

TEST(CieTables, IlluminantAFollowsPlanckAt2856K) {
  // CIE 15:2004 eq. (3.1): S_A(λ) = 100·(560/λ)^5·[e^(c2/(2848·560)) − 1]/[e^(c2/(2848·λ)) − 1]
  // with c2 = 1.435e7 nm·K (a Planckian radiator of 2856 K on today's c2 = 1.4388e-2 m·K).
  // The table has 6 significant digits (5 below 10), so 1e-5 relative is table rounding.
  auto planck = [](double nm) {
    const double c2 = 1.435e7;  // nm·K
    return 100.0 * std::pow(560.0 / nm, 5) * (std::exp(c2 / (2848.0 * 560.0)) - 1.0) /
           (std::exp(c2 / (2848.0 * nm)) - 1.0);
  };
  for (double nm = 380.0; nm <= 780.0; nm += 40.0) {
    EXPECT_NEAR(illuminant_spd(Illuminant::A, nm), planck(nm), 1e-5 * planck(nm)) << nm;
  }
}

TEST(CieTables, LinearInterpolationBetweenNodes) {
  // Halfway between 555 and 560 nm: mean of the tabulated values.
  const double y = cie1931_xyz_bar(557.5).y;
  EXPECT_DOUBLE_EQ(y, 0.5 * (1.0 + 0.995));
  EXPECT_DOUBLE_EQ(illuminant_spd(Illuminant::D65, 382.5), 0.5 * (49.9755 + 52.3118));
}

TEST(CieTables, OutsideVisibleRangeThrows) {
  EXPECT_THROW(cie1931_xyz_bar(379.999), std::out_of_range);
  EXPECT_THROW(cie1931_xyz_bar(780.001), std::out_of_range);
  EXPECT_THROW(cie1931_xyz_bar(std::nan("")), std::out_of_range);
  EXPECT_THROW(illuminant_spd(Illuminant::A, 1000.0), std::out_of_range);
  EXPECT_THROW(observer_weight(Illuminant::D65, 300.0), std::out_of_range);
  EXPECT_NO_THROW(cie1931_xyz_bar(380.0));
  EXPECT_NO_THROW(cie1931_xyz_bar(780.0));
}

TEST(IlluminantNames, ParseIsCaseInsensitiveAndRejectsUnknown) {
  Illuminant il = Illuminant::A;
  EXPECT_TRUE(parse_illuminant("d65", il));
  EXPECT_EQ(il, Illuminant::D65);
  EXPECT_TRUE(parse_illuminant("a", il));
  EXPECT_EQ(il, Illuminant::A);
  EXPECT_FALSE(parse_illuminant("D50", il));
  EXPECT_EQ(illuminant_name(Illuminant::D65), "D65");
  EXPECT_EQ(illuminant_name(Illuminant::A), "A");
}

// Trapezoid rule with 1 nm steps over 380–780 nm: the integration observer_weight is normalised for.
glm::dvec3 integrate_1nm(Illuminant il, double (*transmittance)(double)) {
  glm::dvec3 s(0.0);
  for (int nm = 380; nm <= 780; ++nm) {
    const double w = (nm == 380 || nm == 780) ? 0.5 : 1.0;
    s += w * transmittance(nm) * observer_weight(il, nm);
  }
  return s;
}

TEST(ObserverWeight, UnitTransmittanceGivesYEqualOne) {
  // Definition of the weights: Y = ∫1·w_y dλ = 1 for the 1 nm trapezoid rule; only rounding
  // of a 401-term sum remains (1e-14).
  for (Illuminant il : {Illuminant::D65, Illuminant::A}) {
    const glm::dvec3 xyz = integrate_1nm(il, [](double) { return 1.0; });
    EXPECT_NEAR(xyz.y, 1.0, 1e-14);
    const glm::dvec3 white = illuminant_white_xyz(il);
    EXPECT_NEAR(white.y, 1.0, 1e-14);
    EXPECT_NEAR(xyz.x, white.x, 1e-14);
    EXPECT_NEAR(xyz.z, white.z, 1e-14);
  }
}

TEST(ObserverWeight, HalfTransmittanceHalvesXyz) {
  const glm::dvec3 xyz = integrate_1nm(Illuminant::D65, [](double) { return 0.5; });
  EXPECT_NEAR(xyz.y, 0.5, 1e-14);  // linearity, rounding only
}

TEST(IlluminantWhite, D65ChromaticityIsTheStandardWhitePoint) {
  // CIE 15:2004 Table T.3: D65 x = 0.31272, y = 0.32903 (1 nm data, 360–830 nm). Our 5 nm
  // tables over 380–780 nm move it by < 1e-4; 2e-4 allows that truncation and table rounding.
  const glm::dvec3 w = illuminant_white_xyz(Illuminant::D65);
  const double sum = w.x + w.y + w.z;
  EXPECT_NEAR(w.x / sum, 0.3127, 2e-4);
  EXPECT_NEAR(w.y / sum, 0.3290, 2e-4);
}

TEST(IlluminantWhite, AChromaticityIsTheStandardWhitePoint) {
  // CIE 15:2004 Table T.3: A x = 0.44757, y = 0.40745; tolerance as for D65.
  const glm::dvec3 w = illuminant_white_xyz(Illuminant::A);
  const double sum = w.x + w.y + w.z;
  EXPECT_NEAR(w.x / sum, 0.4476, 2e-4);
  EXPECT_NEAR(w.y / sum, 0.4074, 2e-4);
}

}  // namespace
}  // namespace pmsim
