#include "core/texture/rock_growth.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "core/base/splitmix64.h"
#include "core/crystal/crystal_polyhedron.h"
#include "core/crystal/euler_angles.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/crystal/uniform_orientation.h"
#include "core/texture/grown_tiling.h"

namespace pmsim {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Random {
  std::uint64_t state;
  explicit Random(std::uint64_t seed) : state(splitmix64(seed)) {}
  double uniform() {
    state = splitmix64(state);
    return unit_interval(state);
  }
};

// What a phase's crystals share: habit template, its circumradius and volume per unit size, the
// growth rate and the CSD's moments.
struct PhaseModel {
  CrystalPolyhedron unit;
  double volume_per_size3 = 0.0;
  double rate_per_time = 1.0;  // G: size grown per unit time
  double mean_size = 0.0, mean_size3 = 0.0;
};

// Volume of the unit polyhedron: the fraction of a 24³ grid over its circumscribed cube inside it.
double unit_volume(const CrystalPolyhedron& p) {
  const int n = 24;
  const double r = p.circumradius_mm, h = 2.0 * r / n;
  int inside = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        inside += gauge(p, glm::dvec3(-r + (i + 0.5) * h, -r + (j + 0.5) * h, -r + (k + 0.5) * h)) <= 1.0;
  return inside * h * h * h;
}

// Moments of the truncated exponential n(L) ∝ exp(slope·L) on [min, max] (midpoint rule).
void csd_moments(const CsdRecipe& c, double& mean, double& mean3) {
  double w = 0.0, m1 = 0.0, m3 = 0.0;
  const int n = 400;
  for (int i = 0; i < n; ++i) {
    const double L = c.min_mm + (i + 0.5) * (c.max_mm - c.min_mm) / n, f = std::exp(c.slope_per_mm * (L - c.min_mm));
    w += f;
    m1 += f * L;
    m3 += f * L * L * L;
  }
  mean = m1 / w;
  mean3 = m3 / w;
}

// A size from n(L) by inversion, then kept with probability L / max: the length-biased sizes of
// the crystals a plane cuts.
double cut_crystal_size(const CsdRecipe& c, Random& rng) {
  const double C = -1.0 / c.slope_per_mm, span = c.max_mm - c.min_mm;
  for (;;) {
    const double u = rng.uniform();
    const double L = c.min_mm - C * std::log(1.0 - u * (1.0 - std::exp(-span / C)));
    if (rng.uniform() * c.max_mm <= L) return std::min(L, c.max_mm);
  }
}

PhaseModel phase_model(const PhaseRecipe& ph) {
  PhaseModel m;
  const MineralCrystallography* mc = find_mineral_crystallography(ph.mineral);
  m.unit = habit_template(mc, ph.aspect.value_or(default_habit_aspect(mc)));
  m.volume_per_size3 = unit_volume(m.unit);
  m.rate_per_time = ph.csd.max_mm / (1.0 - ph.nucleation);
  csd_moments(ph.csd, m.mean_size, m.mean_size3);
  return m;
}

std::vector<GrownCrystal> sample_phase(const RockRecipe& r, int k, const PhaseModel& m, double density,
                                       std::uint64_t seed) {
  const PhaseRecipe& ph = r.phases[k];
  const double R = m.unit.circumradius_mm, margin = R * ph.csd.max_mm;
  const double w = r.width_mm + 2.0 * margin, h = r.height_mm + 2.0 * margin;
  const double expected = density * w * h * 2.0 * R * m.mean_size;
  const auto count = static_cast<std::size_t>(std::llround(expected));
  const std::uint64_t phase_seed = splitmix64(seed ^ splitmix64(0xC0FFEEull + static_cast<std::uint64_t>(k)));
  Random rng(phase_seed);
  std::vector<GrownCrystal> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    GrownCrystal& c = out[i];
    c.phase = k;
    c.size_mm = cut_crystal_size(ph.csd, rng);
    c.nucleus_mm = {(rng.uniform() - 0.5) * w, (rng.uniform() - 0.5) * h, (2.0 * rng.uniform() - 1.0) * R * c.size_mm};
    c.from = 1.0 - c.size_mm / m.rate_per_time;
    c.euler_deg = uniform_euler_deg(phase_seed, i);
    c.twinned = ph.twin && rng.uniform() < ph.twin->fraction;
  }
  return out;
}

GrownTiling tiling_of(const RockRecipe& r, const std::vector<GrownCrystal>& crystals, const std::vector<PhaseModel>& models) {
  std::vector<GrainGrowth> g(crystals.size());
  for (std::size_t i = 0; i < crystals.size(); ++i) {
    const GrownCrystal& c = crystals[i];
    const auto& e = c.euler_deg;
    const glm::dmat3 L = crystal_to_sample_from_bunge({e[0] * kPi / 180.0, e[1] * kPi / 180.0, e[2] * kPi / 180.0});
    g[i] = {c.nucleus_mm, c.from, 1.0, placed(models[c.phase].unit, L, c.size_mm)};
  }
  return GrownTiling(std::move(g), !r.matrix_mineral.empty(), r.width_mm, r.height_mm);
}

// Owner counts on an nx × ny raster of point centres; the last entry counts the matrix.
std::vector<std::size_t> owner_counts(const RockRecipe& r, const GrownTiling& t, int nx, int ny) {
  std::vector<std::size_t> n(t.crystals().size() + 1, 0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const glm::dvec2 p{((i + 0.5) / nx - 0.5) * r.width_mm, ((j + 0.5) / ny - 0.5) * r.height_mm};
      const int o = t.owner(p);
      ++n[o < 0 ? t.crystals().size() : static_cast<std::size_t>(o)];
    }
  return n;
}

// Area fractions per phase (then the matrix) and their sampling errors, from raster counts.
void measure_phases(const RockRecipe& r, const std::vector<GrownCrystal>& crystals, const std::vector<std::size_t>& counts,
                    RockGrowth& out) {
  out.area_fraction.assign(r.phases.size() + 1, 0.0);
  out.sampling_error.assign(r.phases.size(), 0.0);
  double total = 0.0;
  for (const std::size_t n : counts) total += static_cast<double>(n);
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const double a = static_cast<double>(counts[i]) / total;
    out.area_fraction[i < crystals.size() ? crystals[i].phase : r.phases.size()] += a;
    if (i < crystals.size()) out.sampling_error[crystals[i].phase] += a * a;
  }
  for (double& e : out.sampling_error) e = std::sqrt(e);
}

std::string composition(const std::string& mineral, double value) {
  // "plagioclase:An55" → "plagioclase:An" + value.
  std::size_t end = mineral.size();
  while (end > 0 && (std::isdigit(static_cast<unsigned char>(mineral[end - 1])) || mineral[end - 1] == '.')) --end;
  return mineral.substr(0, end) + std::to_string(static_cast<int>(std::lround(std::clamp(value, 0.0, 100.0))));
}

// Growth zones, inner to outer by growth time: normal zoning steps from core to rim; oscillatory
// zoning alternates ± amplitude about that trend (plagioclase, Deer, Howie & Zussman 2013).
nlohmann::json zones_json(const PhaseRecipe& ph) {
  const ZoningRecipe& z = *ph.zoning;
  nlohmann::json zones = nlohmann::json::array();
  for (int b = 0; b < z.bands; ++b) {
    const double t = z.bands == 1 ? 1.0 : double(b) / (z.bands - 1);
    double v = z.core + (z.rim - z.core) * t;
    if (z.oscillatory) v += (b % 2 == 0 ? 0.5 : -0.5) * z.amplitude;
    zones.push_back({{"mineral", composition(ph.mineral, v)}, {"outer_fraction", double(b + 1) / z.bands}});
  }
  return zones;
}

}  // namespace

RockGrowth grow_rock(const RockRecipe& r, std::uint64_t seed) {
  std::vector<PhaseModel> models;
  RockGrowth out;
  for (const PhaseRecipe& ph : r.phases) {
    models.push_back(phase_model(ph));
    out.density_per_mm3.push_back(ph.mode_percent / 100.0 / (models.back().volume_per_size3 * models.back().mean_size3));
  }
  // The measuring raster: ~250 points across the longer side (6·10⁴ points: a fraction's
  // counting error is then far below kModeTolerance; the section's own sampling error is not).
  const int nx = static_cast<int>(std::ceil(250.0 * r.width_mm / std::max(r.width_mm, r.height_mm)));
  const int ny = static_cast<int>(std::ceil(250.0 * r.height_mm / std::max(r.width_mm, r.height_mm)));
  std::vector<GrownCrystal> crystals;
  for (out.rounds = 1;; ++out.rounds) {
    crystals.clear();
    for (std::size_t k = 0; k < r.phases.size(); ++k) {
      auto c = sample_phase(r, static_cast<int>(k), models[k], out.density_per_mm3[k], seed);
      crystals.insert(crystals.end(), c.begin(), c.end());
    }
    const GrownTiling t = tiling_of(r, crystals, models);
    measure_phases(r, crystals, owner_counts(r, t, nx, ny), out);
    bool done = true;
    for (std::size_t k = 0; k < r.phases.size(); ++k)
      done = done && std::abs(out.area_fraction[k] - r.phases[k].mode_percent / 100.0) <=
                         std::max(kModeTolerance, out.sampling_error[k]);
    if (done || out.rounds == 6) break;
    for (std::size_t k = 0; k < r.phases.size(); ++k) {
      const double ratio = r.phases[k].mode_percent / 100.0 / std::max(out.area_fraction[k], 1e-4);
      out.density_per_mm3[k] *= std::clamp(ratio, 0.3, 3.0);
    }
  }
  // Keep the crystals that own part of the section on a raster finer than the smallest crystal.
  double min_size = 1e300;
  for (const PhaseRecipe& ph : r.phases) min_size = std::min(min_size, ph.csd.min_mm);
  const double step = std::max(min_size / 3.0, std::max(r.width_mm, r.height_mm) / 2000.0);
  const GrownTiling t = tiling_of(r, crystals, models);
  const int fx = static_cast<int>(std::ceil(r.width_mm / step)), fy = static_cast<int>(std::ceil(r.height_mm / step));
  const auto counts = owner_counts(r, t, fx, fy);
  const double pixel_mm2 = r.width_mm * r.height_mm / (double(fx) * fy);
  for (std::size_t i = 0; i < crystals.size(); ++i) crystals[i].area_mm2 = static_cast<double>(counts[i]) * pixel_mm2;
  out.crystals = std::move(crystals);
  return out;
}

nlohmann::json rock_section_json(const RockRecipe& r, const RockGrowth& g, std::uint64_t seed) {
  nlohmann::json grains = nlohmann::json::array();
  for (const GrownCrystal& c : g.crystals) {
    if (!(c.area_mm2 > 0.0)) continue;
    const PhaseRecipe& ph = r.phases[c.phase];
    nlohmann::json j = {{"mineral", ph.mineral},
                        {"centre_mm", {c.nucleus_mm.x, c.nucleus_mm.y}},
                        {"size_mm", c.size_mm},
                        {"euler_deg", {c.euler_deg[0], c.euler_deg[1], c.euler_deg[2]}},
                        {"growth", {{"nucleus_z_mm", c.nucleus_mm.z}, {"from", c.from}, {"to", 1.0}}}};
    if (ph.aspect) j["aspect"] = *ph.aspect;
    if (ph.zoning) j["zones"] = zones_json(ph);
    if (c.twinned) j["twin"] = {{"law", ph.twin->law}, {"lamella_mm", ph.twin->lamella_mm}};
    grains.push_back(std::move(j));
  }
  if (!r.matrix_mineral.empty()) grains.push_back({{"mineral", r.matrix_mineral}, {"matrix", true}, {"euler_deg", {0.0, 0.0, 0.0}}});
  return {{"type", "section"},
          {"name", r.name},
          {"thickness_um", r.thickness_um},
          {"size_mm", {r.width_mm, r.height_mm}},
          {"source", "Grown by the texture engine (core/texture) from " + r.path + " with seed " + std::to_string(seed) +
                         ". " + r.source},
          {"grains", std::move(grains)}};
}

}  // namespace pmsim
