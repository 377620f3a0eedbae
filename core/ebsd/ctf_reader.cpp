#include "core/ebsd/ctf_reader.h"

#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "core/base/units.h"
#include "core/ebsd/grid_position_check.h"
#include "core/ebsd/laue_group.h"
#include "core/ebsd/map_text.h"
#include "core/ebsd/point_count.h"

namespace pmsim {

namespace {

// "a;b;c" → three numbers (a decimal comma, written by Channel 5 under some locales, is read as
// a point, as MTEX does).
std::array<double, 3> three_numbers(const MapText& t, std::string_view field, std::string_view name) {
  std::array<double, 3> v{};
  std::string_view rest = field;
  for (int k = 0; k < 3; ++k) {
    const std::size_t semi = rest.find(';');
    if ((semi == std::string_view::npos) != (k == 2))
      t.fail(name, field, "expected three numbers separated by ';'");
    std::string token(trimmed(rest.substr(0, semi)));
    for (char& c : token)
      if (c == ',') c = '.';
    v[k] = t.to_double(token, name);
    rest.remove_prefix(semi == std::string_view::npos ? rest.size() : semi + 1);
  }
  return v;
}

EbsdPhase read_phase_line(const MapText& t, std::string_view line, int id) {
  std::string_view rest = line;
  const std::string_view lengths = next_tab_field(rest), angles = next_tab_field(rest);
  const std::string_view name = next_tab_field(rest), laue = next_tab_field(rest);
  const std::string_view space_group = next_tab_field(rest);
  const std::string label = "phase " + std::to_string(id);
  if (laue.empty()) t.fail(label, line, "a phase line needs a;b;c, α;β;γ, the name and the Laue class number");
  EbsdPhase p;
  p.id = id;
  const auto abc = three_numbers(t, lengths, label + " lattice a;b;c");
  const auto ang = three_numbers(t, angles, label + " lattice alpha;beta;gamma");
  p.cell = UnitCell{abc[0], abc[1], abc[2], ang[0], ang[1], ang[2]};
  for (double l : abc)
    if (!(l > 0.0)) t.fail(label + " lattice a;b;c", lengths, "lattice lengths must be > 0 Å");
  for (double a : ang)
    if (!(a > 0.0 && a < 180.0)) t.fail(label + " lattice alpha;beta;gamma", angles, "angles must be in (0, 180)°");
  p.name = std::string(name);
  if (p.name.empty()) t.fail(label + " name", line, "the phase has no name");
  const long laue_number = t.to_integer(laue, label + " Laue class");
  const auto lc = laue_class_from_ctf(laue_number);
  if (!lc) t.fail(label + " Laue class", laue, "Channel 5 Laue class numbers are 1…11");
  p.laue_group = lc->symbol;
  p.system = lc->system;
  p.vendor_symmetry = std::string(laue);
  if (!space_group.empty()) {
    long sg = 0;
    // Some writers leave the field empty or put text there; only a valid number is kept.
    if (parse_number(space_group, sg) && sg >= 1 && sg <= 230) p.space_group = static_cast<int>(sg);
  }
  return p;
}

bool has_field(std::string_view line, std::string_view name) {
  for (std::string_view f = next_field(line); !f.empty(); f = next_field(line))
    if (f == name) return true;
  return false;
}

struct Columns {
  int count = 0;
  int phase = -1, x = -1, y = -1, e1 = -1, e2 = -1, e3 = -1, bc = -1;
};

Columns read_column_line(const MapText& t, std::string_view line) {
  Columns c;
  std::string_view rest = line;
  for (std::string_view f = next_field(rest); !f.empty(); f = next_field(rest), ++c.count) {
    if (f == "Phase") c.phase = c.count;
    else if (f == "X") c.x = c.count;
    else if (f == "Y") c.y = c.count;
    else if (f == "Euler1") c.e1 = c.count;
    else if (f == "Euler2") c.e2 = c.count;
    else if (f == "Euler3") c.e3 = c.count;
    else if (f == "BC") c.bc = c.count;
  }
  const std::pair<int, const char*> need[] = {{c.phase, "Phase"}, {c.x, "X"},        {c.y, "Y"},
                                              {c.e1, "Euler1"},   {c.e2, "Euler2"}, {c.e3, "Euler3"}};
  for (const auto& [col, name] : need)
    if (col < 0) t.fail("column names", line, std::string("the column line has no '") + name + "' column");
  return c;
}

}  // namespace

OrientationMap read_ctf(const std::string& path, const EbsdReadOptions& options) {
  MapText t(path);
  OrientationMap m;
  m.file = path;
  m.vendor = EbsdVendor::OxfordChannel5;
  m.grid = MapGrid::Square;

  std::string_view line;
  if (!t.next_line(line) || line.substr(0, 17) != "Channel Text File")
    t.fail("first line", line, "a Channel 5 .ctf file starts with 'Channel Text File'");

  std::optional<long> xcells, ycells;
  std::optional<double> xstep, ystep;
  bool have_phases = false;
  Columns cols;
  bool have_columns = false;
  while (t.next_line(line)) {
    if (trimmed(line).empty()) continue;
    std::string_view rest = line;
    const std::string_view key = next_tab_field(rest);
    const std::string_view value = next_tab_field(rest);
    // The column line ends the header: it starts with "Phase" as Channel 5 writes it, or, in an
    // export with columns reordered, names the Euler1 column.
    if (key == "Phase" || has_field(line, "Euler1")) {
      cols = read_column_line(t, line);
      have_columns = true;
      break;
    }
    if (key == "XCells") xcells = t.to_integer(value, "XCells");
    else if (key == "YCells") ycells = t.to_integer(value, "YCells");
    else if (key == "XStep") xstep = t.to_double(value, "XStep");
    else if (key == "YStep") ystep = t.to_double(value, "YStep");
    else if (key == "Phases") {
      const long n = t.to_integer(value, "Phases");
      if (n < 1 || n > 255) t.fail("Phases", value, "the number of phases must be in 1…255");
      for (long k = 1; k <= n; ++k) {
        std::string_view pl;
        if (!t.next_line(pl)) t.fail("phase " + std::to_string(k), "", "the file ends inside the phase table");
        m.phases.push_back(read_phase_line(t, pl, static_cast<int>(k)));
      }
      have_phases = true;
    }
    // Every other key (Prj, Author, JobMode, AcqE1…3, Mag, KV, …) says nothing the map needs.
    if (key == "XCells" && *xcells < 1) t.fail("XCells", value, "must be ≥ 1");
    if (key == "YCells" && *ycells < 1) t.fail("YCells", value, "must be ≥ 1");
    if (key == "XStep" && !(*xstep > 0.0)) t.fail("XStep", value, "must be > 0 µm");
    if (key == "YStep" && !(*ystep > 0.0)) t.fail("YStep", value, "must be > 0 µm");
  }
  if (!have_columns) t.fail_header("Phase X Y … column line", "missing: the file has no column line");
  if (!xcells) t.fail_header("XCells", "missing required header key");
  if (!ycells) t.fail_header("YCells", "missing required header key");
  if (!xstep) t.fail_header("XStep", "missing required header key");
  if (!ystep) t.fail_header("YStep", "missing required header key");
  if (!have_phases) t.fail_header("Phases", "missing required header key");
  check_point_count(t, static_cast<double>(*xcells) * static_cast<double>(*ycells));

  m.columns_odd = m.columns_even = static_cast<int>(*xcells);
  m.rows = static_cast<int>(*ycells);
  m.step_x_um = *xstep;
  m.step_y_um = *ystep;
  if (options.keep_quality && cols.bc >= 0) m.quality_kind = MapQuality::BandContrast;
  m.allocate_points();

  const std::size_t n = m.size();
  const int nphases = static_cast<int>(m.phases.size());
  static const char* const kField[] = {"column 1", "column 2", "column 3", "column 4", "column 5", "column 6",
                                       "column 7", "column 8", "column 9", "column 10", "column 11"};
  std::vector<float> v(static_cast<std::size_t>(cols.count));
  std::string_view phase_token;
  std::size_t i = 0;
  PositionCheck positions;
  while (t.next_line(line)) {
    std::string_view rest = line;
    std::string_view f = next_field(rest);
    if (f.empty()) continue;  // blank lines (a trailing one is common)
    if (i == n) t.fail("data", line, "more points than XCells × YCells = " + std::to_string(n) + " in the header");
    int k = 0;
    for (; !f.empty(); f = next_field(rest), ++k) {
      if (k >= cols.count) t.fail("column count", line, "more columns than the column line names (" + std::to_string(cols.count) + ")");
      const std::string_view field = k == cols.phase ? "Phase" : k == cols.x ? "X" : k == cols.y ? "Y"
                                     : k == cols.e1 ? "Euler1" : k == cols.e2 ? "Euler2" : k == cols.e3 ? "Euler3"
                                     : (k < 11 ? kField[k] : "column");
      if (!parse_number(f, v[k]) || !std::isfinite(v[k])) t.fail(field, f, "not a number");
      if (k == cols.phase) phase_token = f;
    }
    if (k != cols.count)
      t.fail("column count", line, std::to_string(k) + " columns where the column line names " + std::to_string(cols.count));
    const float ph = v[cols.phase];
    if (ph != std::floor(ph) || ph < 0.0f || ph > static_cast<float>(nphases))
      t.fail("Phase", phase_token,
             "the phase must be 0 (non-indexed) or one of the header's " + std::to_string(nphases) + " phases");
    if (i == 0) {
      m.origin_x_um = v[cols.x];
      m.origin_y_um = v[cols.y];
    }
    positions.check(m, i, v[cols.x], v[cols.y], t.line_number());
    m.phase[i] = static_cast<std::uint8_t>(ph);
    if (ph != 0.0f) {
      m.phi1_rad[i] = static_cast<float>(radians(v[cols.e1]));
      m.Phi_rad[i] = static_cast<float>(radians(v[cols.e2]));
      m.phi2_rad[i] = static_cast<float>(radians(v[cols.e3]));
    }
    if (m.quality_kind != MapQuality::None) m.quality[i] = v[cols.bc];
    ++i;
  }
  positions.report(m);
  finish_point_count(m, i, "XCells × YCells");
  return m;
}

}  // namespace pmsim
