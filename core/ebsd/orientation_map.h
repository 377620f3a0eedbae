#pragma once
// An EBSD orientation map as read from a vendor file (.ctf, .ang): the grid, the phase table and,
// per point, the phase and the Bunge Euler angles exactly as the file gives them (the vendor's
// specimen and crystal frames; core/ebsd/ebsd_frames.h turns them into pmsim's).
//
// Memory stays flat for maps of millions of points: structure of arrays, one byte of phase and
// three floats of angles per point (13 bytes; float keeps 1e-7 rad, far below an EBSD
// measurement's ~0.5° precision), positions computed from the grid rather than stored, and the
// optional quality column only when asked for (EbsdReadOptions::keep_quality).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/crystal/euler_angles.h"
#include "core/crystal/lattice.h"

namespace pmsim {

enum class EbsdVendor { OxfordChannel5, EdaxTsl };
const char* ebsd_vendor_name(EbsdVendor v);  // "Oxford Instruments HKL Channel 5", "EDAX/TSL OIM"

// Square grid: every row has the same number of points, rows step_y apart. Hexagonal grid (EDAX
// "HexGrid"): rows alternate between columns_odd points (the first row, and every other) and
// columns_even points shifted right by step_x/2; rows are step_y apart (step_x·√3/2 in files the
// vendor writes).
enum class MapGrid { Square, Hexagonal };

struct EbsdPhase {
  int id = 0;                // the phase number points carry (1…N, in header order)
  std::string name;          // as the file spells it (ctf phase name, ang MaterialName)
  std::string formula;       // ang "# Formula" ("" when absent or ctf)
  UnitCell cell;             // lattice parameters, Å and degrees
  CrystalSystem system = CrystalSystem::Triclinic;
  std::string laue_group;    // Hermann–Mauguin symbol of the Laue class ("6/mmm", "m-3m")
  std::string vendor_symmetry;  // the code as written (ctf Laue number "9", ang Symmetry "62")
  int space_group = 0;       // International Tables number, 0 when the file does not give it
};

// What the file calls its quality column, kept when EbsdReadOptions::keep_quality is set.
enum class MapQuality { None, BandContrast, ConfidenceIndex };

struct OrientationMap {
  std::string file;
  EbsdVendor vendor = EbsdVendor::OxfordChannel5;
  MapGrid grid = MapGrid::Square;
  int columns_odd = 0;   // points in the first row (and every second one)
  int columns_even = 0;  // points in the second row (and every second one); = columns_odd on a square grid
  int rows = 0;
  double step_x_um = 0.0, step_y_um = 0.0;
  double origin_x_um = 0.0, origin_y_um = 0.0;  // the first point's position as the file gives it

  std::vector<EbsdPhase> phases;  // phases[k] has id k + 1

  // Per point, in file order (row by row, the first row at the top of the vendor's display).
  std::vector<std::uint8_t> phase;  // 0 = non-indexed, else an EbsdPhase::id
  std::vector<float> phi1_rad, Phi_rad, phi2_rad;  // Bunge, the vendor's frames
  MapQuality quality_kind = MapQuality::None;
  std::vector<float> quality;  // band contrast (ctf BC) or confidence index (ang CI); empty unless kept

  std::size_t points_in_file = 0;  // data lines the file held (< size() for a truncated file)
  std::vector<std::string> warnings;

  std::size_t size() const { return phase.size(); }
  int columns_in_row(int row) const { return (row % 2 == 0) ? columns_odd : columns_even; }
  std::size_t row_start(int row) const;  // index of the row's first point
  int row_of(std::size_t i) const;
  // Position of point i in the file's map frame (x right, y down, µm), the origin at the first point.
  double x_um(std::size_t i) const;
  double y_um(std::size_t i) const;
  bool indexed(std::size_t i) const { return phase[i] != 0; }
  EulerBunge euler(std::size_t i) const { return {phi1_rad[i], Phi_rad[i], phi2_rad[i]}; }
  const EbsdPhase* phase_of(std::size_t i) const {
    return phase[i] == 0 ? nullptr : &phases[phase[i] - 1];
  }
  // Extent of the grid's points (first to last point centre) in x and y, µm.
  double width_um() const;
  double height_um() const { return rows > 1 ? (rows - 1) * step_y_um : 0.0; }

  // Sizes the per-point arrays for the grid, every point non-indexed.
  void allocate_points();
};

struct EbsdReadOptions {
  bool keep_quality = false;  // fill OrientationMap::quality (4 more bytes per point)
};

}  // namespace pmsim
