// report_grain against geometry worked by hand: a quartz grain with its optic axis in the section
// plane (vibration directions along and across the c-axis trace), and a biotite flake cut
// perpendicular to its (001) cleavage.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/matrix.hpp>

#include "core/base/units.h"
#include "core/crystal/euler_angles.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/microscope/grain_report.h"
#include "core/microscope/section_map.h"

#include <nlohmann/json.hpp>

using namespace pmsim;

namespace {

// [0, 180) difference of two line angles, folded to [0, 90].
double line_diff_deg(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 180.0);
  return std::min(d, 180.0 - d);
}

glm::dmat3 rot_z(double deg) {
  const double c = std::cos(radians(deg)), s = std::sin(radians(deg));
  return glm::dmat3(c, s, 0, -s, c, 0, 0, 0, 1);  // columns
}

// A grain placed as section_map places one given by euler_deg: its lattice frame in the section
// and its indicatrix there, the mineral file's X, Y, Z carried by that frame.
SectionMap one_grain(const std::string& mineral, const glm::dmat3& lattice_to_section) {
  const MineralCrystallography* mc = find_mineral_crystallography(mineral);
  SectionMap m;
  m.name = "test";
  SectionGrain g;
  g.mineral = mineral;
  g.crystal = &find_mineral(mineral);
  g.lattice_to_section = lattice_to_section;
  g.orientation = lattice_to_section * mc->indicatrix_axes;
  m.grains.push_back(g);
  return m;
}

}  // namespace

TEST(GrainReport, QuartzWithItsOpticAxisInTheSection) {
  const double a = 35.0;  // the c axis's trace, section frame
  // Columns X, Y, Z: Z = c in the section plane at angle a, X the section normal, Y = Z × X.
  const glm::dvec3 Z(std::cos(radians(a)), std::sin(radians(a)), 0), X(0, 0, 1);
  const MineralCrystallography* m = find_mineral_crystallography("quartz");
  ASSERT_TRUE(m && m->orientation);
  const glm::dmat3 L = glm::dmat3(X, glm::cross(Z, X), Z) * glm::transpose(m->indicatrix_axes);
  SectionMap map = one_grain("quartz", L);
  map.grains[0].twinned = true;
  map.grains[0].twin_law = "test";
  map.grains[0].twin_orientation = rot_z(30.0) * map.grains[0].orientation;
  Scene s;
  s.stage_deg = 25.0;
  s.polarizer_deg = 10.0;
  s.sample.thickness_um = 30.0;
  const GrainReport r = report_grain(s, map, 1);
  // Angles below: 1e-9° is far above the rounding of a few trigonometric calls, far below any
  // geometric mistake.
  EXPECT_EQ(r.id, 1);
  EXPECT_EQ(r.mineral, "quartz");
  // Extinct when the c-axis trace (a + stage in the image) lies on the polarizer or across it.
  ASSERT_EQ(r.extinction_stage_deg.size(), 2u);
  EXPECT_NEAR(r.extinction_stage_deg[0], 65.0, 1e-9);  // 10 − 35 + 90
  EXPECT_NEAR(r.extinction_stage_deg[1], 155.0, 1e-9);
  // Elongation along c ([001]): parallel extinction, length-slow (quartz is optically positive,
  // nε > nω: the c direction vibrates slow).
  ASSERT_TRUE(r.elongation_deg);
  EXPECT_NEAR(line_diff_deg(*r.elongation_deg, a + s.stage_deg), 0.0, 1e-9);
  ASSERT_TRUE(r.extinction_angle_deg);
  EXPECT_NEAR(*r.extinction_angle_deg, 0.0, 1e-9);
  ASSERT_TRUE(r.sign_of_elongation);
  EXPECT_EQ(*r.sign_of_elongation, SignOfElongation::LengthSlow);
  EXPECT_TRUE(r.cleavage_traces_deg.empty()) << "quartz has no cleavage";
  // Γ = d (nε − nω) with both indices in the section (Nesse 2012 ch. 6), nm for d in µm.
  const glm::dvec3 n550 = find_mineral("quartz").principal_indices(550.0);
  EXPECT_NEAR(r.retardation_nm, 30.0 * 1000.0 * (n550.z - n550.x), 1e-9 * r.retardation_nm);
  // The twin individual, turned by 30°, goes extinct 30° earlier (mod 90°).
  ASSERT_TRUE(r.twin);
  EXPECT_EQ(r.twin->law, "test");
  ASSERT_EQ(r.twin->extinction_stage_deg.size(), 2u);
  EXPECT_NEAR(r.twin->extinction_stage_deg[0], 35.0, 1e-9);
  // Bunge angles: turned back into a matrix they give the lattice's axes in the section frame.
  ASSERT_TRUE(r.euler_deg);
  const glm::dmat3 back = crystal_to_sample_from_bunge(
      {radians((*r.euler_deg)[0]), radians((*r.euler_deg)[1]), radians((*r.euler_deg)[2])});
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(back[i][j], L[i][j], 1e-9);
}

TEST(GrainReport, BiotiteCutAcrossItsCleavageIsLengthSlowAlongTheTrace) {
  const MineralCrystallography* m = find_mineral_crystallography("biotite");
  ASSERT_TRUE(m && m->orientation);
  // The lattice turned so that c* (the (001) normal, crystal e3) lies in the section at angle
  // 90° + a: the cleavage trace, normal × c*, is then at angle a.
  const double a = 20.0;
  const glm::dmat3 tilt(1, 0, 0, 0, 0, 1, 0, -1, 0);  // R_x(90°): e3 → (0, −1, 0), in the section
  const glm::dmat3 lattice_to_section = rot_z(a) * tilt;
  const SectionMap map = one_grain("biotite", lattice_to_section);
  Scene s;
  s.stage_deg = 40.0;
  const GrainReport r = report_grain(s, map, 1);
  ASSERT_EQ(r.cleavage_traces_deg.size(), 1u);
  EXPECT_NEAR(line_diff_deg(r.cleavage_traces_deg[0], a + s.stage_deg), 0.0, 1e-9);
  // Tabular on (001): the elongation seen is the cleavage trace.
  ASSERT_TRUE(r.elongation_deg);
  EXPECT_NEAR(line_diff_deg(*r.elongation_deg, r.cleavage_traces_deg[0]), 0.0, 1e-9);
  // Micas are length-slow with near-parallel extinction to the cleavage (Nesse 2012, biotite:
  // "parallel or nearly so", up to a few degrees): X lies near the (001) normal.
  ASSERT_TRUE(r.sign_of_elongation);
  EXPECT_EQ(*r.sign_of_elongation, SignOfElongation::LengthSlow);
  ASSERT_TRUE(r.extinction_angle_deg);
  EXPECT_LT(*r.extinction_angle_deg, 5.0);
  EXPECT_THROW(report_grain(s, map, 2), std::out_of_range);
}

// The report's cleavage traces are the cracks the section draws, for several lattice
// orientations of a plagioclase grain (a mineral with a lattice but no optical orientation in its
// file: its crystal frame comes from euler_deg, not from its indicatrix), including ones where
// (001) or (010) lies too flat to show.
TEST(GrainReport, CleavageTracesAreTheCracksTheSectionDraws) {
  int flat_ones = 0;
  for (const double Phi : {0.0, 20.0, 45.0, 70.0, 90.0})
    for (const double phi2 : {0.0, 30.0, 60.0, 90.0}) {
      const nlohmann::json j = {
          {"size_mm", {2.0, 2.0}},
          {"grains",
           {{{"mineral", "plagioclase"}, {"centre_mm", {0.0, 0.0}}, {"size_mm", 1.5}, {"euler_deg", {15.0, Phi, phi2}}}}}};
      const SectionMap map = section_from_json(j, "cleavage test");
      Scene s;
      s.stage_deg = 12.0;
      const GrainReport r = report_grain(s, map, 1);
      ASSERT_TRUE(r.euler_deg) << "the lattice gives plagioclase its Euler angles";
      const std::vector<CleavageCracks>& cracks = map.grains[0].cracks;
      flat_ones += static_cast<int>(2 - cracks.size());
      ASSERT_EQ(r.cleavage_traces_deg.size(), cracks.size()) << "Phi " << Phi << ", phi2 " << phi2;
      // 1e-9°: the same plane normal through two code paths, rounding only.
      for (std::size_t k = 0; k < cracks.size(); ++k)
        EXPECT_NEAR(line_diff_deg(r.cleavage_traces_deg[k], degrees(cracks[k].trace_rad) + s.stage_deg), 0.0, 1e-9);
    }
  EXPECT_GT(flat_ones, 0) << "some of these orientations must put a cleavage too flat to draw";
}

// Issue 22: grains whose indicatrix is a stand-in on the crystal frame (their mineral file has no
// optical_orientation) are marked so, from the mineral data: plagioclase is, quartz, augite,
// olivine, microcline (files with the block) and almandine (isotropic: needs none) are not. The
// teaching panel's line for them says their extinction angles are not the real mineral's.
TEST(GrainReport, StandInOpticsAreMarkedFromTheMineralData) {
  nlohmann::json grains = nlohmann::json::array();
  const std::vector<std::pair<std::string, bool>> cases = {
      {"plagioclase:An35", true}, {"microcline", false}, {"quartz", false},
      {"augite", false},          {"olivine:Fo85", false}, {"almandine", false}};
  for (std::size_t k = 0; k < cases.size(); ++k)
    grains.push_back({{"mineral", cases[k].first},
                      {"centre_mm", {-1.5 + 0.6 * double(k), 0.0}},
                      {"size_mm", 0.4},
                      {"euler_deg", {10.0, 35.0, 20.0}}});
  const SectionMap map = section_from_json({{"size_mm", {4.0, 2.0}}, {"grains", grains}}, "stand-in test");
  Scene s;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const auto& [mineral, stand_in] = cases[k];
    // The data behind the mark: no optical_orientation for the stand-ins.
    const MineralCrystallography* mc = find_mineral_crystallography(mineral);
    ASSERT_TRUE(mc) << mineral;
    EXPECT_EQ(!mc->orientation && find_mineral(mineral).symmetry() != CrystalSymmetry::Isotropic, stand_in)
        << mineral;
    const GrainReport r = report_grain(s, map, int(k) + 1);
    EXPECT_EQ(r.optics_stand_in, stand_in) << mineral;
    EXPECT_STREQ(grain_optics_name(r), stand_in ? "stand-in" : "published") << mineral;
    const std::string w = grain_optics_warning(r);
    if (stand_in) {
      EXPECT_NE(w.find("stand-in"), std::string::npos) << w;
      EXPECT_NE(w.find("extinction angles are not the real mineral's"), std::string::npos) << w;
    } else {
      EXPECT_TRUE(w.empty()) << mineral << ": " << w;
    }
  }
  // A uniaxial grain given by its optic axis alone has nothing standing in; a biaxial grain of a
  // mineral without an orientation given by x_axis/z_axis has nothing the library can check.
  const SectionMap direct = section_from_json(
      {{"size_mm", {2.0, 2.0}},
       {"grains",
        {{{"mineral", "quartz"}, {"centre_mm", {-0.5, 0.0}}, {"size_mm", 0.4}, {"optic_axis", {1.0, 0.0, 0.0}}},
         {{"mineral", "plagioclase"}, {"centre_mm", {0.5, 0.0}}, {"size_mm", 0.4},
          {"x_axis", {1.0, 0.0, 0.0}}, {"z_axis", {0.0, 1.0, 0.0}}}}}},
      "direct test");
  EXPECT_FALSE(report_grain(s, direct, 1).optics_stand_in);
  EXPECT_TRUE(report_grain(s, direct, 2).optics_stand_in);
}
