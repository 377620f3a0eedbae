// Crystallography from the mineral files: lattice vectors, Miller text, optical orientation, and
// the quantities computed from them (cleavage angles, extinction angles, signs of elongation,
// retardation) against the values Deer, Howie & Zussman (2013, "DHZ") and Nesse (2012) publish.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/base/units.h"
#include "core/crystal/crystal.h"
#include "core/crystal/crystal_cut.h"
#include "core/crystal/lattice.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/crystal/section_optics.h"

using namespace pmsim;

namespace {

const MineralCrystallography& data_of(const char* name) {
  const MineralCrystallography* m = find_mineral_crystallography(name);
  if (!m) throw std::runtime_error(std::string(name) + " has no crystallography");
  return *m;
}

glm::dvec3 n_of(const char* name) { return find_mineral(name).principal_indices(589.3); }

// The section and its optics for a plane (hkl) of a mineral.
SectionOptics section_of(const char* name, const char* plane) {
  const MineralCrystallography& m = data_of(name);
  return section_optics(m.indicatrix_axes, n_of(name), plane_normal(m.cell, parse_miller_plane(plane)));
}

// Angle between the traces of two cleavage planes on the section ⟂ a direction.
double cleavage_angle_deg(const char* name, const char* p1, const char* p2, const char* section_dir) {
  const MineralCrystallography& m = data_of(name);
  const glm::dvec3 n = lattice_direction(m.cell, parse_lattice_direction(section_dir));
  return trace_angle_deg(plane_trace(n, plane_normal(m.cell, parse_miller_plane(p1))),
                         plane_trace(n, plane_normal(m.cell, parse_miller_plane(p2))));
}

}  // namespace

TEST(Lattice, BasesFollowTheStatedFrameAndAreReciprocal) {
  const UnitCell c{9.699, 8.844, 5.272, 90, 106.97, 90};  // augite
  const glm::dmat3 d = direct_basis(c), r = reciprocal_basis(c);
  // a_i · a*_j = δ_ij to rounding (1e-12: products of numbers of order 1 after 10 flops).
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(glm::dot(d[i], r[j]), i == j ? 1.0 : 0.0, 1e-12);
  // e1 ∥ a, e3 ∥ c*, monoclinic b ∥ e2; c tilted by β − 90° toward −e1.
  EXPECT_NEAR(glm::length(glm::cross(d[0], glm::dvec3(1, 0, 0))), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(glm::cross(r[2], glm::dvec3(0, 0, 1))), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(glm::cross(d[1], glm::dvec3(0, 1, 0))), 0.0, 1e-12);
  EXPECT_NEAR(degrees(std::acos(glm::normalize(d[2]).z)), 16.97, 1e-9);
  EXPECT_LT(d[2].x, 0.0);
  // Orthogonal cells give exact axes (no 1e-17 residues): cuts equal typed axes bit for bit.
  const glm::dmat3 o = direct_basis({18.2249, 8.8149, 5.1746, 90, 90, 90});
  EXPECT_EQ(glm::normalize(o[1]), glm::dvec3(0, 1, 0));
  EXPECT_EQ(glm::normalize(o[2]), glm::dvec3(0, 0, 1));
}

TEST(Lattice, MillerTextParsesAndRefusesMalformedText) {
  const auto p = parse_miller_plane("(1-10)");
  EXPECT_EQ(p.h, 1);
  EXPECT_EQ(p.k, -1);
  EXPECT_EQ(p.l, 0);
  const auto d = parse_lattice_direction("[-101]");
  EXPECT_EQ(d.u, -1);
  EXPECT_EQ(d.v, 0);
  EXPECT_EQ(d.w, 1);
  const auto wide = parse_lattice_direction("[1, 0, 12]");
  EXPECT_EQ(wide.w, 12);
  const auto mb = parse_miller_plane("(10-14)");  // Miller–Bravais (hkil) → (hkl)
  EXPECT_EQ(mb.h, 1);
  EXPECT_EQ(mb.k, 0);
  EXPECT_EQ(mb.l, 4);
  const auto a1 = parse_lattice_direction("[2-1-10]");  // [UVTW] → [uvw] = [300] ∥ a
  EXPECT_EQ(a1.u, 3);
  EXPECT_EQ(a1.v, 0);
  EXPECT_EQ(a1.w, 0);
  EXPECT_EQ(miller_text(p), "(1-10)");
  EXPECT_EQ(direction_text(d), "[-101]");
  for (const char* bad : {"110", "(11)", "(1x0)", "[110)", "(000)", "(1-2-10)", "(--110)", "()"})
    EXPECT_THROW(parse_miller_plane(bad), BadValue) << bad;
  for (const char* bad : {"[1 1]", "[a,b,c]", "[000]", "(001)"})
    EXPECT_THROW(parse_lattice_direction(bad), BadValue) << bad;
}

TEST(Lattice, CellConstraintsOfEachSystem) {
  EXPECT_NO_THROW(check_unit_cell(CrystalSystem::Monoclinic, {9.7, 8.8, 5.3, 90, 107, 90}));
  EXPECT_THROW(check_unit_cell(CrystalSystem::Monoclinic, {9.7, 8.8, 5.3, 91, 107, 90}), BadValue);
  EXPECT_THROW(check_unit_cell(CrystalSystem::Monoclinic, {9.7, 8.8, 5.3, 90, 90, 90}), BadValue);
  EXPECT_THROW(check_unit_cell(CrystalSystem::Orthorhombic, {4.7, 10.2, 6.0, 90, 91, 90}), BadValue);
  EXPECT_THROW(check_unit_cell(CrystalSystem::Trigonal, {4.9, 4.9, 5.4, 90, 90, 90}), BadValue);
  EXPECT_THROW(check_unit_cell(CrystalSystem::Tetragonal, {4.9, 5.0, 5.4, 90, 90, 90}), BadValue);
  EXPECT_THROW(check_unit_cell(CrystalSystem::Cubic, {4, 4, 4.1, 90, 90, 90}), BadValue);
  EXPECT_THROW(check_unit_cell(CrystalSystem::Triclinic, {8, 13, 7, 10, 10, 170}), BadValue);  // no volume
  EXPECT_THROW(check_unit_cell(CrystalSystem::Triclinic, {-8, 13, 7, 94, 116, 88}), BadValue);
}

TEST(Crystallography, EveryMineralWithDataHasARightHandedOrthonormalIndicatrix) {
  int with_orientation = 0;
  for (const std::string& name : mineral_names()) {
    const MineralCrystallography* m = find_mineral_crystallography(name);
    if (!m || !m->orientation) continue;
    ++with_orientation;
    const glm::dmat3 A = m->indicatrix_axes;
    const glm::dmat3 I = glm::transpose(A) * A;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(I[i][j], i == j ? 1.0 : 0.0, 1e-12) << name;
    EXPECT_NEAR(glm::determinant(A), 1.0, 1e-12) << name;
  }
  // Every anisotropic mineral of the library but the triclinic feldspars (plagioclase,
  // microcline: their files say why) has orientation data; counted so that a file whose block
  // failed to load cannot pass unnoticed.
  EXPECT_GE(with_orientation, 16);
  ASSERT_NE(find_mineral_crystallography("plagioclase"), nullptr);
  EXPECT_FALSE(find_mineral_crystallography("plagioclase")->orientation);
}

// (a) Cleavage angles in sections ⟂ c, computed from the cells. Published: pyroxene {110} 87°/93°
// (DHZ; Handbook of Mineralogy "(110) ∧ (1-10) ≈ 87°"), orthopyroxene {210} ~88°, amphibole
// {110} ~56°/124° (DHZ, Nesse). The tolerance, 1°, is the rounding of the published values (given
// to the degree) plus the spread of cells within a mineral series (a/b varies by < 1%, which moves
// the angle by < 0.6°).
TEST(Crystallography, PrismaticCleavageAnglesInBasalSections) {
  const double aug = cleavage_angle_deg("augite", "(110)", "(1-10)", "[001]");
  EXPECT_NEAR(aug, 87.0, 1.0);
  EXPECT_NEAR(180.0 - aug, 93.0, 1.0);
  EXPECT_NEAR(cleavage_angle_deg("diopside", "(110)", "(1-10)", "[001]"), 87.0, 1.0);
  EXPECT_NEAR(cleavage_angle_deg("enstatite", "(210)", "(2-10)", "[001]"), 88.0, 1.0);
  const double hbl = cleavage_angle_deg("hornblende", "(110)", "(1-10)", "[001]");
  EXPECT_NEAR(hbl, 56.0, 1.0);
  EXPECT_NEAR(180.0 - hbl, 124.0, 1.0);
  // Calcite rhombohedral cleavages: the faces of the cleavage rhomb meet at 74.9°/105.1° (DHZ);
  // on a section ⟂ c their traces form 60° (threefold axis): exact by symmetry, 1e-9.
  const MineralCrystallography& cal = data_of("calcite");
  const glm::dvec3 n1 = plane_normal(cal.cell, parse_miller_plane("(10-14)"));
  const glm::dvec3 n2 = plane_normal(cal.cell, parse_miller_plane("(-1104)"));
  // The acute angle between the planes (74°55′ in DHZ); 0.2°: the published value is to the
  // minute and a/c of calcites varies by ~0.1%.
  EXPECT_NEAR(degrees(std::acos(std::abs(glm::dot(n1, n2)))), 74.9, 0.2);
  EXPECT_NEAR(cleavage_angle_deg("calcite", "(10-14)", "(-1104)", "[001]"), 60.0, 1e-9);
}

// Extinction angles of (010) sections measured from the c trace (the prism cleavage traces there
// are ∥ c) equal the tabulated Z ∧ c of monoclinic b = Y minerals: computed from the data, they
// must land in the published ranges.
TEST(Crystallography, ExtinctionAnglesOfSectionsParallelTo010) {
  struct Case {
    const char* name;
    double lo, hi;
    bool to_slow;
  };
  for (const Case& k : {Case{"augite", 35, 48, true}, Case{"diopside", 38, 48, true},
                        Case{"hornblende", 12, 34, true}, Case{"gypsum", 38, 38, false}}) {
    const MineralCrystallography& m = data_of(k.name);
    const SectionOptics s = section_of(k.name, "(010)");
    const glm::dvec3 c = lattice_direction(m.cell, {0, 0, 1});
    const Extinction e = extinction_from(s, c);
    if (std::string(k.name) == "gypsum") {
      // Z ∧ c = 52° puts X at 38° from c: the nearer direction is the fast one. 1e-9: exact
      // geometry, the only error is rounding.
      EXPECT_NEAR(e.angle_deg, 38.0, 1e-9);
      EXPECT_FALSE(e.nearer_is_slow);
      continue;
    }
    EXPECT_GE(e.angle_deg, k.lo) << k.name;
    EXPECT_LE(e.angle_deg, k.hi) << k.name;
    EXPECT_EQ(e.nearer_is_slow, k.to_slow) << k.name;
    // and it is the angle typed as the orientation (Y = b makes (010) contain X and Z): 1e-9.
    EXPECT_NEAR(e.angle_deg, m.orientation->angle_deg, 1e-9) << k.name;
  }
  // Orthopyroxene: parallel extinction in prismatic sections (Nesse: "parallel"), in (010) and
  // (100) alike: exact, 1e-9.
  for (const char* plane : {"(010)", "(100)", "(110)"}) {
    const MineralCrystallography& m = data_of("enstatite");
    const SectionOptics s = section_of("enstatite", plane);
    EXPECT_NEAR(extinction_from(s, lattice_direction(m.cell, {0, 0, 1})).angle_deg, 0.0, 1e-9) << plane;
  }
}

// Micas in sections ⟂ (001): extinction to the cleavage trace is parallel or nearly so, "at most a
// few degrees" (Nesse 2012: muscovite 0–3°, biotite nearly parallel). Both (010) and (100)
// sections contain the (001) normal's neighbourhood; (100) sections show exact parallel extinction
// when b is an indicatrix axis (1e-9), (010) sections show the small inclined angle.
TEST(Crystallography, MicasExtinguishNearlyParallelToTheirCleavage) {
  for (const char* name : {"muscovite", "biotite"}) {
    const MineralCrystallography& m = data_of(name);
    const glm::dvec3 cleavage = plane_normal(m.cell, {0, 0, 1});
    for (const char* plane : {"(010)", "(100)"}) {
      const SectionOptics s = section_of(name, plane);
      const Extinction e = extinction_from(s, plane_trace(s.normal, cleavage));
      EXPECT_LE(e.angle_deg, 3.5) << name << " " << plane;
      EXPECT_TRUE(e.nearer_is_slow) << name << " " << plane;  // micas are length-slow
      if (std::string(plane) == "(100)") {
        EXPECT_NEAR(e.angle_deg, 0.0, 1e-9) << name;
      }
    }
  }
}

// (c) Signs of elongation with known answers (Nesse 2012 mineral descriptions): quartz prisms
// length-slow (uniaxial +, elongate ∥ c); tourmaline length-fast (uniaxial −, elongate ∥ c;
// Nesse's textbook example); enstatite length-slow (Z = c); augite and hornblende prisms in (010)
// length-slow (Z within 45° of c); micas in sections ⟂ (001) length-slow (X ⟂ the plates).
TEST(Crystallography, SignsOfElongation) {
  auto sign_in = [](const char* name, const glm::dvec3& normal) {
    const MineralCrystallography& m = data_of(name);
    const SectionOptics s = section_optics(m.indicatrix_axes, n_of(name), normal);
    glm::dvec3 length;
    if (m.habit.elongation)
      length = projected_direction(normal, lattice_direction(m.cell, *m.habit.elongation));
    else
      length = plane_trace(normal, plane_normal(m.cell, *m.habit.tabular));
    return sign_of_elongation(s, length);
  };
  auto normal_of = [](const char* name, const char* plane) {
    const MineralCrystallography& m = data_of(name);
    return plane_normal(m.cell, parse_miller_plane(plane));
  };
  EXPECT_EQ(sign_in("quartz", normal_of("quartz", "(1-100)")), SignOfElongation::LengthSlow);
  EXPECT_EQ(sign_in("tourmaline", normal_of("tourmaline", "(11-20)")), SignOfElongation::LengthFast);
  EXPECT_EQ(sign_in("enstatite", normal_of("enstatite", "(100)")), SignOfElongation::LengthSlow);
  EXPECT_EQ(sign_in("enstatite", normal_of("enstatite", "(010)")), SignOfElongation::LengthSlow);
  EXPECT_EQ(sign_in("augite", normal_of("augite", "(010)")), SignOfElongation::LengthSlow);
  EXPECT_EQ(sign_in("hornblende", normal_of("hornblende", "(010)")), SignOfElongation::LengthSlow);
  EXPECT_EQ(sign_in("muscovite", normal_of("muscovite", "(010)")), SignOfElongation::LengthSlow);
  EXPECT_EQ(sign_in("biotite", normal_of("biotite", "(100)")), SignOfElongation::LengthSlow);
  // A basal section of a uniaxial crystal is circular: no sign.
  const MineralCrystallography& q = data_of("quartz");
  const SectionOptics basal =
      section_optics(q.indicatrix_axes, n_of("quartz"), plane_normal(q.cell, {0, 0, 1}));
  EXPECT_TRUE(basal.circular);
}

// Retardation of a section: Γ = d·(n′γ − n′α). An (010) section of a b = Y monoclinic crystal
// contains X and Z, so it shows the full birefringence nγ − nα; a section ⟂ c of quartz shows 0.
// Exact to rounding (1e-9 nm).
TEST(Crystallography, RetardationOfPrincipalSections) {
  const glm::dvec3 n = n_of("augite");
  EXPECT_NEAR(retardation_nm(section_of("augite", "(010)"), 30.0), 30000.0 * (n.z - n.x), 1e-9);
  const glm::dvec3 ol = n_of("olivine");
  // olivine (001) ⟂ c = Y contains a = Z and b = X: nγ − nα again.
  EXPECT_NEAR(retardation_nm(section_of("olivine", "(001)"), 30.0), 30000.0 * (ol.z - ol.x), 1e-9);
  // (100) ⟂ Z contains X and Y.
  EXPECT_NEAR(retardation_nm(section_of("olivine", "(100)"), 30.0), 30000.0 * (ol.y - ol.x), 1e-9);
}

TEST(CrystalCut, MapsPlaneToStageNormalAndNorthToPlusY) {
  const MineralCrystallography& m = data_of("augite");
  const glm::dmat3 R = crystal_to_lab_of_cut(m.cell, {0, 1, 0}, {0, 0, 1});
  // 1e-12: a rotation built from unit vectors; errors are rounding only.
  const glm::dvec3 z = R * plane_normal(m.cell, {0, 1, 0});
  const glm::dvec3 y = R * lattice_direction(m.cell, {0, 0, 1});
  EXPECT_NEAR(glm::length(z - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(y - glm::dvec3(0, 1, 0)), 0.0, 1e-12);
  EXPECT_NEAR(glm::determinant(R), 1.0, 1e-12);
  // North out of the plane: refused, the message giving the angle. [100] makes 0° with (010);
  // [010] makes 90°.
  EXPECT_NEAR(direction_plane_angle_deg(m.cell, {0, 1, 0}, {1, 0, 0}), 0.0, 1e-12);
  EXPECT_NEAR(direction_plane_angle_deg(m.cell, {0, 1, 0}, {0, 1, 0}), 90.0, 1e-9);
  try {
    cut_orientation(m, {0, 1, 0}, {1, 1, 0});
    FAIL() << "north out of the plane accepted";
  } catch (const BadValue& b) {
    EXPECT_NE(b.why.find("° with the plane (010)"), std::string::npos) << b.why;
  }
}

TEST(MineralCrystallography, BadBlocksNameFileKeyAndValue) {
  const nlohmann::json base = nlohmann::json::parse(R"J({
    "crystal_system": "monoclinic",
    "unit_cell": {"a": 9.7, "b": 8.8, "c": 5.3, "alpha": 90, "beta": 107, "gamma": 90, "source": "s"},
    "optical_orientation": {"b": "Y", "inclined": {"axis": "Z", "from": "c", "angle_deg": 42,
                            "side": "obtuse_beta"}, "source": "s"},
    "cleavage": [{"plane": "(110)", "quality": "good", "source": "s"}]})J");
  EXPECT_NO_THROW(read_mineral_crystallography(JsonReader(base, "f.json"), CrystalSymmetry::Biaxial));
  auto key_of = [&](const char* pointer, const nlohmann::json& v, CrystalSymmetry sym) {
    nlohmann::json j = base;
    j[nlohmann::json::json_pointer(pointer)] = v;
    try {
      read_mineral_crystallography(JsonReader(j, "f.json"), sym);
    } catch (const InputError& e) {
      EXPECT_EQ(e.file, "f.json");
      return e.key;
    }
    return std::string("accepted");
  };
  const auto B = CrystalSymmetry::Biaxial;
  EXPECT_EQ(key_of("/cleavage/0/plane", "(1x0)", B), "cleavage[0].plane");
  EXPECT_EQ(key_of("/unit_cell/alpha", 95, B), "unit_cell");  // monoclinic needs α = 90°
  EXPECT_EQ(key_of("/optical_orientation/inclined/axis", "Y", B), "optical_orientation");
  EXPECT_EQ(key_of("/optical_orientation/inclined/side", "sideways", B), "optical_orientation.inclined.side");
  EXPECT_EQ(key_of("/crystal_system", "cubic", B), "unit_cell");
  EXPECT_EQ(key_of("/unit_cell/source", "", B), "unit_cell.source");
  EXPECT_EQ(key_of("/cleavage/0/quality", "superb", B), "cleavage[0].quality");
  EXPECT_EQ(key_of("/unit_cell/beta", 107, CrystalSymmetry::Uniaxial), "optical_orientation");
}
