// The EDAX/TSL .ang reader on files the tests write: square and hexagonal grids, single- and
// multi-phase phase numbering, the non-indexed marks, odd headers, truncated and malformed files.
#include <gtest/gtest.h>

#include <cmath>

#include "core/base/units.h"
#include "core/crystal/euler_angles.h"
#include "core/ebsd/ang_reader.h"
#include "core/ebsd/map_writer.h"
#include "core/ebsd/read_orientation_map.h"
#include "tests/ebsd_test_files.h"

namespace pmsim {
namespace {

using ebsd_test::crlf;
using ebsd_test::input_error_of;
using ebsd_test::ScratchDir;

// Float storage of radians: 2⁻²⁴ relative, < 4e-7 rad below 2π.
constexpr double kAngleTol = 1e-6;

const std::string kTwoPhases =
    "# TEM_PIXperUM          1.000000\n"
    "# x-star                0.500000\n"
    "# WorkingDistance       15.000000\n"
    "#\n"
    "# Phase 1\n"
    "# MaterialName  \tQuartz\n"
    "# Formula     \tSiO2\n"
    "# Info \t\t\n"
    "# Symmetry              32\n"
    "# LatticeConstants      4.913 4.913 5.405  90.000  90.000 120.000\n"
    "# NumberFamilies        2\n"
    "# hklFamilies   \t 1  0  1 1 0.000000 1\n"
    "# hklFamilies   \t 1  1  0 1 0.000000 1\n"
    "# ElasticConstants \t0.000000 0.000000 0.000000 0.000000 0.000000 0.000000\n"
    "# Categories0 0 0 0 0 \n"
    "#\n"
    "# Phase 2\n"
    "# MaterialName  \tAugite\n"
    "# Formula     \t\n"
    "# Symmetry              20\n"
    "# LatticeConstants      9.699 8.844 5.272  90.000 105.93  90.000\n"
    "#\n"
    "# GRID: SqrGrid\n"
    "# XSTEP: 0.500000\n"
    "# YSTEP: 0.500000\n"
    "# NCOLS_ODD: 3\n"
    "# NCOLS_EVEN: 3\n"
    "# NROWS: 2\n"
    "#\n"
    "# OPERATOR: \tsomeone\n"
    "# SAMPLEID: \t\n"
    "# SCANID: \t\n"
    "#\n";  // 33 lines; data from line 34

const std::string kTwoPhaseData =
    "   0.10000   0.20000   0.30000      0.00000      0.00000 500.0  0.800  1  1000  0.70\n"
    "   2.15380   0.98960   5.04580      0.50000      0.00000 480.0  0.700  2  1000  0.80\n"
    "  12.56637  12.56637  12.56637      1.00000      0.00000   0.0 -1.000  0     0 180.0\n"
    "   6.20000   3.10000   0.00000      0.00000      0.50000 490.0  0.900  1  1000  0.60\n"
    "   1.00000   1.00000   1.00000      0.50000      0.50000 470.0  0.600  0  1000  0.60\n"
    "   0.50000   0.50000   0.50000      1.00000      0.50000 460.0 -1.000  2  1000  0.60\n";

TEST(EbsdAngReader, ReadsASquareMultiPhaseMap) {
  ScratchDir dir;
  const OrientationMap m = read_ang(dir.file("map.ang", kTwoPhases + kTwoPhaseData));
  EXPECT_EQ(m.vendor, EbsdVendor::EdaxTsl);
  EXPECT_EQ(m.grid, MapGrid::Square);
  EXPECT_EQ(m.columns_odd, 3);
  EXPECT_EQ(m.rows, 2);
  EXPECT_DOUBLE_EQ(m.step_x_um, 0.5);
  ASSERT_EQ(m.size(), 6u);
  EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
  ASSERT_EQ(m.phases.size(), 2u);
  EXPECT_EQ(m.phases[0].name, "Quartz");
  EXPECT_EQ(m.phases[0].formula, "SiO2");
  EXPECT_EQ(m.phases[0].system, CrystalSystem::Trigonal);
  EXPECT_EQ(m.phases[0].laue_group, "-3m");
  EXPECT_EQ(m.phases[0].vendor_symmetry, "32");
  EXPECT_EQ(m.phases[1].name, "Augite");
  EXPECT_EQ(m.phases[1].system, CrystalSystem::Monoclinic);
  EXPECT_DOUBLE_EQ(m.phases[1].cell.beta_deg, 105.93);
  // Phase 0 in a file of two phases, CI −1 and the 4π angles are all non-indexed.
  const int phases[] = {1, 2, 0, 1, 0, 0};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(m.phase[i], phases[i]) << "point " << i;
  EXPECT_NEAR(m.phi1_rad[1], 2.1538, kAngleTol);
  EXPECT_NEAR(m.Phi_rad[1], 0.9896, kAngleTol);
  EXPECT_NEAR(m.phi2_rad[1], 5.0458, kAngleTol);
  EXPECT_NEAR(m.phi1_rad[3], 6.2, kAngleTol);
}

TEST(EbsdAngReader, EulerAnglesReadBackAsTheSameRotation) {
  ScratchDir dir;
  const OrientationMap m = read_ang(dir.file("map.ang", kTwoPhases + kTwoPhaseData));
  const glm::dmat3 want = crystal_to_sample_from_bunge({2.1538, 0.9896, 5.0458});
  const glm::dmat3 got = crystal_to_sample_from_bunge(m.euler(1));
  // An angle error δ ≤ 1e-6 moves each entry (products of sines and cosines) by ≤ 3δ.
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(got[c][r], want[c][r], 3e-6);
}

const std::string kOnePhaseHex =
    "# Phase 1\n"
    "# MaterialName  \tForsterite\n"
    "# Symmetry              22\n"
    "# LatticeConstants      4.756 10.207 5.980  90.000  90.000  90.000\n"
    "# GRID: HexGrid\n"
    "# XSTEP: 2.000000\n"
    "# YSTEP: 1.732051\n"
    "# NCOLS_ODD: 3\n"
    "# NCOLS_EVEN: 2\n"
    "# NROWS: 3\n";

TEST(EbsdAngReader, HexGridRowsAlternateAndShiftByHalfAStep) {
  // Single phase: the phase column's 0 (OIM's single-phase numbering) and 1 are phase 1.
  const std::string data =
      "0.1 0.2 0.3 0.000 0.000000 100 0.5 0\n"
      "0.1 0.2 0.3 2.000 0.000000 100 0.5 0\n"
      "0.1 0.2 0.3 4.000 0.000000 100 0.5 1\n"
      "0.1 0.2 0.3 1.000 1.732051 100 0.5 0\n"
      "0.1 0.2 0.3 3.000 1.732051 100 -1 0\n"
      "0.1 0.2 0.3 0.000 3.464102 100 0.5 0\n"
      "0.1 0.2 0.3 2.000 3.464102 100 0.5 0\n"
      "0.1 0.2 0.3 4.000 3.464102 100 0.5 0\n";
  ScratchDir dir;
  const OrientationMap m = read_ang(dir.file("hex.ang", kOnePhaseHex + data));
  EXPECT_EQ(m.grid, MapGrid::Hexagonal);
  EXPECT_EQ(m.columns_odd, 3);
  EXPECT_EQ(m.columns_even, 2);
  ASSERT_EQ(m.size(), 8u);
  EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();  // the written x, y agree with the grid
  const double x[] = {0, 2, 4, 1, 3, 0, 2, 4};
  const double y[] = {0, 0, 0, 1.732051, 1.732051, 3.464102, 3.464102, 3.464102};
  const int row[] = {0, 0, 0, 1, 1, 2, 2, 2};
  for (std::size_t i = 0; i < 8; ++i) {
    EXPECT_EQ(m.row_of(i), row[i]) << i;
    EXPECT_NEAR(m.x_um(i), x[i], 1e-12) << i;  // sums of exact binary steps and halves
    EXPECT_NEAR(m.y_um(i), y[i], 1e-12) << i;  // row × the header's step
  }
  EXPECT_EQ(m.row_start(1), 3u);
  EXPECT_EQ(m.row_start(2), 5u);
  EXPECT_DOUBLE_EQ(m.width_um(), 4.0);
  const int phases[] = {1, 1, 1, 1, 0, 1, 1, 1};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(m.phase[i], phases[i]) << i;
}

TEST(EbsdAngReader, GridMismatchIsReportedOnce) {
  // A row deleted in the middle of the file: the points after it sit one row off.
  const std::string data =
      "0.1 0.2 0.3 0.000 0.000000 100 0.5 0\n"
      "0.1 0.2 0.3 2.000 0.000000 100 0.5 0\n"
      "0.1 0.2 0.3 4.000 0.000000 100 0.5 0\n"
      "0.1 0.2 0.3 0.000 3.464102 100 0.5 0\n"
      "0.1 0.2 0.3 2.000 3.464102 100 0.5 0\n";
  ScratchDir dir;
  const OrientationMap m = read_ang(dir.file("hex.ang", kOnePhaseHex + data));
  ASSERT_EQ(m.warnings.size(), 2u);  // the position, then the point count
  EXPECT_NE(m.warnings[0].find("line 14"), std::string::npos) << m.warnings[0];
  EXPECT_NE(m.warnings[1].find("holds 5"), std::string::npos) << m.warnings[1];
}

TEST(EbsdAngReader, OddHeadersLoadTheSame) {
  // CRLF, trailing blanks, no GRID line (SqrGrid, with a warning), no Formula/Info/families, the
  // phase block without "# Phase" (old OIM files), tabs between values, an extra data column.
  const std::string header =
      "# MaterialName \tQuartz   \n"
      "# Symmetry\t32\n"
      "# LatticeConstants\t4.913\t4.913\t5.405\t90\t90\t120  \n"
      "# XSTEP: 0.5\n"
      "# YSTEP: 0.5\n"
      "# NCOLS_ODD: 2\n"
      "# NCOLS_EVEN: 2\n"
      "# NROWS: 1\n"
      "# SomeFutureKey: 12\n";
  const std::string data =
      "0.1\t0.2\t0.3\t0.0\t0.0\t100\t0.5\t0\t1000\t0.7\t42\n"
      "0.4 0.5 0.6   0.5 0.0 100 0.5 0 1000 0.7 42   \n";
  ScratchDir dir;
  const OrientationMap m = read_ang(dir.file("odd.ang", crlf(header + data)));
  ASSERT_EQ(m.size(), 2u);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("SqrGrid"), std::string::npos);
  EXPECT_EQ(m.phases[0].name, "Quartz");
  EXPECT_EQ(m.phases[0].formula, "");
  EXPECT_EQ(m.phase[0], 1);
  EXPECT_NEAR(m.phi2_rad[1], 0.6, kAngleTol);
}

TEST(EbsdAngReader, SevenColumnFilesAreSinglePhase) {
  // OIM version 2 files end at CI: no phase column.
  const std::string header = kOnePhaseHex.substr(0, kOnePhaseHex.find("# GRID")) +
                             "# GRID: SqrGrid\n# XSTEP: 1\n# YSTEP: 1\n# NCOLS_ODD: 2\n# NCOLS_EVEN: 2\n# NROWS: 1\n";
  ScratchDir dir;
  const OrientationMap m = read_ang(dir.file("v2.ang", header + "1 1 1 0 0 100 0.5\n2 2 2 1 0 100 -1\n"));
  EXPECT_EQ(m.phase[0], 1);
  EXPECT_EQ(m.phase[1], 0);
}

TEST(EbsdAngReader, TruncatedFileLoadsWhatItHoldsWithAWarning) {
  ScratchDir dir;
  const std::string held = kTwoPhaseData.substr(0, kTwoPhaseData.find("   6.20000"));  // 3 of 6
  const OrientationMap m = read_ang(dir.file("cut.ang", kTwoPhases + held));
  ASSERT_EQ(m.size(), 6u);
  EXPECT_EQ(m.points_in_file, 3u);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("promises 6 points"), std::string::npos) << m.warnings[0];
  EXPECT_NE(m.warnings[0].find("holds 3"), std::string::npos) << m.warnings[0];
  for (int i = 3; i < 6; ++i) EXPECT_EQ(m.phase[i], 0);
}

TEST(EbsdAngReader, MalformedFilesNameFileLineAndField) {
  auto replace = [](std::string s, const std::string& from, const std::string& to) {
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  const std::string& h = kTwoPhases;
  const std::string& d = kTwoPhaseData;
  const struct {
    const char* what;
    std::string text, key;
  } cases[] = {
      {"bad number", h + replace(d, "2.15380", "2.1538O"), "line 35: phi1"},
      {"bad CI", h + replace(d, "0.700", "0,700"), "line 35: CI"},
      {"short line", h + replace(d, "1000  0.80\n", "\n"), "line 35: column count"},
      {"too few columns", h + "0.1 0.2 0.3 0 0 500\n", "line 34: column count"},
      {"unknown phase", h + replace(d, "0.700  2", "0.700  3"), "line 35: phase"},
      {"too many points", h + d + d.substr(0, d.find('\n') + 1), "line 40: data"},
      {"bad symmetry", replace(h, "Symmetry              32", "Symmetry              99"), "line 9: Symmetry"},
      {"bad lattice", replace(h, "4.913 4.913 5.405  90.000  90.000 120.000", "4.913 4.913 5.405"), "line 10: LatticeConstants"},
      {"bad NROWS", replace(h, "NROWS: 2", "NROWS: two"), "line 28: NROWS"},
      {"bad GRID", replace(h, "SqrGrid", "TriGrid"), "line 23: GRID"},
      {"missing NROWS", replace(h, "# NROWS: 2\n", ""), "NROWS"},
      {"missing XSTEP", replace(h, "# XSTEP: 0.500000\n", ""), "XSTEP"},
      {"square grid with uneven rows", replace(h, "NCOLS_EVEN: 3", "NCOLS_EVEN: 2"), "NCOLS_EVEN"},
      {"phase without symmetry", replace(h, "# Symmetry              20\n", ""), "line 17: phase 2 Symmetry"},
      {"no phase", "# GRID: SqrGrid\n# XSTEP: 1\n# YSTEP: 1\n# NCOLS_ODD: 1\n# NCOLS_EVEN: 1\n# NROWS: 1\n0 0 0 0 0 1 1 0\n", "Phase"},
  };
  ScratchDir dir;
  for (const auto& c : cases) {
    const std::string path = dir.file("bad.ang", c.text);
    const InputError e = input_error_of([&] { read_ang(path); });
    EXPECT_EQ(e.file, path) << c.what;
    EXPECT_EQ(e.key, c.key) << c.what << ": " << e.what();
  }
}

TEST(EbsdAngReader, WriterRoundTripOfALargeHexMap) {
  // 200 200 points on a hexagonal grid (NCOLS_ODD 501, NCOLS_EVEN 500, 400 rows), three phases.
  OrientationMap m;
  m.vendor = EbsdVendor::EdaxTsl;
  m.grid = MapGrid::Hexagonal;
  m.columns_odd = 501;
  m.columns_even = 500;
  m.rows = 400;
  m.step_x_um = 1.0;
  m.step_y_um = std::sqrt(3.0) / 2.0;
  const UnitCell cubic{5.43, 5.43, 5.43, 90, 90, 90};
  m.phases = {EbsdPhase{1, "Quartz", "SiO2", UnitCell{4.913, 4.913, 5.405, 90, 90, 120}, CrystalSystem::Trigonal, "-3m", "32", 154},
              EbsdPhase{2, "Garnet", "", cubic, CrystalSystem::Cubic, "m-3m", "43", 230},
              EbsdPhase{3, "Enstatite", "", UnitCell{18.23, 8.82, 5.18, 90, 90, 90}, CrystalSystem::Orthorhombic, "mmm", "22", 61}};
  m.allocate_points();
  for (std::size_t i = 0; i < m.size(); ++i) {
    m.phase[i] = i % 11 == 0 ? 0 : static_cast<std::uint8_t>(1 + i % 3);
    m.phi1_rad[i] = static_cast<float>((i % 628) * 0.01);
    m.Phi_rad[i] = static_cast<float>((i % 314) * 0.01);
    m.phi2_rad[i] = static_cast<float>((i % 600) * 0.01);
  }
  ScratchDir dir;
  write_ang(m, dir / "large.ang");
  const OrientationMap r = read_orientation_map(dir / "large.ang");
  ASSERT_EQ(r.size(), 200200u);  // 200 row pairs of 501 + 500
  EXPECT_EQ(r.grid, MapGrid::Hexagonal);
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  ASSERT_EQ(r.phases.size(), 3u);
  EXPECT_EQ(r.phases[1].system, CrystalSystem::Cubic);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (r.phase[i] != m.phase[i]) ++mismatches;
    // Floats written with their shortest round-trip digits read back exactly.
    if (m.phase[i] != 0 && (r.phi1_rad[i] != m.phi1_rad[i] || r.phi2_rad[i] != m.phi2_rad[i])) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0u);
}

}  // namespace
}  // namespace pmsim
