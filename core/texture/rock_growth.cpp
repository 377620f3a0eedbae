#include "core/texture/rock_growth.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <string>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "core/base/input_error.h"
#include "core/base/splitmix64.h"
#include "core/crystal/axis_rotation.h"
#include "core/crystal/crystal_polyhedron.h"
#include "core/crystal/euler_angles.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/crystal/uniform_orientation.h"
#include "core/texture/foam_relaxation.h"
#include "core/texture/grain_packing.h"
#include "core/texture/grown_tiling.h"
#include "core/texture/overgrowth_cement.h"

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
  glm::dvec3 fabric_axis{0.0, 0.0, 1.0};  // crystal frame: the habit axis a fabric aligns
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

// Moments of the truncated n(L) on [min, max] (midpoint rule).
void csd_moments(const CsdRecipe& c, double& mean, double& mean3) {
  double w = 0.0, m1 = 0.0, m3 = 0.0;
  const int n = 400;
  for (int i = 0; i < n; ++i) {
    const double L = c.min_mm + (i + 0.5) * (c.max_mm - c.min_mm) / n, f = c.density(L);
    w += f;
    m1 += f * L;
    m3 += f * L * L * L;
  }
  mean = m1 / w;
  mean3 = m3 / w;
}

// A standard normal deviate (Box–Muller, the cosine branch).
double gaussian(Random& rng) {
  const double u1 = std::max(rng.uniform(), 1e-300), u2 = rng.uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

// A size from n(L) (log-linear: by inversion; log-normal: a normal φ, redrawn outside the range),
// then kept with probability L / max: the length-biased sizes of the crystals a plane cuts.
double cut_crystal_size(const CsdRecipe& c, Random& rng) {
  const double C = -1.0 / c.slope_per_mm, span = c.max_mm - c.min_mm;
  const double phi50 = -std::log2(c.median_mm);
  for (;;) {
    double L;
    if (c.law == CsdRecipe::Law::log_normal) {
      L = std::exp2(-(phi50 + c.sorting_phi * gaussian(rng)));
      if (L < c.min_mm || L > c.max_mm) continue;
    } else {
      const double u = rng.uniform();
      L = c.min_mm - C * std::log(1.0 - u * (1.0 - std::exp(-span / C)));
    }
    if (rng.uniform() * c.max_mm <= L) return std::min(L, c.max_mm);
  }
}

// Three independent standard normal deviates.
glm::dvec3 gaussian3(Random& rng) {
  glm::dvec3 g;
  for (int k = 0; k < 3; ++k) g[k] = gaussian(rng);
  return g;
}

// Turns a uniformly drawn orientation so that its fabric axis (crystal frame) lies along the
// fabric direction perturbed by a Gaussian of spread σ (the smallest rotation taking one to the
// other): the rotation about the axis stays uniform.
std::array<double, 3> aligned(const std::array<double, 3>& euler_deg, const FabricRecipe& f,
                              const glm::dvec3& axis_crystal, Random& rng) {
  const glm::dmat3 L0 = crystal_to_sample_from_bunge({euler_deg[0] * kPi / 180.0, euler_deg[1] * kPi / 180.0,
                                                      euler_deg[2] * kPi / 180.0});
  const double s = f.spread_deg * kPi / 180.0;
  glm::dvec3 target = glm::normalize(glm::dvec3(f.direction[0], f.direction[1], f.direction[2]) + s * gaussian3(rng));
  const glm::dvec3 a = glm::normalize(L0 * axis_crystal);
  if (glm::dot(a, target) < 0.0) target = -target;  // an axis, not a vector
  const glm::dmat3 Q = rotation_taking(a, target);
  const EulerBunge e = bunge_from_crystal_to_sample(Q * L0);
  return {e.phi1_rad * 180.0 / kPi, e.Phi_rad * 180.0 / kPi, e.phi2_rad * 180.0 / kPi};
}

// The habit axis a phase's fabric aligns (crystal frame): the prism axis or the plate normal.
glm::dvec3 fabric_axis(const PhaseRecipe& ph) {
  const MineralCrystallography* mc = find_mineral_crystallography(ph.mineral);
  return ph.fabric->plate_normal ? plane_normal(mc->cell, *mc->habit.tabular)
                                 : lattice_direction(mc->cell, *mc->habit.elongation);
}

PhaseModel phase_model(const PhaseRecipe& ph) {
  PhaseModel m;
  const MineralCrystallography* mc = find_mineral_crystallography(ph.mineral);
  m.unit = ph.rounded ? sphere_polyhedron(1.0) : habit_template(mc, ph.aspect.value_or(default_habit_aspect(mc)));
  m.volume_per_size3 = unit_volume(m.unit);
  m.rate_per_time = ph.csd.max_mm / (1.0 - ph.nucleation);
  csd_moments(ph.csd, m.mean_size, m.mean_size3);
  if (ph.fabric) m.fabric_axis = fabric_axis(ph);
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
    if (ph.fabric) c.euler_deg = aligned(uniform_euler_deg(phase_seed, i), *ph.fabric, m.fabric_axis, rng);
    c.twinned = ph.twin && rng.uniform() < ph.twin->fraction;
  }
  // Without a fabric the orientations draw nothing from rng: by index, in parallel (a microlite
  // population is a million of them).
  if (!ph.fabric)
    tbb::parallel_for(std::size_t(0), count, [&](std::size_t i) { out[i].euler_deg = uniform_euler_deg(phase_seed, i); });
  return out;
}

// A sand's grains touch rather than sink into one another (grain_packing.h): rounded crystals are
// packed until no two overlap by more than this fraction of their radii's sum, a contact disc of
// 0.53 r between equal balls: the long contacts of a compacted sandstone (Taylor 1950).
constexpr double kSandContactOverlap = 0.15;

void pack_rounded(const RockRecipe& r, std::vector<GrownCrystal>& crystals) {
  std::vector<std::size_t> index;
  std::vector<glm::dvec3> centres;
  std::vector<double> radii;
  double margin = 0.0;  // as sample_phase draws them: the section and R·max_mm around it (R = ½)
  for (const PhaseRecipe& ph : r.phases)
    if (ph.rounded) margin = std::max(margin, 0.5 * ph.csd.max_mm);
  for (std::size_t i = 0; i < crystals.size(); ++i)
    if (r.phases[crystals[i].phase].rounded) {
      index.push_back(i);
      centres.push_back(crystals[i].nucleus_mm);
      radii.push_back(0.5 * crystals[i].size_mm);
    }
  if (centres.empty()) return;
  const glm::dvec2 half{0.5 * r.width_mm + margin, 0.5 * r.height_mm + margin};
  pack_balls(centres, radii, -half, half, kSandContactOverlap, 300);
  for (std::size_t k = 0; k < index.size(); ++k) crystals[index[k]].nucleus_mm = centres[k];
}

glm::dmat3 crystal_frame(const GrownCrystal& c) {
  const auto& e = c.euler_deg;
  return crystal_to_sample_from_bunge({e[0] * kPi / 180.0, e[1] * kPi / 180.0, e[2] * kPi / 180.0});
}

// A granoblastic rock's grains are balls (their neighbours set their boundaries), others their
// habit polyhedra, placed from their phase's template as the tiling reads them (no copies).
GrownTiling tiling_of(const RockRecipe& r, const std::vector<GrownCrystal>& crystals, const std::vector<PhaseModel>& models) {
  static const CrystalPolyhedron unit_ball = sphere_polyhedron(1.0);  // × size: sphere_polyhedron(size), bit for bit
  return GrownTiling(
      crystals.size(),
      [&](std::size_t i) {
        const GrownCrystal& c = crystals[i];
        PlacedGrowth g;
        g.nucleus_mm = c.nucleus_mm;
        g.from = c.from;
        g.to = 1.0;
        g.unit = r.granoblastic ? &unit_ball : &models[c.phase].unit;
        if (!r.granoblastic) g.L = crystal_frame(c);
        g.size_mm = c.size_mm;
        g.overgrows = r.phases[c.phase].porphyroblast;
        return g;
      },
      !r.matrix_mineral.empty(), r.width_mm, r.height_mm);
}

// Owner counts on an nx × ny raster of point centres; the last entry counts the matrix. Rows are
// looked up in parallel into a raster of owners, then counted in order.
std::vector<std::size_t> owner_counts(const RockRecipe& r, const GrownTiling& t, int nx, int ny) {
  std::vector<int> owners(static_cast<std::size_t>(nx) * ny);
  tbb::parallel_for(0, ny, [&](int j) {
    for (int i = 0; i < nx; ++i) {
      const glm::dvec2 p{((i + 0.5) / nx - 0.5) * r.width_mm, ((j + 0.5) / ny - 0.5) * r.height_mm};
      owners[static_cast<std::size_t>(j) * nx + i] = t.owner(p);
    }
  });
  std::vector<std::size_t> n(t.size() + 1, 0);
  for (const int o : owners) ++n[o < 0 ? t.size() : static_cast<std::size_t>(o)];
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

// The raster areas are measured on: finer than a third of the smallest crystal (min_size_mm), at
// most 2000 points across the longer side; point counts across and down.
glm::ivec2 area_raster(const RockRecipe& r, double min_size_mm) {
  const double step = std::max(min_size_mm / 3.0, std::max(r.width_mm, r.height_mm) / 2000.0);
  return {static_cast<int>(std::ceil(r.width_mm / step)), static_cast<int>(std::ceil(r.height_mm / step))};
}

// Each crystal's area in the section, on the area raster.
void measure_areas(const RockRecipe& r, const GrownTiling& t, double min_size_mm, std::vector<GrownCrystal>& crystals) {
  const glm::ivec2 raster = area_raster(r, min_size_mm);
  const int fx = raster.x, fy = raster.y;
  const auto counts = owner_counts(r, t, fx, fy);
  const double pixel_mm2 = r.width_mm * r.height_mm / (double(fx) * fy);
  for (std::size_t i = 0; i < crystals.size(); ++i) crystals[i].area_mm2 = static_cast<double>(counts[i]) * pixel_mm2;
}

// A granoblastic rock: nuclei Lloyd-relaxed in a box two grains wider than the section on every
// side and two grains above and below it (the cells the section cuts lie away from the box's
// walls, where the relaxation is one-sided), each a ball of the grain size growing from time 0:
// the section is the relaxed aggregate's Voronoi cells. Phases go to the cells in a random order
// by the modes' quotas (the cells are nearly equal, so the volume fractions are the modes).
RockGrowth grow_foam(const RockRecipe& r, std::uint64_t seed) {
  const GranoblasticRecipe& f = *r.granoblastic;
  const double d = f.grain_mm, margin = 2.0 * d;
  const FoamBox box{{-0.5 * r.width_mm - margin, -0.5 * r.height_mm - margin, -margin},
                    {0.5 * r.width_mm + margin, 0.5 * r.height_mm + margin, margin}};
  const glm::dvec3 e = box.hi - box.lo;
  const double volume = e.x * e.y * e.z, cell_volume = kPi / 6.0 * d * d * d;
  const auto count = static_cast<std::size_t>(std::max(1.0, std::round(volume / cell_volume)));
  const std::vector<glm::dvec3> nuclei = relaxed_foam_nuclei(box, count, f.relax_iterations, seed);
  std::vector<std::size_t> order(count);
  Random rng(splitmix64(seed ^ 0xF0A4ull));
  for (std::size_t i = 0; i < count; ++i) order[i] = i;
  for (std::size_t i = count; i > 1; --i) std::swap(order[i - 1], order[static_cast<std::size_t>(rng.uniform() * double(i)) % i]);
  RockGrowth out;
  std::vector<GrownCrystal> crystals(count);
  std::vector<double> cumulative;
  double sum = 0.0;
  for (const PhaseRecipe& ph : r.phases) cumulative.push_back(sum += ph.mode_percent / 100.0);
  out.density_per_mm3.assign(r.phases.size(), 0.0);
  for (std::size_t q = 0; q < count; ++q) {
    GrownCrystal& c = crystals[order[q]];
    const double u = (double(q) + 0.5) / double(count) * sum;
    c.phase = static_cast<int>(std::lower_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin());
    c.phase = std::min(c.phase, static_cast<int>(r.phases.size()) - 1);
    out.density_per_mm3[c.phase] += 1.0 / volume;
  }
  for (std::size_t i = 0; i < count; ++i) {
    GrownCrystal& c = crystals[i];
    const PhaseRecipe& ph = r.phases[c.phase];
    c.nucleus_mm = nuclei[i];
    c.size_mm = d;
    c.from = 0.0;
    c.euler_deg = uniform_euler_deg(splitmix64(seed ^ 0xF0A5ull), i);
    if (ph.fabric) c.euler_deg = aligned(c.euler_deg, *ph.fabric, fabric_axis(ph), rng);
    c.twinned = ph.twin && rng.uniform() < ph.twin->fraction;
  }
  const GrownTiling t = tiling_of(r, crystals, {});
  const int nx = static_cast<int>(std::ceil(250.0 * r.width_mm / std::max(r.width_mm, r.height_mm)));
  const int ny = static_cast<int>(std::ceil(250.0 * r.height_mm / std::max(r.width_mm, r.height_mm)));
  measure_phases(r, crystals, owner_counts(r, t, nx, ny), out);
  measure_areas(r, t, d, crystals);
  out.crystals = std::move(crystals);
  return out;
}

// Draws, packs, tiles and measures the phases, scaling each density by target / measured area
// fraction until every phase is within kModeTolerance or its sampling error (at most
// kMaxCalibrationRounds); the last round's crystals and their tiling.
struct DrawnRock {
  std::vector<GrownCrystal> crystals;
  GrownTiling tiling;
};

DrawnRock calibrate(const RockRecipe& r, const std::vector<PhaseModel>& models, std::uint64_t seed, RockGrowth& out) {
  // The measuring raster: ~250 points across the longer side (6·10⁴ points: a fraction's
  // counting error is then far below kModeTolerance; the section's own sampling error is not).
  const int nx = static_cast<int>(std::ceil(250.0 * r.width_mm / std::max(r.width_mm, r.height_mm)));
  const int ny = static_cast<int>(std::ceil(250.0 * r.height_mm / std::max(r.width_mm, r.height_mm)));
  DrawnRock d;
  // Per phase: the exponent of its step (halved each time its error changes sign while still out
  // of tolerance: a phase that competes with another can respond to its own density more than
  // proportionally, and the plain ratio then overshoots back and forth), and its last error.
  std::vector<double> exponent(r.phases.size(), 1.0), last_error(r.phases.size(), 0.0);
  for (out.rounds = 1;; ++out.rounds) {
    d.crystals.clear();
    // Each phase has its own random sequence: drawn side by side, joined in phase order.
    std::vector<std::vector<GrownCrystal>> phases(r.phases.size());
    tbb::parallel_for(std::size_t(0), r.phases.size(), [&](std::size_t k) {
      phases[k] = sample_phase(r, static_cast<int>(k), models[k], out.density_per_mm3[k], seed);
    });
    for (std::vector<GrownCrystal>& c : phases) {
      d.crystals.insert(d.crystals.end(), c.begin(), c.end());
      std::vector<GrownCrystal>().swap(c);
    }
    pack_rounded(r, d.crystals);
    d.tiling = tiling_of(r, d.crystals, models);
    measure_phases(r, d.crystals, owner_counts(r, d.tiling, nx, ny), out);
    bool done = true;
    std::vector<bool> within(r.phases.size());
    for (std::size_t k = 0; k < r.phases.size(); ++k) {
      within[k] = std::abs(out.area_fraction[k] - r.phases[k].mode_percent / 100.0) <=
                  std::max(kModeTolerance, out.sampling_error[k]);
      done = done && within[k];
    }
    if (done || out.rounds == kMaxCalibrationRounds) return d;
    for (std::size_t k = 0; k < r.phases.size(); ++k) {
      const double error = r.phases[k].mode_percent / 100.0 - out.area_fraction[k];
      if (!within[k] && error * last_error[k] < 0.0) exponent[k] *= 0.5;
      last_error[k] = error;
      const double ratio = r.phases[k].mode_percent / 100.0 / std::max(out.area_fraction[k], 1e-4);
      out.density_per_mm3[k] *= std::clamp(std::pow(ratio, exponent[k]), 0.3, 3.0);
    }
  }
}

// The overgrowth scale that puts each overgrown phase's cement_percent in the section: on the
// raster measure_areas counts, the pore points' least reach over the phase's grains (those the
// section keeps), and its quantile at the cement's share of all points (overgrowth_scale_for). A
// phase is calibrated alone: two overgrown phases would share the pores both reach.
constexpr double kCalibrationScale = 2.0;  // the forms the reaches are read from: beyond any cement of a porous sand
void calibrate_cement(const RockRecipe& r, const GrownTiling& t, double min_size_mm, RockGrowth& out) {
  out.overgrowth_scale.assign(r.phases.size(), 0.0);
  out.cement_fraction.assign(r.phases.size(), 0.0);
  const glm::ivec2 raster = area_raster(r, min_size_mm);
  const int fx = raster.x, fy = raster.y;  // not a structured binding: clang 14 cannot capture one
  for (std::size_t k = 0; k < r.phases.size(); ++k) {
    const auto& og = r.phases[k].overgrowth;
    if (!og) continue;
    const CrystalPolyhedron unit = overgrowth_unit_form(*find_mineral_crystallography(r.phases[k].mineral));
    std::vector<GrainOvergrowth> grains;
    for (const GrownCrystal& c : out.crystals)
      if (c.phase == int(k) && c.area_mm2 > 0.0)
        grains.push_back({c.nucleus_mm, 0.5 * c.size_mm, kCalibrationScale,
                          overgrowth_form(unit, crystal_frame(c), 0.5 * c.size_mm, kCalibrationScale)});
    const OvergrowthCement cal(std::move(grains), r.width_mm, r.height_mm);
    std::vector<double> reach(static_cast<std::size_t>(fx) * fy, -1.0);
    tbb::parallel_for(0, fy, [&](int j) {
      for (int i = 0; i < fx; ++i) {
        const glm::dvec2 p{((i + 0.5) / fx - 0.5) * r.width_mm, ((j + 0.5) / fy - 0.5) * r.height_mm};
        if (t.owner(p) < 0) reach[static_cast<std::size_t>(j) * fx + i] = cal.least_reach(p);
      }
    });
    std::erase(reach, -1.0);
    const double cement = og->cement_percent / 100.0;
    try {
      out.overgrowth_scale[k] = overgrowth_scale_for(reach, static_cast<std::size_t>(fx) * fy, cement);
    } catch (const std::invalid_argument& e) {
      throw InputError(r.path, "phases[" + std::to_string(k) + "].overgrowth.cement_percent", std::to_string(og->cement_percent),
                       e.what());
    }
    out.cement_fraction[k] = double(std::count_if(reach.begin(), reach.end(), [&](double x) { return x <= out.overgrowth_scale[k]; })) /
                             (double(fx) * fy);
  }
}

}  // namespace

RockGrowth grow_rock(const RockRecipe& r, std::uint64_t seed) {
  if (r.granoblastic) return grow_foam(r, seed);
  std::vector<PhaseModel> models;
  RockGrowth out;
  for (const PhaseRecipe& ph : r.phases) {
    models.push_back(phase_model(ph));
    out.density_per_mm3.push_back(ph.mode_percent / 100.0 / (models.back().volume_per_size3 * models.back().mean_size3));
  }
  // The densities are intensive, so a large section takes them from a centred window of the
  // calibration area first; the whole section then starts from them and is checked as before.
  const double area = r.width_mm * r.height_mm;
  if (area > kCalibrationWindowMm2) {
    RockRecipe w = r;
    const double k = std::sqrt(kCalibrationWindowMm2 / area);
    w.width_mm *= k;
    w.height_mm *= k;
    calibrate(w, models, seed, out);
    out.window_rounds = out.rounds;
  }
  DrawnRock d = calibrate(r, models, seed, out);
  // Keep the crystals that own part of the section.
  double min_size = 1e300;
  for (const PhaseRecipe& ph : r.phases) min_size = std::min(min_size, ph.csd.min_mm);
  measure_areas(r, d.tiling, min_size, d.crystals);
  out.crystals = std::move(d.crystals);
  calibrate_cement(r, d.tiling, min_size, out);
  return out;
}

// A bent crystal's subgrains (section_map.h): a bend axis uniform on the sphere and tilt walls
// containing it (wall normal ⟂ axis, uniform about it). Walls within ~25° of the section plane
// (|n_z| > 0.9) are drawn again: they would smear across the 30 µm section rather than show as bands.
nlohmann::json subgrains_json(const UnduloseRecipe& u, Random& rng) {
  const glm::dvec3 axis = glm::normalize(gaussian3(rng));
  glm::dvec3 wall;
  do {
    const glm::dvec3 v = gaussian3(rng);
    wall = glm::normalize(v - glm::dot(v, axis) * axis);
  } while (std::abs(wall.z) > 0.9);
  return {{"width_mm", u.subgrain_mm}, {"step_deg", u.step_deg}, {"axis", {axis.x, axis.y, axis.z}},
          {"wall_normal", {wall.x, wall.y, wall.z}}};
}

// A crystal's inclusions (rock_recipe.h InclusionRecipe): the recipe's trail direction or a
// random one, the turn of this crystal's growth, and random orientations of their own.
nlohmann::json inclusions_json(const RockRecipe& r, const PhaseRecipe& ph, const GrownCrystal& c, std::uint64_t seed,
                               std::size_t written, Random& rng) {
  const InclusionRecipe& in = *ph.inclusions;
  const std::uint64_t s = splitmix64(seed ^ 0x1C1A5ull);
  const double trail = in.trail_deg ? *in.trail_deg : 180.0 * rng.uniform();
  const double turned = r.granoblastic ? 1.0 : std::min(1.0, c.size_mm / ph.csd.max_mm);
  nlohmann::json euler = nlohmann::json::array();
  for (int k = 0; k < in.orientations; ++k) {
    const auto e = uniform_euler_deg(s, written * 64 + static_cast<std::size_t>(k));
    euler.push_back({e[0], e[1], e[2]});
  }
  nlohmann::json j = {{"mineral", in.mineral},
                      {"size_mm", in.size_mm},
                      {"aspect", in.aspect},
                      {"spacing_mm", in.spacing_mm},
                      {"trail_spacing_mm", in.trail_spacing_mm},
                      {"fraction", in.fraction},
                      {"within", in.within},
                      {"trail_deg", trail},
                      {"rotation_deg", in.rotation_deg * turned},
                      {"euler_deg", std::move(euler)}};
  if (in.halo) j["halo"] = {{"radius_mm", in.halo->radius_mm}, {"darkening", in.halo->darkening}};
  if (in.habit != InclusionHabit::Trail) j["habit"] = inclusion_habit_name(in.habit);
  return j;
}

nlohmann::json rock_section_header_json(const RockRecipe& r, std::uint64_t seed) {
  return {{"type", "section"},
          {"name", r.name},
          {"thickness_um", r.thickness_um},
          {"size_mm", {r.width_mm, r.height_mm}},
          {"source", "Grown by the texture engine (core/texture) from " + r.path + " with seed " + std::to_string(seed) +
                         ". " + r.source}};
}

namespace {

constexpr std::uint64_t kGrainRandomSeed = 0x5B9A1Full;
// The myrmekite rods' orientation stream (its own, so that no other draw moves).
constexpr std::uint64_t kMyrmekiteRodsSalt = 0x3E7Full;

// The grain of crystal c, the written-th of the file; draws from rng only for the phase's
// subgrains, alteration and inclusions.
nlohmann::json grain_json(const RockRecipe& r, const GrownCrystal& c, const std::vector<double>& scales, std::uint64_t seed,
                          std::size_t written, Random& rng) {
  const PhaseRecipe& ph = r.phases[c.phase];
  nlohmann::json j = {{"mineral", ph.mineral},
                      {"centre_mm", {c.nucleus_mm.x, c.nucleus_mm.y}},
                      {"size_mm", c.size_mm},
                      {"euler_deg", {c.euler_deg[0], c.euler_deg[1], c.euler_deg[2]}},
                      {"growth", {{"nucleus_z_mm", c.nucleus_mm.z}, {"from", c.from}, {"to", 1.0}}}};
  if (r.granoblastic || ph.rounded) j["growth"]["shape"] = "sphere";
  if (ph.porphyroblast) j["growth"]["overgrows"] = true;
  if (ph.aspect) j["aspect"] = *ph.aspect;
  if (ph.zoning) j["zones"] = zones_json(ph);
  if (c.twinned) {
    j["twin"] = {{"law", ph.twin->law}, {"lamella_mm", ph.twin->lamella_mm}};
    if (!ph.twin->cross_law.empty())
      j["twin"]["cross"] = {{"law", ph.twin->cross_law}, {"lamella_mm", ph.twin->cross_lamella_mm}};
  }
  if (ph.undulose) j["subgrains"] = subgrains_json(*ph.undulose, rng);
  if (ph.alteration && rng.uniform() < ph.alteration->fraction) {
    // The secondary mineral in a random orientation of its own (it grew in the cracks), or in the
    // host's (a topotactic replacement).
    const auto e = ph.alteration->host_orientation ? c.euler_deg : uniform_euler_deg(splitmix64(seed ^ 0xA17E5ull), written);
    j["alteration"] = {{"mineral", ph.alteration->mineral}, {"vein_mm", ph.alteration->vein_mm}, {"euler_deg", {e[0], e[1], e[2]}}};
  }
  if (ph.inclusions) j["inclusions"] = inclusions_json(r, ph, c, seed, written, rng);
  if (const auto& og = ph.overgrowth) {
    j["overgrowth"] = {{"habit_scale", scales[std::size_t(c.phase)]}};
    if (const auto& d = og->dust)
      j["overgrowth"]["dust"] = {{"mineral", d->mineral}, {"size_mm", d->size_mm}, {"spacing_mm", d->spacing_mm}, {"fraction", d->fraction}};
  }
  if (const auto& m = ph.myrmekite) {
    // The rods' orientation by the grain's index, not from rng: the other draws stay as they were.
    const auto e = uniform_euler_deg(splitmix64(seed ^ kMyrmekiteRodsSalt), written);
    j["myrmekite"] = {{"host", m->host},
                      {"depth_mm", m->depth_mm},
                      {"bulb_mm", m->bulb_mm},
                      {"fraction", m->fraction},
                      {"quartz",
                       {{"mineral", m->quartz_mineral},
                        {"width_mm", m->rod_width_mm},
                        {"spacing_mm", m->rod_spacing_mm},
                        {"euler_deg", {e[0], e[1], e[2]}}}}};
  }
  return j;
}

}  // namespace

RockGrainsJson::RockGrainsJson(const RockRecipe& r, const RockGrowth& g, std::uint64_t seed)
    : recipe_(r), growth_(g), seed_(seed) {
  Random rng(splitmix64(seed ^ kGrainRandomSeed));
  for (std::size_t i = 0; i < g.crystals.size(); ++i) {
    const GrownCrystal& c = g.crystals[i];
    if (!(c.area_mm2 > 0.0)) continue;
    random_state_.push_back(rng.state);
    const PhaseRecipe& ph = r.phases[c.phase];
    if (ph.undulose || ph.alteration || ph.inclusions) grain_json(r, c, g.overgrowth_scale, seed, crystal_.size(), rng);  // its draws
    crystal_.push_back(static_cast<std::uint32_t>(i));
  }
}

nlohmann::json RockGrainsJson::grain(std::size_t k) const {
  if (k == crystal_.size()) return {{"mineral", recipe_.matrix_mineral}, {"matrix", true}, {"euler_deg", {0.0, 0.0, 0.0}}};
  Random rng(0);
  rng.state = random_state_[k];
  return grain_json(recipe_, growth_.crystals[crystal_[k]], growth_.overgrowth_scale, seed_, k, rng);
}

void for_each_rock_grain_json(const RockRecipe& r, const RockGrowth& g, std::uint64_t seed,
                              const std::function<void(const nlohmann::json&)>& grain) {
  const RockGrainsJson grains(r, g, seed);
  for (std::size_t k = 0; k < grains.size(); ++k) grain(grains.grain(k));
}

nlohmann::json rock_section_json(const RockRecipe& r, const RockGrowth& g, std::uint64_t seed) {
  nlohmann::json j = rock_section_header_json(r, seed);
  nlohmann::json grains = nlohmann::json::array();
  for_each_rock_grain_json(r, g, seed, [&](const nlohmann::json& grain) { grains.push_back(grain); });
  j["grains"] = std::move(grains);
  return j;
}

}  // namespace pmsim
