#include "core/base/units.h"
#include "core/microscope/lens_ghosts.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <optional>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "core/base/build_cache.h"
#include "core/crystal/plate.h"
#include "core/lens/lens.h"
#include "core/lens/lens_tracer.h"
#include "core/microscope/evaluation_plan.h"
#include "core/microscope/optical_train.h"
#include "core/microscope/sample_source.h"
#include "core/microscope/view_geometry.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/spectral_bands.h"

namespace pmsim {

namespace {
constexpr double kLensNm = kPhysicalLensNm;
constexpr int kBands = 8;  // 50 nm: the ghost is ~0.2 % of the light
constexpr int kMaxGridSide = 128;

LensGhostTable trace_ghosts(int depth, FresnelModel fresnel) {
  const Lens lens(physical_lens_spec(+1));
  const LensMedia media = lens.media(kLensNm);
  LensTraceOptions opt;
  opt.max_depth = depth;
  opt.fresnel = fresnel;
  LensGhostTable t;
  t.depth = depth;
  const int n = LensGhostTable::kSamples;
  t.paths.resize(n);
  LensBundle bs, bp;
  auto trace = [&](const glm::dvec3& k, const glm::dvec3& pol, LensBundle& b) {
    PolarizedRay r;
    r.dir = k;
    r.pol = pol;
    r.wavelength_nm = kLensNm;
    r.intensity = 1.0;
    b.clear();
    trace_lens(lens.geometry(), media, r, opt, b);
  };
  for (int i = 0; i < n; ++i) {
    const double s = t.max_sin * i / (n - 1), c = std::sqrt(1.0 - s * s);
    const glm::dvec3 k{s, 0.0, c};
    trace(k, {0.0, 1.0, 0.0}, bs);
    trace(k, {c, 0.0, -s}, bp);  // p = s × k
    if (i == 0)
      for (const PolarizedRay& o : bs.rays)
        if (o.depth == 0 && o.dir.z > 0) t.axial_intensity = o.intensity;
    // Forward ghosts: depth ≥ 2 (odd depths leave back toward the specimen except at steep
    // angles, where the ledge and the strongly curved faces can send them forward too).
    std::vector<const PolarizedRay*> ps;
    for (const PolarizedRay& o : bp.rays)
      if (o.depth >= 2 && o.dir.z > 0) ps.push_back(&o);
    for (const PolarizedRay& o : bs.rays) {
      if (o.depth < 2 || o.dir.z <= 0) continue;
      // The same geometric path traced with the p input: same depth, same exit direction.
      const PolarizedRay* q = nullptr;
      for (const PolarizedRay* c2 : ps)
        if (c2->depth == o.depth && glm::length(c2->dir - o.dir) < 1e-9) q = c2;
      LensGhostPath g;
      g.dir = o.dir;
      g.depth = o.depth;
      g.field_s = std::sqrt(std::max(0.0, o.intensity)) * o.pol;
      g.field_p = q ? std::sqrt(std::max(0.0, q->intensity)) * q->pol : glm::dvec3(0.0);
      g.optical_path_mm = o.optical_path_mm;
      g.delta_s_rad = o.delta_rad;
      g.delta_p_rad = q ? q->delta_rad : 0.0;
      t.paths[i].push_back(g);
    }
  }
  // Amplitudes relative to the axial depth-0 transmission, as the direct physical model.
  const double norm = 1.0 / std::sqrt(std::max(1e-30, t.axial_intensity));
  for (auto& v : t.paths)
    for (LensGhostPath& g : v) {
      g.field_s *= norm;
      g.field_p *= norm;
    }
  return t;
}

glm::dvec3 rotate_z(const glm::dvec3& v, double c, double s) {
  return {c * v.x - s * v.y, s * v.x + c * v.y, v.z};
}

// One ghost path as a Jones matrix from transverse_basis(k_in) to transverse_basis(k_out):
// out = a_s·(in·ŝ) ŝ_out + a_p·(in·p̂_in) p̂_out, the s/p eigen-amplitudes a of the meridional
// path (complex, phase 2π·O_p/λ − δ).
JonesMatrix path_jones(const glm::dvec3& k_in, const glm::dvec3& k_out, const glm::dvec3& s_hat, complexd a_s,
                       complexd a_p) {
  glm::dvec3 ai, bi, ao, bo;
  transverse_basis(k_in, ai, bi);
  transverse_basis(k_out, ao, bo);
  const glm::dvec3 p_in = glm::cross(s_hat, k_in), p_out = glm::cross(s_hat, k_out);
  auto out_of = [&](const glm::dvec3& in, const glm::dvec3& onto) {
    return a_s * (glm::dot(in, s_hat) * glm::dot(s_hat, onto)) +
           a_p * (glm::dot(in, p_in) * glm::dot(p_out, onto));
  };
  return {out_of(ai, ao), out_of(bi, ao), out_of(ai, bo), out_of(bi, bo)};
}

inline double sinc(double x) { return std::fabs(x) < 1e-8 ? 1.0 : std::sin(x) / x; }

// Spectral sampling of the ghost image: kBands bands of the visible (or the single line), each
// with its observer weight scaled so that T ≡ 1 gives the illuminant white (Y = 1).
struct GhostBands {
  std::vector<double> centre_nm;
  std::vector<glm::dvec3> xyz_weight;
  double width_nm = 0.0;  // 0 for the single line: no band averaging of cross terms
  bool mono = false;
};

GhostBands ghost_bands(const Scene& scene) {
  GhostBands bands;
  bands.mono = scene.render.single_wavelength_nm > 0;
  if (bands.mono) {
    bands.centre_nm = {scene.render.single_wavelength_nm};
    bands.xyz_weight = {glm::dvec3(1.0)};
    return bands;
  }
  const SpectralBands b = spectral_bands(kBands, scene.illuminant);
  bands.width_nm = b.width_nm[0];
  for (int k = 0; k < kBands; ++k) bands.centre_nm.push_back(b.centre_nm(k));
  bands.xyz_weight = b.weight;
  return bands;
}

// The coarse grid of source directions: at most kMaxGridSide cells a side, stride_px pixels each.
struct GhostGrid {
  int width_px = 0, height_px = 0;
  int stride_px = 1;
  int cells_x = 0, cells_y = 0;
  double disk_radius_px = 0.0;  // ρ = 1 of the back-focal-plane disk
  std::size_t cell(int cx, int cy) const { return static_cast<std::size_t>(cy) * cells_x + cx; }
};

GhostGrid ghost_grid(int width_px, int height_px) {
  GhostGrid grid;
  grid.width_px = width_px;
  grid.height_px = height_px;
  grid.stride_px = std::max(1, (std::max(width_px, height_px) + kMaxGridSide - 1) / kMaxGridSide);
  grid.cells_x = (width_px + grid.stride_px - 1) / grid.stride_px;
  grid.cells_y = (height_px + grid.stride_px - 1) / grid.stride_px;
  grid.disk_radius_px = 0.5 * std::min(width_px, height_px);
  return grid;
}

// The sample under the field centre (the domain of the first non-cone unit, as
// conoscopic_figure_view's units): every ghost passes it along the source direction k.
struct CentreSample {
  bool crystal = false;
  std::vector<PreparedPlate> plate_per_band;
  JonesMatrix jones(std::size_t band, const glm::dvec3& k) const {
    return crystal ? plate_jones(plate_per_band[band], k) : JonesMatrix::identity();
  }
};

std::optional<CentreSample> centre_sample(const EvaluationPlan& plan, const std::vector<double>& centre_nm) {
  const EvalUnit* centre_unit = nullptr;
  for (const EvalUnit& u : plan.units())
    if (!u.cone) {
      centre_unit = &u;
      break;
    }
  if (!centre_unit) return std::nullopt;
  const int domain = centre_unit->domain;
  const double thickness_um = centre_unit->thickness_um;
  CentreSample sample;
  sample.crystal = plan.domains()[domain].crystal && thickness_um > 0;
  sample.plate_per_band.resize(centre_nm.size());
  if (sample.crystal)
    for (std::size_t b = 0; b < centre_nm.size(); ++b) {
      sample.plate_per_band[b] = plan.prepare(domain, centre_nm[b]);
      sample.plate_per_band[b].thickness_um = thickness_um;
    }
  return sample;
}

// Everything that is the same for every source cell.
struct GhostInputs {
  const EvaluationPlan& plan;
  const Scene& scene;
  const LensGhostTable& table;
  const GhostGrid& grid;
  const GhostBands& bands;
  const std::vector<TrainState>& trains;  // per band
  const CentreSample& sample;
};

// One source direction k (a coarse cell centre) and its lens Jones matrices.
struct SourceDirection {
  glm::dvec3 k{0.0, 0.0, 1.0};
  double cos_azimuth = 1.0, sin_azimuth = 0.0;
  glm::dvec3 s_hat{0.0, 1.0, 0.0};  // normal of the meridional plane of k
  glm::dmat2 condenser_lens{1.0}, objective_lens{1.0};
};

// Where one ghost path of a source direction lands.
struct GhostHit {
  glm::dvec3 k_ghost;     // exit direction in the lab (the profile's path rotated to k's azimuth)
  double grid_x, grid_y;  // target in coarse-grid coordinates
  bool in_objective, in_condenser;
};

// Scratch of one TBB task, reused cell after cell (no allocation per cell once warmed up).
struct CellScratch {
  std::vector<GhostHit> hits;
  std::vector<complexd> amp_objective, amp_condenser;  // [path][output]
  std::vector<char> grouped;
  std::vector<std::size_t> group;
};

// The exit directions are placed with the direct light's mapping ρ = sin θ / NA_objective; the
// condenser ghost comes from the aperture direction k_g, lit if sin θ_g ≤ NA_condenser.
void place_ghosts(const GhostInputs& in, const SourceDirection& src, const std::vector<LensGhostPath>& paths,
                  std::vector<GhostHit>& hits) {
  const GhostGrid& grid = in.grid;
  hits.clear();
  for (const LensGhostPath& g : paths) {
    GhostHit h;
    h.k_ghost = rotate_z(g.dir, src.cos_azimuth, src.sin_azimuth);
    const double sg = std::hypot(h.k_ghost.x, h.k_ghost.y);
    const double rho = sg / in.scene.objective.na;
    h.in_objective = rho <= 1.0;
    h.in_condenser = sg <= in.scene.condenser.na;
    const double fx = sg > 1e-12 ? rho * h.k_ghost.x / sg : 0.0,
                 fy = sg > 1e-12 ? rho * h.k_ghost.y / sg : 0.0;
    h.grid_x = (fx * grid.disk_radius_px + 0.5 * grid.width_px) / grid.stride_px - 0.5;
    h.grid_y = (0.5 * grid.height_px - fy * grid.disk_radius_px) / grid.stride_px - 0.5;
    hits.push_back(h);
  }
}

// Per path and train output, the complex amplitude of the objective ghost and of the condenser
// ghost in one band (zero where the ghost misses its aperture).
void band_amplitudes(const SourceDirection& src, const TrainState& train, const JonesMatrix& sample_jones,
                     double wavelength_nm, const std::vector<LensGhostPath>& paths, CellScratch& scratch) {
  const double two_pi = 2.0 * kPi;
  const double lam_mm = wavelength_nm * 1e-6;
  scratch.amp_objective.assign(paths.size() * train.outputs, complexd(0.0));
  scratch.amp_condenser.assign(paths.size() * train.outputs, complexd(0.0));
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const LensGhostPath& g = paths[i];
    const GhostHit& hit = scratch.hits[i];
    const double phase = two_pi * g.optical_path_mm / lam_mm;
    const complexd es = std::polar(1.0, phase - g.delta_s_rad), ep = std::polar(1.0, phase - g.delta_p_rad);
    // s/p eigen-amplitudes of the path (sign included): field along ŝ_out, p̂_out.
    const glm::dvec3 kg0 = g.dir, s0{0.0, 1.0, 0.0};
    const complexd a_s = es * glm::dot(g.field_s, s0);
    const complexd a_p = ep * glm::dot(g.field_p, glm::cross(s0, kg0));
    // Objective ghost: condenser (depth 0) → sample along k → ghost path to k_g.
    if (hit.in_objective) {
      const JonesMatrix G = path_jones(src.k, hit.k_ghost, src.s_hat, a_s, a_p);
      // The Bertrand side sees the ghost in the lab frame: the aplanatic mapping of k_g.
      const JonesMatrix M = jones_from_real(glm::transpose(aplanatic_frame(hit.k_ghost))) * G * sample_jones *
                            jones_from_real(src.condenser_lens);
      for (int o = 0; o < train.outputs; ++o)
        scratch.amp_objective[i * train.outputs + o] = jones_output(train, M, o).x;
    }
    // Condenser ghost (reciprocal path): aperture direction k_g → specimen along k →
    // sample → objective (depth 0) → this cell.
    if (hit.in_condenser) {
      const JonesMatrix G = path_jones(hit.k_ghost, src.k, src.s_hat, a_s, a_p);
      const JonesMatrix M = jones_from_real(src.objective_lens) * sample_jones * G *
                            jones_from_real(aplanatic_frame(hit.k_ghost));
      for (int o = 0; o < train.outputs; ++o)
        scratch.amp_condenser[i * train.outputs + o] = jones_output(train, M, o).x;
    }
  }
}

// Intensity of a group of objective ghosts landing in one cell: |Σ a|² with the cross terms
// band-averaged, sinc(π·ΔO_p·Δλ/λ²) (a flat band of width Δλ around λ).
double coherent_group_intensity(const std::vector<LensGhostPath>& paths, const CellScratch& scratch,
                                int outputs, double wavelength_nm, double band_width_nm) {
  const std::vector<std::size_t>& group = scratch.group;
  double intensity = 0.0;
  for (int o = 0; o < outputs; ++o)
    for (std::size_t a = 0; a < group.size(); ++a)
      for (std::size_t c = a; c < group.size(); ++c) {
        const complexd x = scratch.amp_objective[group[a] * outputs + o],
                       y = scratch.amp_objective[group[c] * outputs + o];
        if (a == c) {
          intensity += std::norm(x);
        } else {
          const double dO_nm = (paths[group[a]].optical_path_mm - paths[group[c]].optical_path_mm) * 1e6;
          intensity += 2.0 * std::real(x * std::conj(y)) *
                       sinc(kPi * dO_nm * band_width_nm / (wavelength_nm * wavelength_nm));
        }
      }
  return intensity;
}

// Objective: paths of this ch landing in the same cell add coherently; each group's intensity is
// spread bilinearly around its target (into this source row's splat list: rows run in parallel).
void splat_objective_ghosts(const GhostInputs& in, std::size_t band, int outputs,
                            const std::vector<LensGhostPath>& paths, CellScratch& scratch,
                            std::vector<std::pair<int, glm::dvec3>>& row_splats) {
  const GhostGrid& grid = in.grid;
  const std::vector<GhostHit>& hits = scratch.hits;
  scratch.grouped.assign(paths.size(), 0);
  for (std::size_t i = 0; i < paths.size(); ++i) {
    if (scratch.grouped[i] || !hits[i].in_objective) continue;
    const long ci = std::lround(hits[i].grid_x), cj = std::lround(hits[i].grid_y);
    scratch.group.clear();
    for (std::size_t j = i; j < paths.size(); ++j)
      if (!scratch.grouped[j] && hits[j].in_objective && std::lround(hits[j].grid_x) == ci &&
          std::lround(hits[j].grid_y) == cj) {
        scratch.group.push_back(j);
        scratch.grouped[j] = 1;
      }
    const double intensity =
        coherent_group_intensity(paths, scratch, outputs, in.bands.centre_nm[band], in.bands.width_nm);
    const glm::dvec3 v = std::max(0.0, intensity) * in.bands.xyz_weight[band];
    const double gx = hits[i].grid_x, gy = hits[i].grid_y;
    const int x0 = static_cast<int>(std::floor(gx)), y0 = static_cast<int>(std::floor(gy));
    const double fx = gx - x0, fy = gy - y0;
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const int x = x0 + dx, y = y0 + dy;
        const double w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy);
        if (x < 0 || y < 0 || x >= grid.cells_x || y >= grid.cells_y || w <= 0) continue;
        row_splats.push_back({y * grid.cells_x + x, v * w});
      }
  }
}

// All ghosts of the source direction at cell (cx, cy): objective ghosts into row_splats,
// condenser ghosts (which land on the cell itself) into cell_xyz[cell][1]. Returns the paths used.
int add_cell_ghosts(const GhostInputs& in, int cx, int cy, CellScratch& scratch,
                    std::vector<glm::dvec3>& cell_xyz, std::vector<std::pair<int, glm::dvec3>>& row_splats) {
  const GhostGrid& grid = in.grid;
  const double px = std::min((cx + 0.5) * grid.stride_px, grid.width_px - 0.5);
  const double py = std::min((cy + 0.5) * grid.stride_px, grid.height_px - 0.5);
  SourceDirection src;
  if (!bfp_direction(in.scene, field_from_pixel(grid.width_px, grid.height_px, px, py), src.k)) return 0;
  const glm::dvec3& k = src.k;
  const double sin_t = std::hypot(k.x, k.y);
  src.cos_azimuth = sin_t > 1e-12 ? k.x / sin_t : 1.0;
  src.sin_azimuth = sin_t > 1e-12 ? k.y / sin_t : 0.0;
  src.s_hat = {-src.sin_azimuth, src.cos_azimuth, 0.0};
  const std::vector<LensGhostPath>& paths = in.table.at(sin_t);
  in.plan.lens_jones(k, src.condenser_lens, src.objective_lens);
  place_ghosts(in, src, paths, scratch.hits);
  for (std::size_t b = 0; b < in.bands.centre_nm.size(); ++b) {
    const TrainState& train = in.trains[b];
    band_amplitudes(src, train, in.sample.jones(b, k), in.bands.centre_nm[b], paths, scratch);
    splat_objective_ghosts(in, b, train.outputs, paths, scratch, row_splats);
    // Condenser: different aperture points are different ch: intensities add here.
    double condenser_intensity = 0.0;
    for (const complexd& a : scratch.amp_condenser) condenser_intensity += std::norm(a);
    cell_xyz[grid.cell(cx, cy) * 2 + 1] += condenser_intensity * in.bands.xyz_weight[b];
  }
  return static_cast<int>(paths.size());
}

// Bilinear upsampling of the [objective, condenser] cells to the pixels inside the
// back-focal-plane disk, summing the energies on the way.
void upsample_to_pixels(const GhostGrid& grid, const std::vector<glm::dvec3>& cell_xyz, bool mono,
                        LensGhostImage& img) {
  const int W = grid.width_px, H = grid.height_px, GW = grid.cells_x, GH = grid.cells_y;
  img.xyz.assign(static_cast<std::size_t>(W) * H * 3, 0.0f);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const glm::dvec2 f = field_from_pixel(W, H, x + 0.5, y + 0.5);
      if (std::hypot(f.x, f.y) > 1.0) continue;
      const double gx = std::clamp((x + 0.5) / grid.stride_px - 0.5, 0.0, GW - 1.0);
      const double gy = std::clamp((y + 0.5) / grid.stride_px - 0.5, 0.0, GH - 1.0);
      const int x0 = std::min(static_cast<int>(gx), std::max(0, GW - 2)),
                y0 = std::min(static_cast<int>(gy), std::max(0, GH - 2));
      const double fx = GW > 1 ? gx - x0 : 0.0, fy = GH > 1 ? gy - y0 : 0.0;
      glm::dvec3 v[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const int xx = std::min(x0 + dx, GW - 1), yy = std::min(y0 + dy, GH - 1);
          const double w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy);
          for (int e = 0; e < 2; ++e) v[e] += w * cell_xyz[grid.cell(xx, yy) * 2 + e];
        }
      img.objective_energy += v[0].y;
      img.condenser_energy += v[1].y;
      const glm::dvec3 sum = v[0] + v[1];
      for (int c = 0; c < 3; ++c) {
        const double val = mono ? sum.y : sum[c];
        img.xyz[(static_cast<std::size_t>(y) * W + x) * 3 + c] =
            std::isfinite(val) ? static_cast<float>(val) : 0.0f;
      }
    }
}

}  // namespace

const std::vector<LensGhostPath>& LensGhostTable::at(double sin_theta) const {
  const double u = std::clamp(sin_theta / max_sin, 0.0, 1.0) * (kSamples - 1);
  return paths[std::min(static_cast<int>(std::lround(u)), kSamples - 1)];
}

const LensGhostTable& lens_ghost_table(int depth, FresnelModel fresnel) {
  static BuildCache<std::pair<int, FresnelModel>, LensGhostTable> cache;
  return *cache.get({depth, fresnel}, [&] { return std::make_shared<const LensGhostTable>(trace_ghosts(depth, fresnel)); });
}

LensGhostImage lens_ghost_image(const EvaluationPlan& plan, const std::atomic<bool>* cancel) {
  LensGhostImage img;
  const Scene& sc = plan.scene();
  if (!plan.lenses() || sc.optics.lens_depth < 2 || sc.mode != ViewMode::Cono || !sc.bertrand_in) return img;
  const LensGhostTable& table = lens_ghost_table(sc.optics.lens_depth, sc.optics.fresnel);
  const GhostGrid grid = ghost_grid(plan.width(), plan.height());
  const GhostBands bands = ghost_bands(sc);
  std::vector<TrainState> trains;
  for (double nm : bands.centre_nm) trains.push_back(make_train(sc, plan.compensator(), nm));
  const std::optional<CentreSample> sample = centre_sample(plan, bands.centre_nm);
  if (!sample) return img;
  const GhostInputs in{plan, sc, table, grid, bands, trains, *sample};

  // [cell][objective, condenser] XYZ; objective ghosts land in other cells, so they are collected
  // per source row and added in row order after the parallel loop (deterministic sums).
  std::vector<glm::dvec3> cell_xyz(static_cast<std::size_t>(grid.cells_x) * grid.cells_y * 2,
                                   glm::dvec3(0.0));
  std::vector<std::vector<std::pair<int, glm::dvec3>>> splats(grid.cells_y);
  std::vector<int> row_paths(grid.cells_y, 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, grid.cells_y, 2), [&](const tbb::blocked_range<int>& rows) {
    CellScratch scratch;
    for (int cy = rows.begin(); cy != rows.end(); ++cy) {
      if (cancel && cancel->load(std::memory_order_relaxed)) return;
      for (int cx = 0; cx < grid.cells_x; ++cx)
        row_paths[cy] += add_cell_ghosts(in, cx, cy, scratch, cell_xyz, splats[cy]);
    }
  });
  if (cancel && cancel->load()) return img;
  for (int cy = 0; cy < grid.cells_y; ++cy) {
    img.paths += row_paths[cy];
    for (const auto& [cell, v] : splats[cy]) cell_xyz[static_cast<std::size_t>(cell) * 2] += v;
  }
  upsample_to_pixels(grid, cell_xyz, bands.mono, img);
  return img;
}

}  // namespace pmsim
