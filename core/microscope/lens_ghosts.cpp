#include "core/microscope/lens_ghosts.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "core/crystal/plate.h"
#include "core/lens/lens.h"
#include "core/lens/lens_tracer.h"
#include "core/microscope/evaluation_plan.h"
#include "core/microscope/optical_train.h"
#include "core/microscope/sample_source.h"
#include "core/microscope/view_geometry.h"
#include "core/spectrum/cie.h"

namespace pmsim {

namespace {
constexpr double kLensNm = kPhysicalLensNm;
constexpr int kBands = 8;                    // 50 nm: the ghost is ~0.2 % of the light
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
JonesMatrix path_jones(const glm::dvec3& k_in, const glm::dvec3& k_out, const glm::dvec3& s_hat,
                       complexd a_s, complexd a_p) {
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

}  // namespace

const std::vector<LensGhostPath>& LensGhostTable::at(double sin_theta) const {
  const double u = std::clamp(sin_theta / max_sin, 0.0, 1.0) * (kSamples - 1);
  return paths[std::min(static_cast<int>(std::lround(u)), kSamples - 1)];
}

const LensGhostTable& lens_ghost_table(int depth, FresnelModel fresnel) {
  static std::mutex mu;
  static std::map<std::pair<int, FresnelModel>, std::unique_ptr<LensGhostTable>> cache;
  std::lock_guard<std::mutex> lock(mu);
  auto& slot = cache[{depth, fresnel}];
  if (!slot) slot = std::make_unique<LensGhostTable>(trace_ghosts(depth, fresnel));
  return *slot;
}

LensGhostImage lens_ghost_image(const EvaluationPlan& plan, const std::atomic<bool>* cancel) {
  LensGhostImage img;
  const Scene& sc = plan.scene();
  if (!plan.lenses() || sc.optics.lens_depth < 2 || sc.mode != ViewMode::Cono || !sc.bertrand_in) return img;
  const LensGhostTable& table = lens_ghost_table(sc.optics.lens_depth, sc.optics.fresnel);
  const int W = plan.width(), H = plan.height();
  const int stride = std::max(1, (std::max(W, H) + kMaxGridSide - 1) / kMaxGridSide);
  const int GW = (W + stride - 1) / stride, GH = (H + stride - 1) / stride;
  const double half = 0.5 * std::min(W, H);

  // Spectral bands (or the single line) with their observer weights, Y = 1 for T ≡ 1.
  std::vector<double> nm;
  std::vector<glm::dvec3> weight;
  const bool mono = sc.render.single_wavelength_nm > 0;
  double band_nm = 0.0;
  if (mono) {
    nm = {sc.render.single_wavelength_nm};
    weight = {glm::dvec3(1.0)};
  } else {
    band_nm = (kVisibleMaxNm - kVisibleMinNm) / kBands;
    glm::dvec3 sum(0.0);
    for (int b = 0; b < kBands; ++b) {
      const double lo = kVisibleMinNm + b * band_nm;
      glm::dvec3 w(0.0);
      for (int s = 0; s < 50; ++s) w += observer_weight(sc.illuminant, lo + (s + 0.5) * band_nm / 50);
      nm.push_back(lo + 0.5 * band_nm);
      weight.push_back(w);
      sum += w;
    }
    const glm::dvec3 scale = illuminant_white_xyz(sc.illuminant) / sum;
    for (glm::dvec3& w : weight) w *= scale;
  }
  std::vector<TrainState> trains;
  for (double l : nm) trains.push_back(make_train(sc, plan.compensator(), l));

  // The domain under the field centre (as conoscopic_figure_view's units).
  const EvalUnit* unit0 = nullptr;
  for (const EvalUnit& u : plan.units())
    if (!u.cone) {
      unit0 = &u;
      break;
    }
  if (!unit0) return img;
  const int dom = unit0->domain;
  const double thickness = unit0->thickness_um;
  const bool crystal = plan.domains()[dom].crystal && thickness > 0;
  std::vector<PreparedPlate> prepared(nm.size());
  if (crystal)
    for (std::size_t b = 0; b < nm.size(); ++b) {
      prepared[b] = plan.prepare(dom, nm[b]);
      prepared[b].thickness_um = thickness;
    }
  auto sample_jones = [&](std::size_t b, const glm::dvec3& k) {
    return crystal ? plate_jones(prepared[b], k) : JonesMatrix::identity();
  };

  // Source directions at the coarse cell centres.
  const double two_pi = 2.0 * std::numbers::pi;
  std::vector<glm::dvec3> grid(static_cast<std::size_t>(GW) * GH * 2, glm::dvec3(0.0));  // [obj, cond]
  std::vector<std::vector<std::pair<int, glm::dvec3>>> splats(GH);  // objective: per source row
  std::vector<int> row_paths(GH, 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, GH, 2), [&](const tbb::blocked_range<int>& r) {
    for (int cy = r.begin(); cy != r.end(); ++cy) {
      if (cancel && cancel->load(std::memory_order_relaxed)) return;
      for (int cx = 0; cx < GW; ++cx) {
        const double px = std::min((cx + 0.5) * stride, W - 0.5), py = std::min((cy + 0.5) * stride, H - 0.5);
        glm::dvec3 k;
        if (!bfp_direction(sc, field_from_pixel(W, H, px, py), k)) continue;
        const double sin_t = std::hypot(k.x, k.y);
        const double cphi = sin_t > 1e-12 ? k.x / sin_t : 1.0, sphi = sin_t > 1e-12 ? k.y / sin_t : 0.0;
        const glm::dvec3 s_hat{-sphi, cphi, 0.0};
        const auto& paths = table.at(sin_t);
        row_paths[cy] += static_cast<int>(paths.size());
        glm::dmat2 lc, lo;
        plan.lens_jones(k, lc, lo);
        // Per path: exit direction, target cell, and per band the complex amplitudes.
        struct Hit {
          glm::dvec3 kg;
          double gx, gy;  // target in coarse-grid coordinates
          bool in_objective, in_condenser;
        };
        std::vector<Hit> hits;
        for (const LensGhostPath& g : paths) {
          Hit h;
          h.kg = rotate_z(g.dir, cphi, sphi);
          const double sg = std::hypot(h.kg.x, h.kg.y);
          const double rho = sg / sc.objective.na;
          h.in_objective = rho <= 1.0;
          h.in_condenser = sg <= sc.condenser.na;
          const double fx = sg > 1e-12 ? rho * h.kg.x / sg : 0.0, fy = sg > 1e-12 ? rho * h.kg.y / sg : 0.0;
          h.gx = (fx * half + 0.5 * W) / stride - 0.5;
          h.gy = (0.5 * H - fy * half) / stride - 0.5;
          hits.push_back(h);
        }
        for (std::size_t b = 0; b < nm.size(); ++b) {
          const TrainState& t = trains[b];
          const JonesMatrix J = sample_jones(b, k);
          const double lam_mm = nm[b] * 1e-6;
          std::vector<complexd> amp_obj(paths.size() * t.outputs), amp_cond(paths.size() * t.outputs);
          for (std::size_t i = 0; i < paths.size(); ++i) {
            const LensGhostPath& g = paths[i];
            const double phase = two_pi * g.optical_path_mm / lam_mm;
            const complexd es = std::polar(1.0, phase - g.delta_s_rad), ep = std::polar(1.0, phase - g.delta_p_rad);
            // s/p eigen-amplitudes of the path (sign included): field along ŝ_out, p̂_out.
            const glm::dvec3 kg0 = g.dir, s0{0.0, 1.0, 0.0};
            const complexd a_s = es * glm::dot(g.field_s, s0);
            const complexd a_p = ep * glm::dot(g.field_p, glm::cross(s0, kg0));
            // Objective ghost: condenser (depth 0) → sample along k → ghost path to k_g.
            if (hits[i].in_objective) {
              const JonesMatrix G = path_jones(k, hits[i].kg, s_hat, a_s, a_p);
              // The Bertrand side sees the ghost in the lab frame: the aplanatic mapping of k_g.
              const JonesMatrix M = jones_from_real(glm::transpose(aplanatic_frame(hits[i].kg))) * G * J * jones_from_real(lc);
              for (int o = 0; o < t.outputs; ++o) amp_obj[i * t.outputs + o] = jones_output(t, M, o).x;
            }
            // Condenser ghost (reciprocal path): aperture direction k_g → specimen along k →
            // sample → objective (depth 0) → this cell.
            if (hits[i].in_condenser) {
              const JonesMatrix G = path_jones(hits[i].kg, k, s_hat, a_s, a_p);
              const JonesMatrix M = jones_from_real(lo) * J * G * jones_from_real(aplanatic_frame(hits[i].kg));
              for (int o = 0; o < t.outputs; ++o) amp_cond[i * t.outputs + o] = jones_output(t, M, o).x;
            }
          }
          // Objective: paths of this ch landing in the same cell add coherently (cross terms
          // band-averaged); each group's intensity is spread bilinearly around its target.
          std::vector<char> done(paths.size(), 0);
          for (std::size_t i = 0; i < paths.size(); ++i) {
            if (done[i] || !hits[i].in_objective) continue;
            const long ci = std::lround(hits[i].gx), cj = std::lround(hits[i].gy);
            double I = 0.0;
            std::vector<std::size_t> group;
            for (std::size_t j = i; j < paths.size(); ++j)
              if (!done[j] && hits[j].in_objective && std::lround(hits[j].gx) == ci && std::lround(hits[j].gy) == cj) {
                group.push_back(j);
                done[j] = 1;
              }
            for (int o = 0; o < t.outputs; ++o)
              for (std::size_t a = 0; a < group.size(); ++a)
                for (std::size_t c = a; c < group.size(); ++c) {
                  const complexd x = amp_obj[group[a] * t.outputs + o], y = amp_obj[group[c] * t.outputs + o];
                  if (a == c) {
                    I += std::norm(x);
                  } else {
                    const double dO_nm = (paths[group[a]].optical_path_mm - paths[group[c]].optical_path_mm) * 1e6;
                    I += 2.0 * std::real(x * std::conj(y)) *
                         sinc(std::numbers::pi * dO_nm * band_nm / (nm[b] * nm[b]));
                  }
                }
            const glm::dvec3 v = std::max(0.0, I) * weight[b];
            const double gx = hits[i].gx, gy = hits[i].gy;
            const int x0 = static_cast<int>(std::floor(gx)), y0 = static_cast<int>(std::floor(gy));
            const double fx = gx - x0, fy = gy - y0;
            for (int dy = 0; dy < 2; ++dy)
              for (int dx = 0; dx < 2; ++dx) {
                const int x = x0 + dx, y = y0 + dy;
                const double w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy);
                if (x < 0 || y < 0 || x >= GW || y >= GH || w <= 0) continue;
                splats[cy].push_back({y * GW + x, v * w});
              }
          }
          // Condenser: different aperture points are different ch: intensities add here.
          double Ic = 0.0;
          for (const complexd& a : amp_cond) Ic += std::norm(a);
          grid[(static_cast<std::size_t>(cy) * GW + cx) * 2 + 1] += Ic * weight[b];
        }
      }
    }
  });
  if (cancel && cancel->load()) return img;
  for (int cy = 0; cy < GH; ++cy) {
    img.paths += row_paths[cy];
    for (const auto& [cell, v] : splats[cy]) grid[static_cast<std::size_t>(cell) * 2] += v;
  }

  // Bilinear upsampling to the pixels inside the back-focal-plane disk.
  img.xyz.assign(static_cast<std::size_t>(W) * H * 3, 0.0f);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const glm::dvec2 f = field_from_pixel(W, H, x + 0.5, y + 0.5);
      if (std::hypot(f.x, f.y) > 1.0) continue;
      const double gx = std::clamp((x + 0.5) / stride - 0.5, 0.0, GW - 1.0);
      const double gy = std::clamp((y + 0.5) / stride - 0.5, 0.0, GH - 1.0);
      const int x0 = std::min(static_cast<int>(gx), std::max(0, GW - 2)), y0 = std::min(static_cast<int>(gy), std::max(0, GH - 2));
      const double fx = GW > 1 ? gx - x0 : 0.0, fy = GH > 1 ? gy - y0 : 0.0;
      glm::dvec3 v[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const int xx = std::min(x0 + dx, GW - 1), yy = std::min(y0 + dy, GH - 1);
          const double w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy);
          for (int e = 0; e < 2; ++e) v[e] += w * grid[(static_cast<std::size_t>(yy) * GW + xx) * 2 + e];
        }
      img.objective_energy += v[0].y;
      img.condenser_energy += v[1].y;
      const glm::dvec3 sum = v[0] + v[1];
      for (int c = 0; c < 3; ++c) {
        const double val = mono ? sum.y : sum[c];
        img.xyz[(static_cast<std::size_t>(y) * W + x) * 3 + c] = std::isfinite(val) ? static_cast<float>(val) : 0.0f;
      }
    }
  return img;
}

}  // namespace pmsim
