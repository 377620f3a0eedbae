// Mineral names: aliases (assets/minerals/aliases.json), compositions of solid solutions
// ("plagioclase:An35"), their canonical spelling, and the series data behind them.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/base/input_error.h"
#include "core/base/units.h"
#include "core/crystal/crystal.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/crystal/mineral_series.h"

using namespace pmsim;

namespace {

double two_vz_deg(const Crystal& c) {
  const glm::dvec3 n = c.principal_indices(589.3);
  return optic_angle_2v_rad(n.x, n.y, n.z) * 180.0 / kPi;
}

// The InputError a bad name gives; fails the test when there is none.
InputError error_of(const std::string& name) {
  try {
    find_mineral(name);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for " << name;
  return InputError("", "", "", "");
}

}  // namespace

TEST(MineralNames, EveryAliasResolvesToItsTargetsCrystal) {
  const auto aliases = mineral_aliases();
  ASSERT_GE(aliases.size(), 20u);
  for (const auto& [alias, target] : aliases) {
    EXPECT_EQ(canonical_mineral_name(alias), canonical_mineral_name(target)) << alias;
    EXPECT_EQ(&find_mineral(alias), &find_mineral(target)) << alias;
    EXPECT_EQ(find_mineral(alias).name(), target) << alias;  // targets are canonical
  }
}

TEST(MineralNames, AliasesNamedInTheIssueResolveAsDocumented) {
  EXPECT_EQ(canonical_mineral_name("OPX"), "enstatite");
  EXPECT_EQ(canonical_mineral_name("Hypersthene"), "enstatite");
  EXPECT_EQ(canonical_mineral_name("orthopyroxene"), "enstatite");
  EXPECT_EQ(canonical_mineral_name("cpx"), "augite");
  EXPECT_EQ(canonical_mineral_name("clinopyroxene"), "augite");
  EXPECT_EQ(canonical_mineral_name("K-feldspar"), "orthoclase");
  EXPECT_EQ(canonical_mineral_name("kfs"), "orthoclase");
  EXPECT_EQ(canonical_mineral_name("amphibole"), "hornblende");
  EXPECT_EQ(canonical_mineral_name("forsterite"), "olivine:Fo100");
  EXPECT_EQ(canonical_mineral_name("fayalite"), "olivine:Fo0");
  EXPECT_EQ(canonical_mineral_name("albite"), "plagioclase:An0");
  EXPECT_EQ(canonical_mineral_name("anorthite"), "plagioclase:An100");
}

TEST(MineralNames, CompositionsHaveOneCanonicalSpellingAndOneCrystal) {
  EXPECT_EQ(canonical_mineral_name("Plagioclase:an35"), "plagioclase:An35");
  EXPECT_EQ(canonical_mineral_name(" plagioclase : An 35.50 "), "plagioclase:An35.5");
  EXPECT_EQ(canonical_mineral_name("plagioclase:An035"), "plagioclase:An35");
  EXPECT_EQ(canonical_mineral_name("olivine:Fa12"), "olivine:Fo88");
  EXPECT_EQ(canonical_mineral_name("olivine:Fa12.3"), "olivine:Fo87.7");
  EXPECT_EQ(canonical_mineral_name("plag:An60"), "plagioclase:An60");  // alias + composition
  const Crystal& a = find_mineral("plagioclase:An35");
  EXPECT_EQ(&a, &find_mineral("PLAGIOCLASE:An35.0"));
  EXPECT_EQ(a.name(), "plagioclase:An35");
  EXPECT_EQ(find_mineral("olivine:Fa12").name(), "olivine:Fo88");
  // Compositions share their series' crystallography (same file, same pointer).
  EXPECT_EQ(find_mineral_crystallography("olivine:Fo88"), find_mineral_crystallography("olivine"));
  EXPECT_EQ(find_mineral_crystallography("forsterite"), find_mineral_crystallography("olivine"));
}

TEST(MineralNames, BadNamesAreInputErrorsNamingTheValue) {
  {
    const InputError e = error_of("plagioclase:An150");
    EXPECT_EQ(e.value, "plagioclase:An150");
    EXPECT_NE(e.reason.find("An150"), std::string::npos) << e.reason;
    EXPECT_NE(e.reason.find("0..100"), std::string::npos) << e.reason;
  }
  EXPECT_NE(error_of("olivine:Fo-5").reason.find("mol %"), std::string::npos);
  for (const char* bad : {"plagioclase:Fo30", "plagioclase:An", "plagioclase:An1e1", "plagioclase:An.5",
                          "plagioclase:An3.5.1", "olivine:An50", "plagioclase:"}) {
    const InputError e = error_of(bad);
    EXPECT_EQ(e.value, bad);
    EXPECT_NE(e.reason.find("composition"), std::string::npos) << bad << ": " << e.reason;
  }
  EXPECT_NE(error_of("quartz:An10").reason.find("not a solid-solution series"), std::string::npos);
  EXPECT_NE(error_of("forsterite:Fo90").reason.find("already names a composition"), std::string::npos);
  const InputError u = error_of("unobtainium:An5");
  EXPECT_NE(u.reason.find("unknown mineral (known: "), std::string::npos);
  EXPECT_NE(u.reason.find("quartz"), std::string::npos);
  EXPECT_THROW(canonical_mineral_name("unobtainium"), InputError);
}

TEST(MineralSeries, PlainNamesKeepTheirFilesIndices) {
  // Existing scenes and golden images use the plain names: their crystals are the files' own
  // "indices" blocks, exactly (bit for bit), whatever the series says.
  EXPECT_EQ(find_mineral("plagioclase").principal_indices(589.3), glm::dvec3(1.545, 1.549, 1.553));
  EXPECT_EQ(find_mineral("olivine").principal_indices(589.3), glm::dvec3(1.654, 1.671, 1.69));
  EXPECT_EQ(find_mineral("plagioclase").name(), "plagioclase");
}

TEST(MineralSeries, IndicesInterpolateLinearlyBetweenTabulatedPoints) {
  const MineralSeries* s = find_mineral_series("plagioclase:An10");
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->component, "An");
  const glm::dvec3 n0 = find_mineral("plagioclase:An0").principal_indices(550);
  const glm::dvec3 n20 = find_mineral("plagioclase:An20").principal_indices(550);
  const glm::dvec3 n10 = find_mineral("plagioclase:An10").principal_indices(550);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(n10[k], 0.5 * (n0[k] + n20[k]), 1e-15);  // rounding only
  EXPECT_EQ(find_mineral_series("quartz"), nullptr);
}

TEST(MineralSeries, Computed2VMatchesTheLiterature2VAtEveryTabulatedComposition) {
  for (const char* name : {"plagioclase", "olivine"}) {
    const MineralSeries* s = find_mineral_series(name);
    ASSERT_NE(s, nullptr);
    for (const SeriesPoint& p : s->points) {
      ASSERT_TRUE(p.literature_2vz_deg) << name;
      const std::string comp = std::string(name) + ":" + s->component + std::to_string(int(p.composition));
      // nβ is given to 4 decimals; a change of its last digit (±0.5e-4) moves 2V by up to ~0.4°
      // in these low-birefringence series, so 0.5° is the rounding of the data, not a fit.
      EXPECT_NEAR(two_vz_deg(find_mineral(comp)), *p.literature_2vz_deg, 0.5) << comp;
    }
  }
}

TEST(MineralSeries, OlivineOpticSignFlipsNearFo85To90) {
  // Deer, Howie & Zussman 2013 (olivine): forsterite is biaxial positive (2Vz ≈ 82°), fayalite
  // negative (2Vz ≈ 134°), 2V = 90° near Fo85–Fo88. The crossing is found by bisection on the
  // interpolated indices and must lie in Fo85–Fo90, the range the brief and the texts give.
  EXPECT_LT(two_vz_deg(find_mineral("forsterite")), 90.0);
  EXPECT_GT(two_vz_deg(find_mineral("fayalite")), 90.0);
  double lo = 0, hi = 100;  // 2Vz(lo) > 90 > 2Vz(hi)
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    const std::string name = "olivine:Fo" + std::to_string(mid);
    (two_vz_deg(find_mineral(name)) > 90.0 ? lo : hi) = mid;
  }
  EXPECT_GE(lo, 85.0);
  EXPECT_LE(lo, 90.0);
  // Monotonic along the series (a sign flip, not an oscillation): sampled every 5 mol %.
  double prev = 180.0;
  for (int fo = 0; fo <= 100; fo += 5) {
    const double v = two_vz_deg(find_mineral("olivine:Fo" + std::to_string(fo)));
    EXPECT_LT(v, prev) << fo;
    prev = v;
  }
}
