// Catalogue glasses: Sellmeier dispersion against the SCHOTT catalogue, Beer–Lambert attenuation
// against the catalogue's internal transmittance.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/materials/medium.h"

namespace pmsim {
namespace {

constexpr double kD = 587.5618, kF = 486.1327, kC = 656.2725, kE = 546.0740;  // Fraunhofer lines

struct Catalogue {
  const char* name;
  double nd, vd;
};
// SCHOTT optical glass data sheets (2015/2017 catalogue): n_d (5 decimals) and v_d (2 decimals).
constexpr Catalogue kGlasses[] = {
    {"N-BK7", 1.51680, 64.17}, {"N-SF11", 1.78472, 25.68}, {"N-SF6", 1.80518, 25.36},
    {"F2", 1.62004, 36.37},    {"N-SK16", 1.62041, 60.32},
};

TEST(SchottGlass, SellmeierReproducesCatalogueNd) {
  // The catalogue prints n_d with 5 decimals (±5e-6) and the Sellmeier fit is good to ~1e-6 in
  // the visible, so 1e-5 is the catalogue's own accuracy.
  for (const auto& g : kGlasses) {
    EXPECT_NEAR(find_medium(g.name).nd(), g.nd, 1e-5) << g.name;
    // nd() is n at the helium d line itself (the same evaluation, so to rounding).
    EXPECT_NEAR(find_medium(g.name).nd(), find_medium(g.name).n(kD), 1e-12) << g.name;
  }
}

TEST(SchottGlass, AbbeNumberMatchesCatalogue) {
  // v_d is printed with 2 decimals (±0.005); a fit residual of 1e-6 in n_F − n_C changes v_d by
  // v_d·1e-6/(n_F − n_C) ≤ 0.008 (N-BK7), so 0.015 is rounding plus fit error.
  for (const auto& g : kGlasses) {
    EXPECT_NEAR(find_medium(g.name).abbe_vd(), g.vd, 0.015) << g.name;
  }
}

TEST(SchottGlass, FraunhoferLineIndicesMatchCatalogue) {
  // Data-sheet n_F, n_C (and n_e for N-BK7), 5 decimals: tolerance 1e-5 as for n_d.
  struct Lines {
    const char* name;
    double nF, nC;
  };
  constexpr Lines lines[] = {{"N-BK7", 1.52238, 1.51432},
                             {"N-SF6", 1.82783, 1.79608},
                             {"F2", 1.63208, 1.61503},
                             {"N-SK16", 1.62756, 1.61727}};
  for (const auto& l : lines) {
    const Medium& m = find_medium(l.name);
    EXPECT_NEAR(m.n(kF), l.nF, 1e-5) << l.name;
    EXPECT_NEAR(m.n(kC), l.nC, 1e-5) << l.name;
  }
  EXPECT_NEAR(find_medium("N-BK7").n(kE), 1.51872, 1e-5);
}

TEST(SchottGlass, NormalDispersionAcrossTheVisible) {
  // Far from absorption bands dn/dλ < 0 (normal dispersion): strictly decreasing on a 1 nm grid.
  for (const auto& g : kGlasses) {
    const Medium& m = find_medium(g.name);
    double previous = m.n(380.0);
    for (double nm = 381.0; nm <= 780.0; nm += 1.0) {
      const double n = m.n(nm);
      ASSERT_LT(n, previous) << g.name << " at " << nm;
      previous = n;
    }
  }
}

TEST(SchottGlass, SellmeierFormulaByHand) {
  // n² − 1 = Σ B λ²/(λ² − C) evaluated independently for N-BK7 at 632.8 nm (HeNe): 1.515089 to
  // rounding of the six-term sum (1e-12).
  const double B[3] = {1.03961212, 0.231792344, 1.01046945};
  const double C[3] = {0.00600069867, 0.0200179144, 103.560653};
  const double l2 = 0.6328 * 0.6328;
  double s = 1.0;
  for (int i = 0; i < 3; ++i) s += B[i] * l2 / (l2 - C[i]);
  EXPECT_NEAR(find_medium("n-bk7").n(632.8), std::sqrt(s), 1e-12);
  EXPECT_NEAR(std::sqrt(s), 1.515089, 1e-6);
}

TEST(SchottGlass, AttenuationReproducesCatalogueInternalTransmittance) {
  // Beer–Lambert: τ_i(d) = e^(−μ d). At a catalogue wavelength μ is the tabulated one, so
  // 25 mm of glass transmits the catalogue τ_i to rounding (1e-12).
  struct Tau {
    const char* name;
    double nm, tau25;
  };
  constexpr Tau taus[] = {{"N-BK7", 400.0, 0.992},  {"N-BK7", 546.0, 0.996}, {"N-SF11", 400.0, 0.600},
                          {"N-SF11", 380.0, 0.120}, {"N-SF6", 420.0, 0.810}, {"F2", 380.0, 0.963},
                          {"N-SK16", 500.0, 0.991}};
  for (const auto& t : taus) {
    const double mu = find_medium(t.name).attenuation_per_mm(t.nm);
    EXPECT_NEAR(std::exp(-mu * 25.0), t.tau25, 1e-12) << t.name << " " << t.nm;
    // And at 10 mm the data sheet's other column follows as τ25^(10/25).
    EXPECT_NEAR(std::exp(-mu * 10.0), std::pow(t.tau25, 0.4), 1e-12);
  }
}

TEST(SchottGlass, AttenuationInterpolatesLinearlyBetweenCatalogueWavelengths) {
  const Medium& m = find_medium("N-SF11");
  const double mu400 = -std::log(0.600) / 25.0, mu405 = -std::log(0.670) / 25.0;
  EXPECT_NEAR(m.attenuation_per_mm(402.0), mu400 + 0.4 * (mu405 - mu400), 1e-15);
  // Dense flints absorb in the blue: μ(400) ≫ μ(600).
  EXPECT_GT(m.attenuation_per_mm(400.0), 10.0 * m.attenuation_per_mm(600.0));
  for (double nm = 380.0; nm <= 780.0; nm += 5.0) {
    for (const auto& g : kGlasses) {
      const double mu = find_medium(g.name).attenuation_per_mm(nm);
      EXPECT_TRUE(std::isfinite(mu) && mu >= 0.0) << g.name << " " << nm;
    }
  }
}

TEST(SchottGlass, OutsideTheFormulaRangeThrowsOutOfRange) {
  // SCHOTT gives N-SF11's Sellmeier fit for 370–2500 nm and N-BK7's for 300–2500 nm.
  EXPECT_THROW(find_medium("N-SF11").n(360.0), std::out_of_range);
  EXPECT_NO_THROW(find_medium("N-SF11").n(370.0));
  EXPECT_THROW(find_medium("N-BK7").n(2600.0), std::out_of_range);
  EXPECT_THROW(find_medium("N-BK7").n(std::nan("")), std::out_of_range);
  EXPECT_THROW(find_medium("N-BK7").attenuation_per_mm(-5.0), std::out_of_range);
  // F2's formula starts at 320 nm but its transmittance data at 334 nm.
  EXPECT_NO_THROW(find_medium("F2").n(325.0));
  EXPECT_THROW(find_medium("F2").attenuation_per_mm(325.0), std::out_of_range);
  try {
    find_medium("N-SF11").n(200.0);
    FAIL() << "expected std::out_of_range";
  } catch (const std::out_of_range& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("N-SF11"), std::string::npos) << msg;
    EXPECT_NE(msg.find("200"), std::string::npos) << msg;
    EXPECT_NE(msg.find("370"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace pmsim
