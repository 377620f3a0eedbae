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
  CMat2 jones;        // sample transverse basis of k → exit transverse basis
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

}  // namespace

StrategyResult render_physical_lens_model(const Scene& scene_in) {
  const auto t0 = std::chrono::steady_clock::now();
  Scene scene = scene_in;
  scene.render.strategy = RenderStrategy::Exact;  // geometry only: the modes are fitted here, per unit
  if (scene.render.wavelengths <= 0) scene.render.wavelengths = 32;
  const auto plan = compile_evaluation_plan(scene);
  std::vector<std::array<PreparedPlate, 3>> anchors(plan->domains().size());
  for (std::size_t d = 0; d < plan->domains().size(); ++d)
    if (plan->domains()[d].crystal)
      for (int a = 0; a < 3; ++a) anchors[d][a] = plan->prepare(static_cast<int>(d), ModalFit::kAnchorNm[a]);
  const SpectralLevel L = make_spectral_level(*plan, scene.render.wavelengths);
  const int W = plan->width(), H = plan->height();

  Optics O;
  const Lens objective(physical_lens_spec(+1));
  const Lens condenser(physical_lens_spec(-1));
  O.objective = &objective.geometry();
  O.condenser = &condenser.geometry();
  O.media = objective.media(kLensNm);
  O.opt.max_depth = scene.optics.lens_depth;
  O.opt.fresnel = scene.optics.fresnel;
  O.opt.tir = TirMode::Stop;
  O.bfp_z_mm = O.objective->back_vertex().z + 2.0;

  // Height-to-pixel relation of the depth-0 rays along azimuth 0: r(ρ), ρ = sinθ/NA.
  const int kTable = 512;
  std::vector<double> table_r(kTable + 1, -1.0);
  {
    LensBundle bundle;
    std::vector<PolarizedRay> fw[2];
    std::vector<ObjectivePath> paths;
    for (int i = 0; i <= kTable; ++i) {
      const double s = std::min(0.999999, scene.objective.na * i / kTable);
      objective_paths(O, {s, 0.0, std::sqrt(1 - s * s)}, paths, bundle, fw);
      for (const ObjectivePath& p : paths)
        if (p.main) table_r[i] = p.bfp_r_mm;
    }
  }
  const double half_px = 0.5 * std::min(W, H);
  auto pixel_of_bfp = [&](double r_mm, double az) -> long {
    int best = -1;
    double bd = 1e300;
    for (int i = 0; i <= kTable; ++i)
      if (table_r[i] >= 0 && std::fabs(table_r[i] - r_mm) < bd) {
        bd = std::fabs(table_r[i] - r_mm);
        best = i;
      }
    if (best < 0) return -1;
    const double rho = static_cast<double>(best) / kTable;
    const double px = 0.5 * W + rho * std::cos(az) * half_px, py = 0.5 * H - rho * std::sin(az) * half_px;
    const long x = static_cast<long>(std::floor(px)), y = static_cast<long>(std::floor(py));
    if (x < 0 || y < 0 || x >= W || y >= H) return -1;
    return y * W + x;
  };

  // Unit → pixel (one unit per lit pixel in the conoscopic view).
  std::vector<long> pixel_of_unit(plan->units().size(), -1);
  for (long i = 0; i < static_cast<long>(W) * H; ++i)
    for (int r = plan->pixel_offset()[i]; r < plan->pixel_offset()[i + 1]; ++r) pixel_of_unit[plan->refs()[r].unit] = i;

  // Exposure convention (issue 3): amplitudes relative to the axial ray's depth-0 path through
  // both lenses, so that an empty stage between parallel polars gives Y = 1 on the axis.
  double axial = 1.0;
  {
    LensBundle bundle;
    std::vector<PolarizedRay> fw[2];
    std::vector<ObjectivePath> paths;
    CMat2 Jc;
    const glm::dvec3 kz = kLightDirection;
    if (condenser_jones(O, kz, Jc, bundle, fw[0])) {
      objective_paths(O, kz, paths, bundle, fw);
      for (const ObjectivePath& p : paths)
        if (p.main) axial = std::norm((p.jones * (Jc * CVec2{1.0, 0.0})).x);
    }
    if (!(axial > 0.0)) axial = 1.0;
  }
  const glm::dvec2 pol = polarizer_direction(scene.polarizer_deg);
  const CVec2 p_in{pol.x, pol.y};
  glm::dvec2 outputs[2];
  int n_out = 1;
  if (scene.analyzer_in) {
    outputs[0] = polarizer_direction(scene.analyzer_deg);
  } else {
    n_out = 2;
    outputs[0] = {1, 0};
    outputs[1] = {0, 1};
  }

  tbb::enumerable_thread_specific<std::vector<glm::dvec3>> acc(
      [&] { return std::vector<glm::dvec3>(static_cast<std::size_t>(W) * H, glm::dvec3(0.0)); });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, plan->units().size(), 32), [&](const tbb::blocked_range<std::size_t>& range) {
    auto& img = acc.local();
    LensBundle bundle;
    std::vector<PolarizedRay> fw[2];
    std::vector<ObjectivePath> paths;
    for (std::size_t u = range.begin(); u != range.end(); ++u) {
      const EvalUnit& unit = plan->units()[u];
      if (pixel_of_unit[u] < 0) continue;
      CMat2 Jc;
      if (!condenser_jones(O, unit.k_air, Jc, bundle, fw[0])) continue;
      objective_paths(O, unit.k_air, paths, bundle, fw);
      const CVec2 e_s = Jc * p_in;  // field at the sample, transverse basis of k
      const bool crystal = plan->domains()[unit.domain].crystal && unit.thickness_um > 0;
      const double scale = crystal ? unit.thickness_um / plan->domains()[unit.domain].thickness_um : 1.0;
      ModalFit fit;
      if (crystal) fit.fit(anchors[unit.domain].data(), unit.k_air);
      for (const ObjectivePath& path : paths) {
        const long px = path.main ? pixel_of_unit[u] : pixel_of_bfp(path.bfp_r_mm, path.bfp_azimuth);
        if (px < 0) continue;
        glm::dvec3 xyz(0.0);
        for (int i = 0; i < L.n; ++i) {
          double t = 0.0;
          if (!crystal) {
            const CVec2 e = path.jones * e_s;
            for (int o = 0; o < n_out; ++o) t += std::norm(outputs[o].x * e.x + outputs[o].y * e.y);
          } else {
            const ModalPoint m = fit.at(L.nm[i], scale);
            glm::dvec2 e1 = m.e1, e2 = m.e2;
            double det = e1.x * e2.y - e1.y * e2.x;
            if (std::fabs(det) < 1e-9) {
              e2 = {-e1.y, e1.x};
              det = 1.0;
            }
            const glm::dvec2 d1{e2.y / det, -e2.x / det}, d2{-e1.y / det, e1.x / det};
            const cd a1 = m.t1 * (d1.x * e_s.x + d1.y * e_s.y), a2 = m.t2 * (d2.x * e_s.x + d2.y * e_s.y);
            const CVec2 f1 = path.jones * CVec2{a1 * e1.x, a1 * e1.y};
            const CVec2 f2 = path.jones * CVec2{a2 * e2.x, a2 * e2.y};
            const double lambda = L.nm[i], two_pi = 2.0 * std::numbers::pi;
            const double phi = two_pi * m.gamma_nm / lambda;
            const double dphi = two_pi * (m.dgamma_dnm / lambda - m.gamma_nm / (lambda * lambda));
            const double x = 0.5 * dphi * L.band_nm;
            const double sinc = std::fabs(x) < 1e-8 ? 1.0 : std::sin(x) / x;
            for (int o = 0; o < n_out; ++o) {
              const cd c1 = outputs[o].x * f1.x + outputs[o].y * f1.y;
              const cd c2 = outputs[o].x * f2.x + outputs[o].y * f2.y;
              // fast mode phase −φ/2, slow +φ/2: |c1 e^{−iφ/2} + c2 e^{iφ/2}|², band-averaged.
              t += std::norm(c1) + std::norm(c2) + 2.0 * std::real(c1 * std::conj(c2) * std::polar(1.0, -phi)) * sinc;
            }
          }
          if (std::isfinite(t)) xyz += L.weight[i] * std::max(0.0, t);
        }
        img[static_cast<std::size_t>(px)] += xyz / axial;
      }
    }
  });
  std::vector<glm::dvec3> sum(static_cast<std::size_t>(W) * H, glm::dvec3(0.0));
  for (const auto& img : acc)
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += img[i];
  StrategyResult r;
  r.xyz.resize(sum.size() * 3);
  for (std::size_t i = 0; i < sum.size(); ++i)
    for (int c = 0; c < 3; ++c) r.xyz[3 * i + c] = std::isfinite(sum[i][c]) ? static_cast<float>(sum[i][c]) : 0.0f;
  r.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  r.wavelengths = L.n;
  r.model_report = "bench-side SML condenser + objective (paper lens, N-BK7), dT = " +
                   std::to_string(scene.optics.lens_depth) + (scene.optics.fresnel == FresnelModel::Schlick ? ", Schlick" : ", Fresnel") +
                   ", ghosts splatted by back-focal-plane crossing; plate: renderer's modal fit, " +
                   std::to_string(L.n) + " bands";
  return r;
}

}  // namespace pmsim
