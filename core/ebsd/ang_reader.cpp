#include "core/ebsd/ang_reader.h"

#include <cmath>
#include <optional>

#include "core/base/units.h"
#include "core/ebsd/grid_position_check.h"
#include "core/ebsd/laue_group.h"
#include "core/ebsd/map_text.h"
#include "core/ebsd/point_count.h"

namespace pmsim {

namespace {

// OIM writes 4π (12.566…) for the angles of a point it did not index; a real Bunge angle is at
// most 2π. The threshold sits between the two with room for rounding of the written digits.
constexpr double kNonIndexedEuler = 3.0 * kPi;

struct PhaseDraft {
  EbsdPhase phase;
  int file_id = 0;  // the number after "# Phase"
  bool has_name = false, has_symmetry = false, has_lattice = false;
  std::size_t line = 0;
};

void finish_phase(const MapText& t, const PhaseDraft& d) {
  const std::string label = "phase " + std::to_string(d.file_id);
  const char* missing = !d.has_name       ? "MaterialName"
                        : !d.has_symmetry ? "Symmetry"
                        : !d.has_lattice  ? "LatticeConstants"
                                          : nullptr;
  if (missing)
    throw InputError(t.path(), "line " + std::to_string(d.line) + ": " + label + " " + missing, "",
                     std::string("the phase block that starts here has no '# ") + missing + "' line");
}

// The phase block a phase key belongs to.
PhaseDraft& current_phase(const MapText& t, std::vector<PhaseDraft>& drafts) {
  // A MaterialName before any "# Phase" line starts phase 1 (files of old OIM versions).
  if (drafts.empty()) {
    drafts.push_back({});
    drafts.back().file_id = 1;
    drafts.back().line = t.line_number();
  }
  return drafts.back();
}

// "# LatticeConstants a b c alpha beta gamma" (Å, degrees).
UnitCell read_lattice_constants(const MapText& t, std::string_view value) {
  std::string_view r = value;
  double v[6];
  for (double& x : v) {
    const std::string_view f = next_field(r);
    if (f.empty()) t.fail("LatticeConstants", value, "expected six numbers a b c alpha beta gamma");
    x = t.to_double(f, "LatticeConstants");
  }
  if (!next_field(r).empty()) t.fail("LatticeConstants", value, "expected six numbers a b c alpha beta gamma");
  for (int k = 0; k < 3; ++k)
    if (!(v[k] > 0.0)) t.fail("LatticeConstants", value, "lattice lengths must be > 0 Å");
  for (int k = 3; k < 6; ++k)
    if (!(v[k] > 0.0 && v[k] < 180.0)) t.fail("LatticeConstants", value, "angles must be in (0, 180)°");
  return UnitCell{v[0], v[1], v[2], v[3], v[4], v[5]};
}

// One phase block's header line ("# Phase", "# MaterialName", "# Formula", "# Symmetry",
// "# LatticeConstants"); false for a key that is not a phase's.
bool read_phase_line(const MapText& t, std::string_view key, std::string_view value, std::vector<PhaseDraft>& drafts) {
  if (key == "Phase") {
    // "# Phase 1" starts a block; "# Phase index: …" (OIM's notes) does not.
    long id = 0;
    if (!parse_number(value, id)) return true;
    if (id < 1 || id > 255) t.fail("Phase", value, "phase numbers must be in 1…255");
    if (!drafts.empty()) finish_phase(t, drafts.back());
    drafts.push_back({});
    drafts.back().file_id = static_cast<int>(id);
    drafts.back().line = t.line_number();
  } else if (key == "MaterialName") {
    PhaseDraft& d = current_phase(t, drafts);
    d.phase.name = std::string(value);
    d.has_name = !value.empty();
  } else if (key == "Formula") {
    current_phase(t, drafts).phase.formula = std::string(value);
  } else if (key == "Symmetry") {
    PhaseDraft& d = current_phase(t, drafts);
    const auto lc = laue_class_from_ang(value);
    if (!lc)
      t.fail("Symmetry", value, "not an EDAX symmetry code (1, 2, 20, 21, 22, 3, 32, 4, 42, 6, 62, 23, 43)");
    d.phase.laue_group = lc->symbol;
    d.phase.system = lc->system;
    d.phase.vendor_symmetry = std::string(value);
    d.has_symmetry = true;
  } else if (key == "LatticeConstants") {
    PhaseDraft& d = current_phase(t, drafts);
    d.phase.cell = read_lattice_constants(t, value);
    d.has_lattice = true;
  } else {
    return false;
  }
  return true;
}

// The header's grid: its kind, steps and the points per row and rows.
struct AngGrid {
  std::optional<double> xstep, ystep;
  std::optional<long> ncols_odd, ncols_even, nrows;
  std::optional<std::string> grid;
};

void read_grid_line(const MapText& t, std::string_view key, std::string_view value, AngGrid& g) {
  if (key == "GRID") {
    if (value != "SqrGrid" && value != "HexGrid") t.fail("GRID", value, "expected SqrGrid or HexGrid");
    g.grid = std::string(value);
  } else if (key == "XSTEP") {
    g.xstep = t.to_double(value, "XSTEP");
    if (!(*g.xstep > 0.0)) t.fail("XSTEP", value, "must be > 0 µm");
  } else if (key == "YSTEP") {
    g.ystep = t.to_double(value, "YSTEP");
    if (!(*g.ystep > 0.0)) t.fail("YSTEP", value, "must be > 0 µm");
  } else if (key == "NCOLS_ODD") {
    g.ncols_odd = t.to_integer(value, "NCOLS_ODD");
    if (*g.ncols_odd < 1) t.fail("NCOLS_ODD", value, "must be ≥ 1");
  } else if (key == "NCOLS_EVEN") {
    g.ncols_even = t.to_integer(value, "NCOLS_EVEN");
    if (*g.ncols_even < 0) t.fail("NCOLS_EVEN", value, "must be ≥ 0");
  } else if (key == "NROWS") {
    g.nrows = t.to_integer(value, "NROWS");
    if (*g.nrows < 1) t.fail("NROWS", value, "must be ≥ 1");
  }
  // Every other key (Info, NumberFamilies, hklFamilies, ElasticConstants, Categories, the
  // pattern-centre and operator lines, …) says nothing the map needs.
}

// The "#" lines up to the first data line, which it returns ("" for a file of header only).
std::string_view read_header(MapText& t, AngGrid& g, std::vector<PhaseDraft>& drafts) {
  std::string_view line;
  while (t.next_line(line)) {
    std::string_view s = trimmed(line);
    if (s.empty()) continue;
    if (s.front() != '#') return s;
    s.remove_prefix(1);
    std::string_view rest = s;
    std::string_view key = next_field(rest);
    const std::string_view value = trimmed(rest);
    if (!key.empty() && key.back() == ':') key.remove_suffix(1);
    if (!read_phase_line(t, key, value, drafts)) read_grid_line(t, key, value, g);
  }
  return {};
}

// The header's promises, checked against each other, into m's grid.
void apply_grid(const MapText& t, const std::string& path, const AngGrid& g, OrientationMap& m) {
  if (!g.xstep) t.fail_header("XSTEP", "missing required header key");
  if (!g.ystep) t.fail_header("YSTEP", "missing required header key");
  if (!g.ncols_odd) t.fail_header("NCOLS_ODD", "missing required header key");
  if (!g.ncols_even) t.fail_header("NCOLS_EVEN", "missing required header key");
  if (!g.nrows) t.fail_header("NROWS", "missing required header key");
  m.grid = (g.grid && *g.grid == "HexGrid") ? MapGrid::Hexagonal : MapGrid::Square;
  if (!g.grid) m.warnings.push_back(path + ": no '# GRID:' line; read as SqrGrid");
  if (m.grid == MapGrid::Square && *g.ncols_even != *g.ncols_odd)
    t.fail_header("NCOLS_EVEN", "a SqrGrid has NCOLS_EVEN = NCOLS_ODD (" + std::to_string(*g.ncols_odd) +
                                    "), the file says " + std::to_string(*g.ncols_even));
  if (m.grid == MapGrid::Hexagonal && *g.nrows > 1 && *g.ncols_even < 1)
    t.fail_header("NCOLS_EVEN", "a HexGrid of several rows needs NCOLS_EVEN ≥ 1");
  const double promised = static_cast<double>(*g.nrows / 2) * static_cast<double>(*g.ncols_odd + *g.ncols_even) +
                          static_cast<double>(*g.nrows % 2) * static_cast<double>(*g.ncols_odd);
  check_point_count(t, promised);
  m.columns_odd = static_cast<int>(*g.ncols_odd);
  m.columns_even = static_cast<int>(*g.ncols_even);
  m.rows = static_cast<int>(*g.nrows);
  m.step_x_um = *g.xstep;
  m.step_y_um = *g.ystep;
}

// Phase numbers in the data → OrientationMap ids (header order), in id_of_file_id[256]; a file
// of one phase also maps 0 to it.
void number_phases(const std::string& path, std::vector<PhaseDraft>& drafts, OrientationMap& m,
                   int (&id_of_file_id)[256]) {
  for (std::size_t k = 0; k < drafts.size(); ++k) {
    const int fid = drafts[k].file_id;
    if (id_of_file_id[fid] != 0)
      throw InputError(path, "line " + std::to_string(drafts[k].line) + ": Phase", std::to_string(fid),
                       "the header describes phase " + std::to_string(fid) + " twice");
    drafts[k].phase.id = static_cast<int>(k) + 1;
    id_of_file_id[fid] = drafts[k].phase.id;
    m.phases.push_back(drafts[k].phase);
  }
  if (m.phases.size() == 1) id_of_file_id[0] = 1;
}

// The data lines: phi1 PHI phi2 x y IQ CI [phase …], one point each, in the grid's order.
struct AngRows {
  MapText& t;
  OrientationMap& m;
  const int (&id_of_file_id)[256];
  bool single_phase;
  int ncols = 0;  // the first data line's, which every other must have
  double v[32] = {};  // the line's numbers

  // Parses one line's numbers into v and checks its column count; returns the phase column's
  // token ("" without one).
  std::string_view read_fields(std::string_view line) {
    static const char* const kField[] = {"phi1", "PHI", "phi2", "x", "y", "IQ", "CI", "phase"};
    std::string_view rest = line;
    std::string_view f = next_field(rest);
    int k = 0;
    std::string_view phase_token;
    for (; !f.empty(); f = next_field(rest), ++k) {
      if (k >= 32 || (ncols > 0 && k >= ncols))
        t.fail("column count", line, "more columns than the first data line's " + std::to_string(ncols));
      if (!parse_number(f, v[k]) || !std::isfinite(v[k]))
        t.fail(k < 8 ? kField[k] : "column " + std::to_string(k + 1), f, "not a number");
      if (k == 7) phase_token = f;
    }
    if (ncols == 0) {
      if (k < 7) t.fail("column count", line, "an .ang data line has at least 7 columns (phi1 PHI phi2 x y IQ CI)");
      if (k == 7 && !single_phase)
        t.fail("column count", line, "7 columns (no phase column) in a file of several phases");
      ncols = k;
    } else if (k != ncols) {
      t.fail("column count", line, std::to_string(k) + " columns where the first data line has " + std::to_string(ncols));
    }
    return phase_token;
  }

  // The point's OrientationMap phase id (0: non-indexed) from v.
  int phase_id(std::string_view phase_token) const {
    int id = 1;
    if (ncols >= 8) {
      const double p = v[7];
      if (p != std::floor(p) || p < 0.0 || p > 255.0 || id_of_file_id[static_cast<int>(p)] == 0) {
        if (!(p == 0.0 && !single_phase))
          t.fail("phase", phase_token, "not a phase of the header (0 = non-indexed in a file of several phases)");
      }
      id = (p == 0.0 && !single_phase) ? 0 : id_of_file_id[static_cast<int>(p)];
    }
    const bool sentinel = v[0] > kNonIndexedEuler || v[1] > kNonIndexedEuler || v[2] > kNonIndexedEuler;
    if (v[6] == -1.0 || sentinel) id = 0;
    return id;
  }

  void read(std::string_view first_data) {
    const std::size_t n = m.size();
    std::size_t i = 0;
    PositionCheck positions;
    std::string_view line = first_data;
    bool have = !first_data.empty();
    while (have) {
      std::string_view rest = line;
      if (!next_field(rest).empty()) {
        if (i == n) t.fail("data", line, "more points than the header's grid holds (" + std::to_string(n) + ")");
        const int id = phase_id(read_fields(line));
        if (i == 0) {
          m.origin_x_um = v[3];
          m.origin_y_um = v[4];
        }
        positions.check(m, i, v[3], v[4], t.line_number());
        m.phase[i] = static_cast<std::uint8_t>(id);
        if (id != 0) {
          m.phi1_rad[i] = static_cast<float>(v[0]);
          m.Phi_rad[i] = static_cast<float>(v[1]);
          m.phi2_rad[i] = static_cast<float>(v[2]);
        }
        if (m.quality_kind != MapQuality::None) m.quality[i] = static_cast<float>(v[6]);
        ++i;
      }
      have = t.next_line(line);
    }
    positions.report(m);
    finish_point_count(m, i, "NROWS rows of NCOLS_ODD/NCOLS_EVEN points");
  }
};

}  // namespace

OrientationMap read_ang(const std::string& path, const EbsdReadOptions& options) {
  MapText t(path);
  OrientationMap m;
  m.file = path;
  m.vendor = EbsdVendor::EdaxTsl;

  AngGrid grid;
  std::vector<PhaseDraft> drafts;
  const std::string_view first_data = read_header(t, grid, drafts);
  if (drafts.empty())
    t.fail_header("Phase", "missing: the header describes no phase (no '# Phase' or '# MaterialName')");
  finish_phase(t, drafts.back());
  apply_grid(t, path, grid, m);

  int id_of_file_id[256] = {};
  number_phases(path, drafts, m, id_of_file_id);

  if (options.keep_quality) m.quality_kind = MapQuality::ConfidenceIndex;
  m.allocate_points();
  AngRows rows{t, m, id_of_file_id, m.phases.size() == 1};
  rows.read(first_data);
  return m;
}

}  // namespace pmsim
