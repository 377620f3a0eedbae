#include "core/base/units.h"
#include "core/bench/physical_lens_model.h"

#include <chrono>
#include <cmath>
#include <array>
#include <complex>
#include <numbers>

#include <glm/geometric.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/base/conventions.h"
#include "core/crystal/plate.h"
#include "core/lens/lens.h"
#include "core/lens/lens_tracer.h"
#include "core/microscope/evaluation_plan.h"
#include "core/microscope/modal_fit.h"
#include "core/microscope/sample_source.h"
#include "core/microscope/view_geometry.h"
#include "core/render/image_develop.h"
#include "core/render/spectral_level.h"

namespace pmsim {

namespace {

using cd = std::complex<double>;
constexpr double kLensNm = kPhysicalLensNm;

struct CVec2 {
  cd x, y;
};
struct CMat2 {  // columns: response to input basis vector 0 and 1
  CVec2 c0, c1;
  CVec2 operator*(const CVec2& v) const { return {c0.x * v.x + c1.x * v.y, c0.y * v.x + c1.y * v.y}; }
};

struct ObjectivePath {
  CMat2 jones;                               // sample transverse basis of k → exit transverse basis
  double bfp_r_mm = 0.0, bfp_azimuth = 0.0;  // where the exit ray crosses the back-focal plane
  bool main = false;
};

CVec2 field_in_basis(const PolarizedRay& r) {
  glm::dvec3 a, b;
  transverse_basis(r.dir, a, b);
  const cd ph = std::polar(std::sqrt(std::max(0.0, r.intensity)), -r.delta_rad);
  return {ph * glm::dot(r.pol, a), ph * glm::dot(r.pol, b)};
}

PolarizedRay make_ray(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& pol) {
  PolarizedRay r;
  r.origin = o;
  r.dir = d;
  r.pol = pol;
  r.wavelength_nm = kLensNm;
  r.intensity = 1.0;
  return r;
}

struct Optics {
  const LensGeometry* condenser = nullptr;
  const LensGeometry* objective = nullptr;
  LensMedia media;
  LensTraceOptions opt;
  double bfp_z_mm = 0.0;
};

// Forward rays leaving the lens toward +z (the ones that go on up the microscope).
void forward_rays(const LensBundle& b, std::vector<PolarizedRay>& out) {
  out.clear();
  for (const PolarizedRay& r : b.rays)
    if (r.dir.z > 0.0) out.push_back(r);
}

// Condenser: Jones matrix from the polarizer frame (basis of the incoming ray ≈ lab x, y) to the
// transverse basis of k at the sample. False if no depth-0 ray reaches the sample along k.
bool condenser_jones(const Optics& O, const glm::dvec3& k, CMat2& J, LensBundle& bundle,
                     std::vector<PolarizedRay>& fw) {
  LensTraceOptions back = O.opt;
  back.max_depth = 0;
  glm::dvec3 a, b;
  transverse_basis(k, a, b);
  bundle.clear();
  trace_lens(*O.condenser, O.media, make_ray(glm::dvec3(0.0), -k, a), back, bundle);
  const PolarizedRay* exit = nullptr;
  for (const PolarizedRay& r : bundle.rays)
    if (r.depth == 0 && r.dir.z < 0.0) exit = &r;
  if (!exit) return false;
  const glm::dvec3 d_in = -exit->dir, o_in = exit->origin - d_in * 1.0;
  glm::dvec3 ia, ib;
  transverse_basis(d_in, ia, ib);
  CVec2 col[2];
  for (int c = 0; c < 2; ++c) {
    bundle.clear();
    LensTraceOptions one = O.opt;
    one.max_depth = 0;
    trace_lens(*O.condenser, O.media, make_ray(o_in, d_in, c == 0 ? ia : ib), one, bundle);
    forward_rays(bundle, fw);
    // The depth-0 ray that runs back along k through the sample (reciprocity of the path) — not
    // the entry reflection, which on the steep rim of the cap can also head upward.
    const PolarizedRay* best = nullptr;
    for (const PolarizedRay& r : fw)
      if (r.depth == 0 && (!best || glm::dot(r.dir, k) > glm::dot(best->dir, k))) best = &r;
    if (!best || glm::dot(best->dir, k) < 1.0 - 1e-9) return false;
    // Its transverse basis is that of k.
    col[c] = field_in_basis(*best);
  }
  J = {col[0], col[1]};
  return true;
}

// Objective: one Jones matrix per forward path (depth 0 = main, then ghosts).
void objective_paths(const Optics& O, const glm::dvec3& k, std::vector<ObjectivePath>& paths,
                     LensBundle& bundle, std::vector<PolarizedRay> fw[2]) {
  paths.clear();
  glm::dvec3 a, b;
  transverse_basis(k, a, b);
  for (int c = 0; c < 2; ++c) {
    bundle.clear();
    trace_lens(*O.objective, O.media, make_ray(glm::dvec3(0.0), k, c == 0 ? a : b), O.opt, bundle);
    forward_rays(bundle, fw[c]);
  }
  auto add = [&](const PolarizedRay& ra, const PolarizedRay& rb) {
    ObjectivePath p;
    p.jones = {field_in_basis(ra), field_in_basis(rb)};
    p.main = ra.depth == 0;
    // Crossing of the back-focal plane z = bfp_z_mm.
    const double t = (O.bfp_z_mm - ra.origin.z) / ra.dir.z;
    const glm::dvec3 q = ra.origin + t * ra.dir;
    p.bfp_r_mm = std::hypot(q.x, q.y);
    p.bfp_azimuth = std::atan2(q.y, q.x);
    paths.push_back(p);
  };
  // The depth-0 path exists for both input polarizations whenever the lens transmits at all.
  // (The entry reflection is depth 0 too and may head upward on the steep rim of the front cap:
  // the transmitted ray is the one through the back cap, the brightest depth-0 forward ray.)
  const PolarizedRay *ma = nullptr, *mb = nullptr;
  for (const PolarizedRay& r : fw[0])
    if (r.depth == 0 && (!ma || r.intensity > ma->intensity)) ma = &r;
  for (const PolarizedRay& r : fw[1])
    if (r.depth == 0 && (!mb || r.intensity > mb->intensity)) mb = &r;
  if (ma && mb) add(*ma, *mb);
  // Ghosts: the two trees match ray for ray unless a branch of zero intensity was dropped for one
  // polarization (e.g. p light at Brewster's angle inside); then the ghosts of this direction are
  // left out (counted in the model report).
  if (fw[0].size() != fw[1].size()) return;
  for (std::size_t i = 0; i < fw[0].size(); ++i) {
    const PolarizedRay &ra = fw[0][i], &rb = fw[1][i];
    if (&ra == ma || ra.depth != rb.depth || glm::dot(ra.dir, rb.dir) < 1.0 - 1e-12) continue;
    add(ra, rb);
  }
}

// The bench's copy of the scene: geometry only (the modes are fitted here, per unit), and 32
// bands unless the scene asks for a number.
Scene bench_scene(const Scene& scene_in) {
  Scene scene = scene_in;
  scene.render.strategy = RenderStrategy::Exact;
  if (scene.render.wavelengths <= 0) scene.render.wavelengths = 32;
  return scene;
}

// Per crystal domain, the plate prepared at the three ModalFit anchors.
std::vector<std::array<PreparedPlate, 3>> modal_anchors(const EvaluationPlan& plan) {
  std::vector<std::array<PreparedPlate, 3>> anchors(plan.domains().size());
  for (std::size_t d = 0; d < plan.domains().size(); ++d)
    if (plan.domains()[d].crystal)
      for (int a = 0; a < 3; ++a) anchors[d][a] = plan.prepare(static_cast<int>(d), ModalFit::kAnchorNm[a]);
  return anchors;
}

Optics make_optics(const Lens& objective, const Lens& condenser, const Scene& scene) {
  Optics optics;
  optics.objective = &objective.geometry();
  optics.condenser = &condenser.geometry();
  optics.media = objective.media(kLensNm);
  optics.opt.max_depth = scene.optics.lens_depth;
  optics.opt.fresnel = scene.optics.fresnel;
  optics.opt.tir = TirMode::Stop;
  optics.bfp_z_mm = optics.objective->back_vertex().z + 2.0;
  return optics;
}

// Height-to-pixel relation of the depth-0 rays along azimuth 0: r(ρ), ρ = sinθ/NA, sampled at
// kSamples + 1 equal steps of ρ; a ghost crossing the back-focal plane at r lands where the
// depth-0 ray of the nearest r does.
struct BfpHeightTable {
  static constexpr int kSamples = 512;
  std::vector<double> r_mm;  // −1 where no depth-0 ray leaves
  int width_px = 0, height_px = 0;
  double disk_radius_px = 0.0;

  // The pixel (y·width + x) of the crossing at radius r_mm, azimuth_rad; −1 off the table/image.
  long pixel(double bfp_r_mm, double azimuth_rad) const {
    int best = -1;
    double bd = 1e300;
    for (int i = 0; i <= kSamples; ++i)
      if (r_mm[i] >= 0 && std::fabs(r_mm[i] - bfp_r_mm) < bd) {
        bd = std::fabs(r_mm[i] - bfp_r_mm);
        best = i;
      }
    if (best < 0) return -1;
    const double rho = static_cast<double>(best) / kSamples;
    const double px = 0.5 * width_px + rho * std::cos(azimuth_rad) * disk_radius_px;
    const double py = 0.5 * height_px - rho * std::sin(azimuth_rad) * disk_radius_px;
    const long x = static_cast<long>(std::floor(px)), y = static_cast<long>(std::floor(py));
    if (x < 0 || y < 0 || x >= width_px || y >= height_px) return -1;
    return y * width_px + x;
  }
};

BfpHeightTable bfp_height_table(const Optics& optics, double objective_na, int width_px, int height_px) {
  BfpHeightTable table;
  table.r_mm.assign(BfpHeightTable::kSamples + 1, -1.0);
  table.width_px = width_px;
  table.height_px = height_px;
  table.disk_radius_px = 0.5 * std::min(width_px, height_px);
  LensBundle bundle;
  std::vector<PolarizedRay> fw[2];
  std::vector<ObjectivePath> paths;
  for (int i = 0; i <= BfpHeightTable::kSamples; ++i) {
    const double s = std::min(0.999999, objective_na * i / BfpHeightTable::kSamples);
    objective_paths(optics, {s, 0.0, std::sqrt(1 - s * s)}, paths, bundle, fw);
    for (const ObjectivePath& p : paths)
      if (p.main) table.r_mm[i] = p.bfp_r_mm;
  }
  return table;
}

// Unit → pixel (one unit per lit pixel in the conoscopic view); −1 for units no pixel refers to.
std::vector<long> pixel_of_units(const EvaluationPlan& plan) {
  std::vector<long> pixel_of_unit(plan.units().size(), -1);
  for (long i = 0; i < static_cast<long>(plan.width()) * plan.height(); ++i)
    for (int ref = plan.pixel_offset()[i]; ref < plan.pixel_offset()[i + 1]; ++ref)
      pixel_of_unit[plan.refs()[ref].unit] = i;
  return pixel_of_unit;
}

// Exposure convention (issue 3): amplitudes relative to the axial ray's depth-0 path through
// both lenses, so that an empty stage between parallel polars gives Y = 1 on the axis.
double axial_intensity(const Optics& optics) {
  double axial = 1.0;
  LensBundle bundle;
  std::vector<PolarizedRay> fw[2];
  std::vector<ObjectivePath> paths;
  CMat2 condenser;
  const glm::dvec3 kz = kLightDirection;
  if (condenser_jones(optics, kz, condenser, bundle, fw[0])) {
    objective_paths(optics, kz, paths, bundle, fw);
    for (const ObjectivePath& p : paths)
      if (p.main) axial = std::norm((p.jones * (condenser * CVec2{1.0, 0.0})).x);
  }
  if (!(axial > 0.0)) axial = 1.0;
  return axial;
}

// The detected polarizations: the analyzer's direction, or both lab axes without analyzer.
struct DetectedOutputs {
  glm::dvec2 dir[2];
  int count = 1;
};

DetectedOutputs detected_outputs(const Scene& scene) {
  DetectedOutputs out;
  if (scene.analyzer_in) {
    out.dir[0] = polarizer_direction(scene.analyzer_deg);
  } else {
    out.count = 2;
    out.dir[0] = {1, 0};
    out.dir[1] = {0, 1};
  }
  return out;
}

// Detected intensity of one band through the plate's two modes: the sample field e_s is split
// on the (non-orthogonal) mode polarizations e1, e2 with the dual basis d1, d2, each part carried
// by its mode transmission and the objective path; fast mode phase −φ/2, slow +φ/2, so
// |c1 e^{−iφ/2} + c2 e^{iφ/2}|² = |c1|² + |c2|² + 2 Re(c1 c2* e^{−iφ}), the cross term averaged
// over the band Δλ: × sinc(½ dφ/dλ · Δλ), φ = 2π Γ/λ.
double crystal_band_intensity(const ModalPoint& m, const CVec2& e_s, const CMat2& path_jones,
                              double wavelength_nm, double band_nm, const DetectedOutputs& outputs) {
  glm::dvec2 e1 = m.e1, e2 = m.e2;
  double det = e1.x * e2.y - e1.y * e2.x;
  if (std::fabs(det) < 1e-9) {
    e2 = {-e1.y, e1.x};
    det = 1.0;
  }
  const glm::dvec2 d1{e2.y / det, -e2.x / det}, d2{-e1.y / det, e1.x / det};
  const cd a1 = m.t1 * (d1.x * e_s.x + d1.y * e_s.y), a2 = m.t2 * (d2.x * e_s.x + d2.y * e_s.y);
  const CVec2 f1 = path_jones * CVec2{a1 * e1.x, a1 * e1.y};
  const CVec2 f2 = path_jones * CVec2{a2 * e2.x, a2 * e2.y};
  const double lambda = wavelength_nm, two_pi = 2.0 * kPi;
  const double phi = two_pi * m.gamma_nm / lambda;
  const double dphi = two_pi * (m.dgamma_dnm / lambda - m.gamma_nm / (lambda * lambda));
  const double x = 0.5 * dphi * band_nm;
  const double sinc = std::fabs(x) < 1e-8 ? 1.0 : std::sin(x) / x;
  double t = 0.0;
  for (int o = 0; o < outputs.count; ++o) {
    const cd c1 = outputs.dir[o].x * f1.x + outputs.dir[o].y * f1.y;
    const cd c2 = outputs.dir[o].x * f2.x + outputs.dir[o].y * f2.y;
    t += std::norm(c1) + std::norm(c2) + 2.0 * std::real(c1 * std::conj(c2) * std::polar(1.0, -phi)) * sinc;
  }
  return t;
}

// Everything that is the same for every unit.
struct BenchInputs {
  const EvaluationPlan& plan;
  const SpectralLevel& level;
  const Optics& optics;
  const std::vector<std::array<PreparedPlate, 3>>& anchors;
  const BfpHeightTable& bfp;
  const std::vector<long>& pixel_of_unit;
  CVec2 polarizer;  // lab x, y
  const DetectedOutputs& outputs;
  double axial;
};

// Scratch of one TBB task, reused unit after unit.
struct UnitScratch {
  LensBundle bundle;
  std::vector<PolarizedRay> fw[2];
  std::vector<ObjectivePath> paths;
};

// The light of unit u (one condenser direction k) through every objective path, added to the
// pixel where each path lands, in XYZ relative to the axial transmission.
void add_unit_light(const BenchInputs& in, std::size_t u, UnitScratch& scratch,
                    std::vector<glm::dvec3>& img) {
  const EvalUnit& unit = in.plan.units()[u];
  if (in.pixel_of_unit[u] < 0) return;
  CMat2 condenser;
  if (!condenser_jones(in.optics, unit.k_air, condenser, scratch.bundle, scratch.fw[0])) return;
  objective_paths(in.optics, unit.k_air, scratch.paths, scratch.bundle, scratch.fw);
  const CVec2 e_s = condenser * in.polarizer;  // field at the sample, transverse basis of k
  const bool crystal = in.plan.domains()[unit.domain].crystal && unit.thickness_um > 0;
  const double scale = crystal ? unit.thickness_um / in.plan.domains()[unit.domain].thickness_um : 1.0;
  ModalFit fit;
  if (crystal) fit.fit(in.anchors[unit.domain].data(), unit.k_air);
  const SpectralLevel& L = in.level;
  for (const ObjectivePath& path : scratch.paths) {
    const long px = path.main ? in.pixel_of_unit[u] : in.bfp.pixel(path.bfp_r_mm, path.bfp_azimuth);
    if (px < 0) continue;
    glm::dvec3 xyz(0.0);
    for (int i = 0; i < L.n; ++i) {
      double t = 0.0;
      if (!crystal) {
        const CVec2 e = path.jones * e_s;
        for (int o = 0; o < in.outputs.count; ++o)
          t += std::norm(in.outputs.dir[o].x * e.x + in.outputs.dir[o].y * e.y);
      } else {
        t = crystal_band_intensity(fit.at(L.nm[i], scale), e_s, path.jones, L.nm[i], L.band_nm, in.outputs);
      }
      if (std::isfinite(t)) xyz += L.weight[i] * std::max(0.0, t);
    }
    img[static_cast<std::size_t>(px)] += xyz / in.axial;
  }
}

}  // namespace

StrategyResult render_physical_lens_model(const Scene& scene_in) {
  const auto t0 = std::chrono::steady_clock::now();
  const Scene scene = bench_scene(scene_in);
  const auto plan = compile_evaluation_plan(scene);
  const std::vector<std::array<PreparedPlate, 3>> anchors = modal_anchors(*plan);
  const SpectralLevel L = make_spectral_level(*plan, scene.render.wavelengths);
  const int W = plan->width(), H = plan->height();

  const Lens objective(physical_lens_spec(+1));
  const Lens condenser(physical_lens_spec(-1));
  const Optics optics = make_optics(objective, condenser, scene);
  const BfpHeightTable bfp = bfp_height_table(optics, scene.objective.na, W, H);
  const std::vector<long> pixel_of_unit = pixel_of_units(*plan);
  const glm::dvec2 pol = polarizer_direction(scene.polarizer_deg);
  const DetectedOutputs outputs = detected_outputs(scene);
  const BenchInputs in{
      *plan, L, optics, anchors, bfp, pixel_of_unit, CVec2{pol.x, pol.y}, outputs, axial_intensity(optics)};

  // One image per thread (ghosts land on other units' pixels), summed afterwards.
  tbb::enumerable_thread_specific<std::vector<glm::dvec3>> acc(
      [&] { return std::vector<glm::dvec3>(static_cast<std::size_t>(W) * H, glm::dvec3(0.0)); });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, plan->units().size(), 32),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      auto& img = acc.local();
                      UnitScratch scratch;
                      for (std::size_t u = range.begin(); u != range.end(); ++u)
                        add_unit_light(in, u, scratch, img);
                    });
  std::vector<glm::dvec3> sum(static_cast<std::size_t>(W) * H, glm::dvec3(0.0));
  for (const auto& img : acc)
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += img[i];
  StrategyResult r;
  r.xyz.resize(sum.size() * 3);
  for (std::size_t i = 0; i < sum.size(); ++i)
    for (int c = 0; c < 3; ++c)
      r.xyz[3 * i + c] = std::isfinite(sum[i][c]) ? static_cast<float>(sum[i][c]) : 0.0f;
  r.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  r.wavelengths = L.n;
  r.model_report = "bench-side SML condenser + objective (paper lens, N-BK7), dT = " +
                   std::to_string(scene.optics.lens_depth) +
                   (scene.optics.fresnel == FresnelModel::Schlick ? ", Schlick" : ", Fresnel") +
                   ", ghosts splatted by back-focal-plane crossing; plate: renderer's modal fit, " +
                   std::to_string(L.n) + " bands";
  return r;
}

}  // namespace pmsim
