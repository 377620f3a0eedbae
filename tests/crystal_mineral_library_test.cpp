// The mineral library as a whole: every file loads with its cited crystallography, and the
// quantities computed from the data of the newer minerals (extinction, signs of elongation,
// cleavage angles) land on what Nesse (2012), Deer, Howie & Zussman (2013, "DHZ") and the
// Handbook of Mineralogy publish.
#include <cmath>
#include <filesystem>
#include <string>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/base/asset_locator.h"
#include "core/base/json_reader.h"
#include "core/base/units.h"
#include "core/crystal/crystal.h"
#include "core/crystal/lattice.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/crystal/section_optics.h"

using namespace pmsim;

namespace {

const MineralCrystallography& data_of(const std::string& name) {
  const MineralCrystallography* m = find_mineral_crystallography(name);
  if (!m) throw std::runtime_error(name + " has no crystallography");
  return *m;
}

SectionOptics section_of(const std::string& name, const char* plane) {
  const MineralCrystallography& m = data_of(name);
  return section_optics(m.indicatrix_axes, find_mineral(name).principal_indices(589.3),
                        plane_normal(m.cell, parse_miller_plane(plane)));
}

// The elongation seen in a section: the habit's direction projected, or the trace of its
// tabular plane.
glm::dvec3 length_in(const std::string& name, const SectionOptics& s) {
  const MineralCrystallography& m = data_of(name);
  if (m.habit.elongation) return projected_direction(s.normal, lattice_direction(m.cell, *m.habit.elongation));
  return plane_trace(s.normal, plane_normal(m.cell, *m.habit.tabular));
}

// Dihedral angle between two lattice planes, acute, in degrees.
double plane_angle_deg(const std::string& name, const char* p1, const char* p2) {
  const MineralCrystallography& m = data_of(name);
  const double c = glm::dot(plane_normal(m.cell, parse_miller_plane(p1)), plane_normal(m.cell, parse_miller_plane(p2)));
  return degrees(std::acos(std::abs(c)));
}

// A phase whose file says "amorphous": true (glass) has no crystal system or cell.
bool is_amorphous(const std::string& name) {
  const std::string path = asset_dir() + "/minerals/" + name + ".json";
  if (!std::filesystem::is_regular_file(path)) return false;  // an alias
  return read_json_file(path, "mineral file").value("amorphous", false);
}

}  // namespace

TEST(MineralLibrary, EveryMineralHasCitedCrystallography) {
  int anisotropic_with_orientation = 0;
  for (const std::string& name : mineral_names()) {
    SCOPED_TRACE(name);
    const Crystal& c = find_mineral(name);
    EXPECT_FALSE(c.source().empty());
    const MineralCrystallography* m = find_mineral_crystallography(name);
    if (is_amorphous(name)) {  // volcanic glass: no lattice to cite, and isotropic by nature
      EXPECT_EQ(m, nullptr);
      EXPECT_EQ(c.symmetry(), CrystalSymmetry::Isotropic);
      continue;
    }
    ASSERT_NE(m, nullptr) << "every library mineral has at least its crystal system and cell";
    EXPECT_FALSE(m->cell_source.empty());
    if (m->orientation) {
      EXPECT_FALSE(m->orientation->source.empty());
      ++anisotropic_with_orientation;
    } else if (c.symmetry() != CrystalSymmetry::Isotropic) {
      // Only triclinic feldspars lack the full published orientation of X, Y, Z (see their
      // files' notes); everything else anisotropic has one.
      EXPECT_EQ(m->system, CrystalSystem::Triclinic);
    }
    for (const Cleavage& k : m->cleavage) EXPECT_FALSE(k.source.empty());
    if (m->habit.elongation || m->habit.tabular) {
      EXPECT_FALSE(m->habit.source.empty());
    }
    for (const TwinLaw& t : m->twins) EXPECT_FALSE(t.source.empty());
  }
  EXPECT_GE(anisotropic_with_orientation, 16);
}

// Prism sections of orthorhombic and pseudo-orthorhombic minerals with Z ∥ c show parallel
// extinction and are length-slow (Nesse 2012: sillimanite, staurolite). Exact geometry: 1e-9°.
TEST(MineralLibrary, ParallelExtinctionAndLengthSlowPrisms) {
  for (const char* name : {"sillimanite", "staurolite"}) {
    for (const char* plane : {"(100)", "(010)", "(110)"}) {
      const SectionOptics s = section_of(name, plane);
      const glm::dvec3 length = length_in(name, s);
      EXPECT_NEAR(extinction_from(s, length).angle_deg, 0.0, 1e-9) << name << plane;
      EXPECT_EQ(sign_of_elongation(s, length), SignOfElongation::LengthSlow) << name << plane;
    }
  }
}

// Uniaxial prisms: apatite (−) length-fast, zircon (+) length-slow, both with parallel
// extinction (Nesse 2012). Exact: 1e-9°.
TEST(MineralLibrary, UniaxialAccessoryPrisms) {
  struct Case {
    const char* name;
    const char* plane;
    SignOfElongation sign;
  };
  for (const Case& k : {Case{"apatite", "(10-10)", SignOfElongation::LengthFast},
                        Case{"zircon", "(100)", SignOfElongation::LengthSlow},
                        Case{"zircon", "(110)", SignOfElongation::LengthSlow}}) {
    const SectionOptics s = section_of(k.name, k.plane);
    const glm::dvec3 length = length_in(k.name, s);
    EXPECT_NEAR(extinction_from(s, length).angle_deg, 0.0, 1e-9) << k.name;
    EXPECT_EQ(sign_of_elongation(s, length), k.sign) << k.name;
  }
}

// Chlorite (clinochlore, optically positive): Z nearly ⟂ (001), so sections across the plates
// extinguish within a degree of the cleavage trace and are length-fast, unlike the micas (Nesse
// 2012: "positive chlorites are length-fast"). 1°: the data put Z 0.3° from the (001) normal.
TEST(MineralLibrary, ChloriteIsLengthFastOnItsCleavage) {
  for (const char* plane : {"(010)", "(100)", "(110)"}) {
    const SectionOptics s = section_of("chlorite", plane);
    const glm::dvec3 trace = plane_trace(s.normal, plane_normal(data_of("chlorite").cell, {0, 0, 1}));
    EXPECT_LE(extinction_from(s, trace).angle_deg, 1.0) << plane;
    EXPECT_EQ(sign_of_elongation(s, trace), SignOfElongation::LengthFast) << plane;
  }
}

// Kyanite, triclinic: Z′ ∧ c = 27–32° on (100), Z′ ∧ c = 5–8° on (010), X′ ∧ a = 0–25° on (001)
// (Handbook of Mineralogy). The (100) angle is the datum (30°) and comes back exactly (1e-9°);
// the other two are predictions of the data. On (010) the model gives 4.2°: the Handbook's X is
// only "approximately ⟂ (100)", and the few degrees that X leans off the (100) normal in real
// kyanite are not published, so the check there is the published upper bound only.
TEST(MineralLibrary, KyaniteExtinctionOnItsCleavageFaces) {
  const MineralCrystallography& m = data_of("kyanite");
  const glm::dvec3 a = lattice_direction(m.cell, {1, 0, 0}), c = lattice_direction(m.cell, {0, 0, 1});
  const SectionOptics s100 = section_of("kyanite", "(100)");
  const Extinction e100 = extinction_from(s100, projected_direction(s100.normal, c));
  EXPECT_NEAR(e100.angle_deg, 30.0, 1e-9);
  EXPECT_TRUE(e100.nearer_is_slow);
  const SectionOptics s010 = section_of("kyanite", "(010)");
  const Extinction e010 = extinction_from(s010, projected_direction(s010.normal, c));
  EXPECT_LE(e010.angle_deg, 8.0);
  EXPECT_TRUE(e010.nearer_is_slow);
  const SectionOptics s001 = section_of("kyanite", "(001)");
  const Extinction e001 = extinction_from(s001, projected_direction(s001.normal, a));
  EXPECT_LE(e001.angle_deg, 25.0);
  EXPECT_FALSE(e001.nearer_is_slow);  // X′ is the nearer one
  // Bladed crystals elongate along c, (100) sections length-slow (Nesse 2012).
  EXPECT_EQ(sign_of_elongation(s100, length_in("kyanite", s100)), SignOfElongation::LengthSlow);
}

// The two feldspar cleavages (001) and (010), computed from the cells: plagioclase 93–94°
// (Nesse 2012), microcline 90°41′ (Handbook of Mineralogy: "intersecting at 90°"; DHZ). 0.5°:
// the published values are given to the degree (plagioclase) or minute, and the cell of one
// sample stands for the mineral (the angle α* varies by ~0.5° across the plagioclase series in
// Brown et al. 2016).
TEST(MineralLibrary, FeldsparCleavageAnglesFromTheCells) {
  EXPECT_NEAR(180.0 - plane_angle_deg("plagioclase", "(001)", "(010)"), 93.5, 0.5);
  EXPECT_NEAR(180.0 - plane_angle_deg("microcline", "(001)", "(010)"), 90.0 + 41.0 / 60.0, 0.5);
  // A composition shares the series' lattice.
  EXPECT_EQ(&data_of("plagioclase:An60"), &data_of("plagioclase"));
}

// The prismatic {110} cleavages of the chain silicates in sections ⟂ c, computed from each cell:
// pyroxenes ~87°/93°, amphiboles ~56°/124° (DHZ; Nesse 2012). 1°: the published angles are
// given to the degree and a/b varies within each series by < 1 % (< 0.6° of angle).
TEST(MineralLibrary, ChainSilicateCleavageAnglesFromTheCells) {
  auto angle = [](const std::string& name) {
    const MineralCrystallography& m = data_of(name);
    const glm::dvec3 c = lattice_direction(m.cell, {0, 0, 1});
    return trace_angle_deg(plane_trace(c, plane_normal(m.cell, {1, 1, 0})),
                           plane_trace(c, plane_normal(m.cell, {1, -1, 0})));
  };
  for (const char* px : {"augite", "diopside", "omphacite", "jadeite", "aegirine"})
    EXPECT_NEAR(angle(px), 87.0, 1.0) << px;
  for (const char* amph : {"hornblende", "tremolite", "actinolite", "glaucophane"})
    EXPECT_NEAR(angle(amph), 56.0, 1.0) << amph;
}

// Extinction of (010) sections against the c trace (the prism cleavage traces there are ∥ c),
// computed from the orientation data of the b = Y monoclinic pyroxenes and amphiboles: inside
// the published ranges of Nesse (2012) and DHZ (2013). Aegirine's nearer direction is the fast
// one (X ∧ c small, length-fast); the others' is the slow one (Z ∧ c).
TEST(MineralLibrary, MonoclinicChainSilicateExtinctionAnglesInTheirPublishedRanges) {
  struct Case {
    const char* name;
    double lo_deg, hi_deg;
    bool nearer_is_slow;
  };
  for (const Case& k : {Case{"omphacite", 35, 48, true}, Case{"jadeite", 33, 40, true},
                        Case{"aegirine", 0, 10, false}, Case{"tremolite", 10, 21, true},
                        Case{"actinolite", 10, 21, true}, Case{"glaucophane", 4, 14, true}}) {
    const SectionOptics s = section_of(k.name, "(010)");
    const Extinction e = extinction_from(s, lattice_direction(data_of(k.name).cell, {0, 0, 1}));
    EXPECT_GE(e.angle_deg, k.lo_deg) << k.name;
    EXPECT_LE(e.angle_deg, k.hi_deg) << k.name;
    EXPECT_EQ(e.nearer_is_slow, k.nearer_is_slow) << k.name;
    EXPECT_EQ(sign_of_elongation(s, length_in(k.name, s)),
              k.nearer_is_slow ? SignOfElongation::LengthSlow : SignOfElongation::LengthFast)
        << k.name;
  }
}

// Pleochroism tied to X, Y, Z (Nesse 2012): staurolite's Z golden yellow (absorbs blue) against
// a colourless X; glaucophane's Z blue (absorbs red) against a colourless X; chlorite's
// Y = Z greener (absorb red more than X). Ordering checks: the tables are shaped, not measured,
// so only which axis absorbs more at which end of the spectrum is a published fact.
TEST(MineralLibrary, PleochroismFollowsThePublishedAxisColours) {
  const glm::dvec3 st_blue = find_mineral("staurolite").principal_absorption_per_um(450);
  EXPECT_GT(st_blue.z, st_blue.y);
  EXPECT_GT(st_blue.y, st_blue.x);
  const Crystal& gln = find_mineral("glaucophane");
  EXPECT_GT(gln.principal_absorption_per_um(650).z, gln.principal_absorption_per_um(650).x);
  EXPECT_GT(gln.principal_absorption_per_um(650).z, gln.principal_absorption_per_um(450).z);  // blue
  const glm::dvec3 chl_red = find_mineral("chlorite").principal_absorption_per_um(650);
  EXPECT_GT(chl_red.y, chl_red.x);
  EXPECT_EQ(chl_red.y, chl_red.z);
  for (const char* name : {"staurolite", "glaucophane", "aegirine", "actinolite", "chlorite", "phlogopite"})
    EXPECT_TRUE(find_mineral(name).absorbing()) << name;
}
