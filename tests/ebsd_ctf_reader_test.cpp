// The Channel 5 .ctf reader on files the tests write: the grid, the phase table, per-point phase
// and angles, odd headers, truncated and malformed files, a 200 000-point map.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "core/base/units.h"
#include "core/crystal/euler_angles.h"
#include "core/ebsd/ctf_reader.h"
#include "core/ebsd/map_writer.h"
#include "core/ebsd/read_orientation_map.h"
#include "tests/ebsd_test_files.h"

namespace pmsim {
namespace {

using ebsd_test::crlf;
using ebsd_test::input_error_of;
using ebsd_test::ScratchDir;

// Angles are stored as float radians: a float keeps 2⁻²⁴ relative, 4e-7 rad at 2π; 1e-6 rad
// bounds that with room for the degree → radian product.
constexpr double kAngleTol = 1e-6;

const std::string kHeader =
    "Channel Text File\n"
    "Prj\tmade-up granulite\n"
    "Author\t[Unknown]\n"
    "JobMode\tGrid\n"
    "XCells\t3\n"
    "YCells\t2\n"
    "XStep\t2.5\n"
    "YStep\t2.5\n"
    "AcqE1\t0\n"
    "AcqE2\t0\n"
    "AcqE3\t0\n"
    "Euler angles refer to Sample Coordinate system (CS0)!\tMag\t100\tCoverage\t100\tDevice\t0\tKV\t20\t"
    "TiltAngle\t70\tTiltAxis\t0\n"
    "Phases\t2\n"
    "4.913;4.913;5.405\t90.000;90.000;120.000\tQuartz\t7\t154\tQuartz (trigonal)\n"
    "4.756;10.207;5.980\t90.000;90.000;90.000\tForsterite\t3\t62\n"
    "Phase\tX\tY\tBands\tError\tEuler1\tEuler2\tEuler3\tMAD\tBC\tBS\n";  // line 16; data from line 17

const std::string kData =
    "1\t0.0000\t0.0000\t8\t0\t10.0000\t20.0000\t30.0000\t0.4\t150\t160\n"
    "2\t2.5000\t0.0000\t7\t0\t123.4000\t56.7000\t289.1000\t0.5\t140\t150\n"
    "0\t5.0000\t0.0000\t0\t3\t0.0000\t0.0000\t0.0000\t0\t20\t30\n"
    "1\t0.0000\t2.5000\t8\t0\t359.0000\t179.0000\t1.0000\t0.3\t151\t161\n"
    "1\t2.5000\t2.5000\t8\t0\t45.0000\t90.0000\t0.0000\t0.3\t152\t162\n"
    "2\t5.0000\t2.5000\t6\t0\t0.0000\t0.0000\t0.0000\t0.6\t130\t140\n";

TEST(EbsdCtfReader, ReadsGridPhasesAndPoints) {
  ScratchDir dir;
  const OrientationMap m = read_ctf(dir.file("map.ctf", kHeader + kData));
  EXPECT_EQ(m.vendor, EbsdVendor::OxfordChannel5);
  EXPECT_EQ(m.grid, MapGrid::Square);
  EXPECT_EQ(m.columns_odd, 3);
  EXPECT_EQ(m.columns_even, 3);
  EXPECT_EQ(m.rows, 2);
  EXPECT_EQ(m.step_x_um, 2.5);  // exact: the decimal "2.5" is a binary fraction
  EXPECT_EQ(m.step_y_um, 2.5);
  ASSERT_EQ(m.size(), 6u);
  EXPECT_EQ(m.points_in_file, 6u);
  EXPECT_TRUE(m.warnings.empty());

  ASSERT_EQ(m.phases.size(), 2u);
  EXPECT_EQ(m.phases[0].id, 1);
  EXPECT_EQ(m.phases[0].name, "Quartz");
  EXPECT_EQ(m.phases[0].system, CrystalSystem::Trigonal);
  EXPECT_EQ(m.phases[0].laue_group, "-3m");
  EXPECT_EQ(m.phases[0].space_group, 154);
  EXPECT_DOUBLE_EQ(m.phases[0].cell.a_A, 4.913);
  EXPECT_DOUBLE_EQ(m.phases[0].cell.c_A, 5.405);
  EXPECT_DOUBLE_EQ(m.phases[0].cell.gamma_deg, 120.0);
  EXPECT_EQ(m.phases[1].name, "Forsterite");
  EXPECT_EQ(m.phases[1].system, CrystalSystem::Orthorhombic);
  EXPECT_EQ(m.phases[1].laue_group, "mmm");
  EXPECT_DOUBLE_EQ(m.phases[1].cell.b_A, 10.207);

  const int phases[] = {1, 2, 0, 1, 1, 2};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(m.phase[i], phases[i]) << "point " << i;
  EXPECT_FALSE(m.indexed(2));
  EXPECT_EQ(m.phase_of(2), nullptr);
  EXPECT_EQ(m.phase_of(1)->name, "Forsterite");
  EXPECT_NEAR(m.phi1_rad[1], radians(123.4), kAngleTol);
  EXPECT_NEAR(m.Phi_rad[1], radians(56.7), kAngleTol);
  EXPECT_NEAR(m.phi2_rad[1], radians(289.1), kAngleTol);
  EXPECT_NEAR(m.phi1_rad[3], radians(359.0), kAngleTol);
  EXPECT_NEAR(m.Phi_rad[3], radians(179.0), kAngleTol);
  // Positions from the grid: x right, y down, µm from the first point.
  EXPECT_DOUBLE_EQ(m.x_um(2), 5.0);
  EXPECT_DOUBLE_EQ(m.y_um(2), 0.0);
  EXPECT_DOUBLE_EQ(m.x_um(4), 2.5);
  EXPECT_DOUBLE_EQ(m.y_um(4), 2.5);
  EXPECT_DOUBLE_EQ(m.width_um(), 5.0);
  EXPECT_DOUBLE_EQ(m.height_um(), 2.5);
  EXPECT_TRUE(m.quality.empty());  // not asked for
}

TEST(EbsdCtfReader, KeepsBandContrastWhenAsked) {
  ScratchDir dir;
  EbsdReadOptions o;
  o.keep_quality = true;
  const OrientationMap m = read_ctf(dir.file("map.ctf", kHeader + kData), o);
  EXPECT_EQ(m.quality_kind, MapQuality::BandContrast);
  ASSERT_EQ(m.quality.size(), 6u);
  EXPECT_EQ(m.quality[0], 150.0f);
  EXPECT_EQ(m.quality[5], 130.0f);
}

TEST(EbsdCtfReader, EulerAnglesReadBackAsTheSameRotation) {
  // A point written with known angles gives the crystal_to_sample matrix of those angles.
  ScratchDir dir;
  const OrientationMap m = read_ctf(dir.file("map.ctf", kHeader + kData));
  const glm::dmat3 want = crystal_to_sample_from_bunge({radians(123.4), radians(56.7), radians(289.1)});
  const glm::dmat3 got = crystal_to_sample_from_bunge(m.euler(1));
  // Each entry is a sum of products of sines and cosines of the angles: an angle error δ moves it
  // by at most 3δ ≤ 3e-6.
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(got[c][r], want[c][r], 3e-6) << c << "," << r;
}

TEST(EbsdCtfReader, OddHeadersLoadTheSame) {
  // CRLF line ends, trailing blanks, a byte-order mark, extra and unknown keys, no optional keys
  // (Prj, Author, JobMode, AcqE, the Euler line), a blank line, keys in another order.
  std::string odd =
      "\xEF\xBB\xBF"
      "Channel Text File  \n"
      "YCells\t2   \n"
      "XCells\t3\t\n"
      "SomeNewKey\tsome value\n"
      "\n"
      "YStep\t2.5\n"
      "XStep\t2.5 \n"
      "Phases\t2\n"
      "4.913;4.913;5.405\t90.000;90.000;120.000\tQuartz\t7\n"  // no space group: optional
      "4.756;10.207;5.980\t90.000;90.000;90.000\tForsterite\t3\t62\n"
      "Phase\tX\tY\tBands\tError\tEuler1\tEuler2\tEuler3\tMAD\tBC\tBS  \n";
  ScratchDir dir;
  const OrientationMap a = read_ctf(dir.file("a.ctf", kHeader + kData));
  const OrientationMap b = read_ctf(dir.file("b.ctf", crlf(odd + kData + "\n")));
  ASSERT_EQ(b.size(), a.size());
  EXPECT_TRUE(b.warnings.empty());
  EXPECT_EQ(b.phases[0].space_group, 0);
  EXPECT_EQ(b.phases[0].name, "Quartz");
  EXPECT_EQ(b.phases[1].name, "Forsterite");
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(b.phase[i], a.phase[i]);
    EXPECT_EQ(b.phi1_rad[i], a.phi1_rad[i]);
    EXPECT_EQ(b.Phi_rad[i], a.Phi_rad[i]);
    EXPECT_EQ(b.phi2_rad[i], a.phi2_rad[i]);
  }
}

TEST(EbsdCtfReader, ColumnsAreFoundByName) {
  // Channel 5 lets the user export fewer or reordered columns: the column line says which.
  const std::string header = kHeader.substr(0, kHeader.find("Phase\tX")) + "X\tY\tPhase\tEuler1\tEuler2\tEuler3\n";
  ScratchDir dir;
  const OrientationMap m =
      read_ctf(dir.file("m.ctf", header + "0\t0\t2\t1\t2\t3\n2.5\t0\t0\t0\t0\t0\n5\t0\t1\t4\t5\t6\n"));
  EXPECT_EQ(m.phase[0], 2);
  EXPECT_EQ(m.phase[1], 0);
  EXPECT_EQ(m.phase[2], 1);
  EXPECT_NEAR(m.phi2_rad[2], radians(6.0), kAngleTol);
  EXPECT_EQ(m.points_in_file, 3u);
}

TEST(EbsdCtfReader, TruncatedFileLoadsWhatItHoldsWithAWarning) {
  ScratchDir dir;
  const std::string held = kData.substr(0, kData.find("1\t2.5000\t2.5000"));  // 4 of 6 points
  const OrientationMap m = read_ctf(dir.file("cut.ctf", kHeader + held));
  ASSERT_EQ(m.size(), 6u);
  EXPECT_EQ(m.points_in_file, 4u);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("promises 6 points"), std::string::npos) << m.warnings[0];
  EXPECT_NE(m.warnings[0].find("holds 4"), std::string::npos) << m.warnings[0];
  EXPECT_EQ(m.phase[3], 1);
  EXPECT_EQ(m.phase[4], 0);
  EXPECT_EQ(m.phase[5], 0);
}

struct Malformed {
  const char* what;
  std::string text;
  std::string key;  // InputError::key
};

TEST(EbsdCtfReader, MalformedFilesNameFileLineAndField) {
  const std::string head = kHeader;
  auto replace = [](std::string s, const std::string& from, const std::string& to) {
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  const Malformed cases[] = {
      {"bad number", head + replace(kData, "123.4000", "12x.4"), "line 18: Euler1"},
      {"bad phase", head + replace(kData, "2\t5.0000\t2.5000", "3\t5.0000\t2.5000"), "line 22: Phase"},
      {"short line", head + replace(kData, "\t0.5\t140\t150\n", "\n"), "line 18: column count"},
      {"long line", head + replace(kData, "\t0.5\t140\t150\n", "\t0.5\t140\t150\t7\n"), "line 18: column count"},
      {"too many points", head + kData + kData.substr(0, kData.find('\n') + 1), "line 23: data"},
      {"bad XCells", replace(head, "XCells\t3", "XCells\tthree"), "line 5: XCells"},
      {"zero XStep", replace(head, "XStep\t2.5", "XStep\t0"), "line 7: XStep"},
      {"missing YStep", replace(head, "YStep\t2.5\n", ""), "YStep"},
      {"bad Laue class", replace(head, "Quartz\t7", "Quartz\t12"), "line 14: phase 1 Laue class"},
      {"bad lattice", replace(head, "4.913;4.913;5.405", "4.913;4.913"), "line 14: phase 1 lattice a;b;c"},
      {"no column line", head.substr(0, head.find("Phase\tX")), "Phase X Y … column line"},
      {"not a ctf", "Channel Test File\n" + head.substr(head.find('\n') + 1) + kData, "line 1: first line"},
  };
  ScratchDir dir;
  for (const Malformed& c : cases) {
    const std::string path = dir.file("bad.ctf", c.text);
    const InputError e = input_error_of([&] { read_ctf(path); });
    EXPECT_EQ(e.file, path) << c.what;
    EXPECT_EQ(e.key, c.key) << c.what << ": " << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << c.what;
  }
  // The offending text is shown as written.
  const std::string path = dir.file("bad.ctf", head + replace(kData, "123.4000", "12x.4"));
  EXPECT_EQ(input_error_of([&] { read_ctf(path); }).value, "12x.4");
  EXPECT_EQ(input_error_of([&] { read_ctf(dir / "absent.ctf"); }).file, dir / "absent.ctf");
}

TEST(EbsdCtfReader, LargeMapLoads) {
  // 200 000 points (500 × 400), two phases, every 7th point non-indexed, written by the map writer.
  OrientationMap m;
  m.columns_odd = m.columns_even = 500;
  m.rows = 400;
  m.step_x_um = m.step_y_um = 1.5;
  m.phases = {EbsdPhase{1, "Quartz", "", UnitCell{4.913, 4.913, 5.405, 90, 90, 120}, CrystalSystem::Trigonal, "-3m", "7", 154},
              EbsdPhase{2, "Calcite", "", UnitCell{4.99, 4.99, 17.06, 90, 90, 120}, CrystalSystem::Trigonal, "-3m", "7", 167}};
  m.allocate_points();
  for (std::size_t i = 0; i < m.size(); ++i) {
    m.phase[i] = i % 7 == 0 ? 0 : static_cast<std::uint8_t>(1 + (i / 500) % 2);
    m.phi1_rad[i] = static_cast<float>((i % 628) * 0.01);
    m.Phi_rad[i] = static_cast<float>((i % 314) * 0.01);
    m.phi2_rad[i] = static_cast<float>((i % 600) * 0.01);
  }
  ScratchDir dir;
  write_ctf(m, dir / "large.ctf");
  const OrientationMap r = read_orientation_map(dir / "large.ctf");
  ASSERT_EQ(r.size(), 200000u);
  EXPECT_EQ(r.points_in_file, 200000u);
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (r.phase[i] != m.phase[i]) ++mismatches;
    // Written in degrees with float's shortest round-trip digits, read back, converted: within
    // the float tolerance above.
    if (m.phase[i] != 0 && std::abs(r.phi2_rad[i] - m.phi2_rad[i]) > kAngleTol) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0u);
}

}  // namespace
}  // namespace pmsim
