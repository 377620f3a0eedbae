// The orientation conventions of EBSD files: each vendor's crystal frame against pmsim's, each
// vendor's Euler reference frame against the section, and where map points lie on the section.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "core/base/units.h"
#include "core/ebsd/ctf_reader.h"
#include "core/ebsd/ebsd_frames.h"
#include "tests/ebsd_test_files.h"

namespace pmsim {
namespace {

// Rotation matrices built from unit vectors in double precision: entries exact to ~1e-15; 1e-12
// leaves room for the few products involved.
constexpr double kTol = 1e-12;

void expect_near(const glm::dvec3& got, const glm::dvec3& want, double tol, const char* what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], tol) << what << " component " << k;
}

void expect_proper_rotation(const glm::dmat3& R, const char* what) {
  const glm::dmat3 id = glm::transpose(R) * R;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(id[c][r], c == r ? 1.0 : 0.0, kTol) << what;
  EXPECT_NEAR(glm::determinant(R), 1.0, kTol) << what;
}

const UnitCell kQuartz{4.913, 4.913, 5.405, 90, 90, 120};
const UnitCell kAugite{9.699, 8.844, 5.272, 90, 105.93, 90};
const UnitCell kTriclinic{8.14, 12.79, 7.16, 94.3, 116.6, 87.7};  // albite-like
const UnitCell kForsterite{4.756, 10.207, 5.980, 90, 90, 90};

TEST(EbsdFrames, OrthogonalCellsShareOneFrame) {
  for (EbsdVendor v : {EbsdVendor::OxfordChannel5, EbsdVendor::EdaxTsl})
    for (CrystalSystem s : {CrystalSystem::Cubic, CrystalSystem::Tetragonal, CrystalSystem::Orthorhombic}) {
      const glm::dmat3 R = vendor_crystal_frame(v, s, kForsterite);
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) EXPECT_NEAR(R[c][r], c == r ? 1.0 : 0.0, kTol);
    }
}

TEST(EbsdFrames, HexagonalXIsAlongAStarForOxfordAndAlongAForEdax) {
  for (CrystalSystem s : {CrystalSystem::Hexagonal, CrystalSystem::Trigonal}) {
    const glm::dmat3 ox = vendor_crystal_frame(EbsdVendor::OxfordChannel5, s, kQuartz);
    const glm::dmat3 ed = vendor_crystal_frame(EbsdVendor::EdaxTsl, s, kQuartz);
    expect_proper_rotation(ox, "Oxford");
    expect_proper_rotation(ed, "EDAX");
    // Oxford: x ∥ a* = the normal of (100) = [10-10], 30° from a toward b; z ∥ c.
    expect_near(ox[0], plane_normal(kQuartz, {1, 0, 0}), kTol, "Oxford x");
    expect_near(ox[0], glm::dvec3(std::cos(radians(30)), std::sin(radians(30)), 0), kTol, "Oxford x at 30°");
    expect_near(ox[1], lattice_direction(kQuartz, {0, 1, 0}), kTol, "Oxford y ∥ b = [-12-10]");
    expect_near(ox[2], lattice_direction(kQuartz, {0, 0, 1}), kTol, "Oxford z");
    // EDAX: x ∥ a = [2-1-10], z ∥ c: pmsim's own frame.
    expect_near(ed[0], lattice_direction(kQuartz, {1, 0, 0}), kTol, "EDAX x");
    expect_near(ed[2], lattice_direction(kQuartz, {0, 0, 1}), kTol, "EDAX z");
  }
}

TEST(EbsdFrames, MonoclinicAndTriclinicFrames) {
  for (EbsdVendor v : {EbsdVendor::OxfordChannel5, EbsdVendor::EdaxTsl}) {
    // b unique: x ∥ a*, y ∥ b, z ∥ c for both vendors (pmsim: x ∥ a, z ∥ c*): a turn of β − 90°
    // about b.
    const glm::dmat3 R = vendor_crystal_frame(v, CrystalSystem::Monoclinic, kAugite);
    expect_proper_rotation(R, "monoclinic");
    expect_near(R[0], plane_normal(kAugite, {1, 0, 0}), kTol, "x ∥ a*");
    expect_near(R[1], lattice_direction(kAugite, {0, 1, 0}), kTol, "y ∥ b");
    expect_near(R[2], lattice_direction(kAugite, {0, 0, 1}), kTol, "z ∥ c");
    EXPECT_NEAR(std::acos(R[0][0]), radians(105.93 - 90.0), 1e-12);
  }
  const glm::dmat3 ox = vendor_crystal_frame(EbsdVendor::OxfordChannel5, CrystalSystem::Triclinic, kTriclinic);
  const glm::dmat3 ed = vendor_crystal_frame(EbsdVendor::EdaxTsl, CrystalSystem::Triclinic, kTriclinic);
  expect_proper_rotation(ox, "Oxford triclinic");
  expect_proper_rotation(ed, "EDAX triclinic");
  expect_near(ox[0], plane_normal(kTriclinic, {1, 0, 0}), kTol, "Oxford x ∥ a*");
  expect_near(ox[2], lattice_direction(kTriclinic, {0, 0, 1}), kTol, "Oxford z ∥ c");
  expect_near(ed[0], lattice_direction(kTriclinic, {1, 0, 0}), kTol, "EDAX x ∥ a");
  expect_near(ed[2], plane_normal(kTriclinic, {0, 0, 1}), kTol, "EDAX z ∥ c*");
}

TEST(EbsdFrames, SpecimenFramesOnTheSection) {
  // Oxford: the Euler frame is x right (east), y up (north), z toward the observer.
  const glm::dmat3 ox = vendor_specimen_frame(EbsdVendor::OxfordChannel5);
  expect_proper_rotation(ox, "Oxford");
  expect_near(ox[0], {1, 0, 0}, kTol, "Oxford X");
  expect_near(ox[1], {0, 1, 0}, kTol, "Oxford Y");
  // EDAX: X along the map's y (down on the display: south), Y along the map's x (east).
  const glm::dmat3 ed = vendor_specimen_frame(EbsdVendor::EdaxTsl);
  expect_proper_rotation(ed, "EDAX");
  expect_near(ed[0], {0, -1, 0}, kTol, "EDAX X");
  expect_near(ed[1], {1, 0, 0}, kTol, "EDAX Y");
  expect_near(ed[2], {0, 0, 1}, kTol, "EDAX Z");
}

TEST(EbsdFrames, HexagonalCAxisAlongTheMapsXBothWays) {
  // The same grain, c along the map's x (east on the section), as each vendor writes it.
  // Oxford specimen X is east: Bunge e3 = (sin φ1 sin Φ, −cos φ1 sin Φ, cos Φ) = X at φ1 = Φ = 90°.
  // EDAX specimen Y is east: e3 = Y at φ1 = 180°, Φ = 90°.
  const glm::dvec3 c_axis(0, 0, 1), east(1, 0, 0);
  for (CrystalSystem s : {CrystalSystem::Hexagonal, CrystalSystem::Trigonal}) {
    const glm::dmat3 Rox = vendor_crystal_frame(EbsdVendor::OxfordChannel5, s, kQuartz);
    const glm::dmat3 Red = vendor_crystal_frame(EbsdVendor::EdaxTsl, s, kQuartz);
    const glm::dmat3 ox = crystal_to_section(EbsdVendor::OxfordChannel5, Rox, {radians(90), radians(90), 0.0});
    const glm::dmat3 ed = crystal_to_section(EbsdVendor::EdaxTsl, Red, {radians(180), radians(90), 0.0});
    expect_near(ox * c_axis, east, kTol, "Oxford c");
    expect_near(ed * c_axis, east, kTol, "EDAX c");
    // With all angles 0 the a axis shows the crystal-frame convention: Oxford's x is a*, so a lies
    // 30° clockwise of the specimen X (east); EDAX's x is a, along its X (south).
    const glm::dvec3 a_axis(1, 0, 0);
    expect_near(crystal_to_section(EbsdVendor::OxfordChannel5, Rox, {}) * a_axis,
                {std::cos(radians(-30)), std::sin(radians(-30)), 0}, kTol, "Oxford a");
    expect_near(crystal_to_section(EbsdVendor::EdaxTsl, Red, {}) * a_axis, {0, -1, 0}, kTol, "EDAX a");
  }
}

TEST(EbsdFrames, ReadPointToSection) {
  // End to end: a .ctf point at (90°, 90°, 0°) of a trigonal phase has its c axis east.
  const std::string text =
      "Channel Text File\nXCells\t2\nYCells\t1\nXStep\t1000\nYStep\t1000\nPhases\t1\n"
      "4.913;4.913;5.405\t90;90;120\tQuartz\t7\t154\n"
      "Phase\tX\tY\tBands\tError\tEuler1\tEuler2\tEuler3\tMAD\tBC\tBS\n"
      "1\t0\t0\t8\t0\t90\t90\t0\t0.4\t150\t160\n1\t1000\t0\t8\t0\t0\t0\t0\t0.4\t150\t160\n";
  ebsd_test::ScratchDir dir;
  const OrientationMap m = read_ctf(dir.file("c.ctf", text));
  const EbsdPhase& q = *m.phase_of(0);
  const glm::dmat3 R = vendor_crystal_frame(m.vendor, q.system, q.cell);
  // Float-stored angles: c moves by at most the angle error, < 1e-6 rad.
  expect_near(crystal_to_section(m.vendor, R, m.euler(0)) * glm::dvec3(0, 0, 1), {1, 0, 0}, 1e-6, "c");
}

TEST(EbsdFrames, SectionPositionsAreCentredWithYNorth) {
  OrientationMap m;
  m.columns_odd = m.columns_even = 3;
  m.rows = 2;
  m.step_x_um = m.step_y_um = 1000.0;  // 1 mm
  m.allocate_points();
  // Extent 2 mm × 1 mm; the first point (top left on the vendor's display) is west and north.
  const glm::dvec2 first = section_position_mm(m, 0), last = section_position_mm(m, 5);
  EXPECT_DOUBLE_EQ(first.x, -1.0);
  EXPECT_DOUBLE_EQ(first.y, 0.5);
  EXPECT_DOUBLE_EQ(last.x, 1.0);
  EXPECT_DOUBLE_EQ(last.y, -0.5);
  // A hexagonal grid: the even rows' half-step shift widens the extent by half a step.
  OrientationMap h = m;
  h.grid = MapGrid::Hexagonal;
  h.columns_even = 3;
  EXPECT_DOUBLE_EQ(h.width_um(), 2500.0);
  EXPECT_DOUBLE_EQ(section_position_mm(h, 3).x, -0.75);  // 0.5 mm − 2.5 mm / 2
}

}  // namespace
}  // namespace pmsim
