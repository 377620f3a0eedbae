#include "core/specimen/forward_response.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/base/units.h"
#include "core/spectrum/cie.h"
#include "core/specimen/forward_source.h"
#include "core/specimen/jones_path.h"
#include "core/specimen/specimen_random.h"
#include "core/spectrum/spectral_bands.h"

namespace pmsim {

namespace {

// λ within a band: K values a pass, stratified, one per chroma node in a 2×2 pattern (as the
// forward image renderer, forward_plane_light.cpp).
constexpr int kLambdasPerBand = 4;
constexpr int kDefaultChromaPeriod = 4;
constexpr double kReferenceNm = 555.0;

// The grid a pass traces onto: nx × ny points of `um` µm (point (i, j) at frame offset
// (i − (nx − 1)/2, (ny − 1)/2 − j)·um), its chroma nodes every `period` points, and (Disc) the
// radius in points beyond which no source is traced.
struct PassGrid {
  int nx = 0, ny = 0;
  double um = 1.0;
  int period = kDefaultChromaPeriod;
  int cnx = 0, cny = 0;
  double disc_radius = 0.0;  // 0: the whole rectangle
};

PassGrid make_grid(int nx, int ny, double um, int period, double disc_radius) {
  PassGrid g;
  g.nx = nx;
  g.ny = ny;
  g.um = um;
  g.period = period;
  g.cnx = (nx - 1 + period - 1) / period + 1;
  g.cny = (ny - 1 + period - 1) / period + 1;
  g.disc_radius = disc_radius;
  return g;
}

// Sums of splatted Mueller blocks (12 numbers each) over a set of passes. In double: the splats
// arrive in any thread order, and double sums rounded to the response's floats come out the same
// whatever the order (a render is reproducible bit for bit).
struct Accumulators {
  std::vector<double> ref, ref_node, band_node;
  int passes = 0;
  void assign(const PassGrid& g, int nb) {
    ref.assign(std::size_t(g.nx) * g.ny * 12, 0.0);
    ref_node.assign(std::size_t(g.cnx) * g.cny * 12, 0.0);
    band_node.assign(std::size_t(g.cnx) * g.cny * std::size_t(nb) * 12, 0.0);
    passes = 0;
  }
};

// Each exit's share of its path's partially coherent Mueller matrix (core/optics/mueller.h): its
// own block plus γ_ef·Re K(J_e, J_f) with every other exit, so the shares add up to the path's
// total and each lands where its branch is imaged.
std::array<MuellerBlock, kMaxJonesLeaves> exit_shares(const JonesPath& p) {
  std::array<MuellerBlock, kMaxJonesLeaves> m{};
  for (int e = 0; e < p.n_exits; ++e) {
    const JonesExit& xe = p.exits[std::size_t(e)];
    m[std::size_t(e)] = mueller_cross_block(xe.jones, xe.jones);
    for (int f = 0; f < p.n_exits; ++f) {
      if (f == e) continue;
      const JonesExit& xf = p.exits[std::size_t(f)];
      const glm::dvec3 dd = xe.dir - xf.dir;
      const double gamma = std::exp(-p.k0_crystal_um * glm::dot(dd, dd));
      if (gamma < 1e-12) continue;
      const MuellerBlock k = mueller_cross_block(xe.jones, xf.jones);
      for (std::size_t i = 0; i < 12; ++i) m[std::size_t(e)][i] += gamma * k[i];
    }
  }
  return m;
}

class ResponseTracer {
 public:
  ResponseTracer(const SpecimenScene& scene, const ResponseRenderOptions& o, const std::atomic<bool>* cancel)
      : scene_(scene), o_(o), cancel_(cancel), empty_({}, scene.mineral(), scene.liquid(), scene.glass(), scene.air(),
                                                      scene.layers()) {
    const PlaneLightOptions& l = o.light;
    mono_ = l.single_wavelength_nm > 0.0;
    nb_ = mono_ ? 1 : std::max(kCrossedPolarBands, l.bands);
    bands_ = spectral_bands(nb_, l.illuminant, !mono_);
    lambda_ref_ = mono_ ? l.single_wavelength_nm : kReferenceNm;
    na_ = l.objective_na;
    nac_ = effective_condenser_na(l.condenser_aperture_na);
    z_air_ = objective_focus_z_air_um(scene, l.focus_um);
    z_source_ = -scene.layers().slide_um - 5.0;
    cos_ = std::cos(-l.stage_rad);
    sin_ = std::sin(-l.stage_rad);
    const double tan_na = std::min(na_, 0.95) / std::sqrt(1.0 - std::min(na_, 0.95) * std::min(na_, 0.95));
    reach_um_ = (scene.layers().liquid_um + std::abs(l.focus_um) + 5.0) * tan_na + 2.0;
  }

  bool cancelled() const { return cancel_ && cancel_->load(std::memory_order_relaxed); }
  int bands() const { return nb_; }
  bool mono() const { return mono_; }
  double lambda_ref() const { return lambda_ref_; }
  const SpectralBands& spectral() const { return bands_; }

  PassRay pass_ray(double u1, double u2, double wavelength_nm) const {
    PassRay r;
    r.dir = cone_direction(nac_, u1, u2);
    r.wavelength_nm = wavelength_nm;
    // The exposure: the empty field's unpolarized transmittance is 1.
    const JonesPath p = trace(empty_, {0.0, 0.0, z_source_}, r);
    if (p.n_exits > 0) {
      r.shift = focal_point(p.exits[0], z_air_);
      r.empty_t = p.exits[0].power;
    }
    return r;
  }

  // The pass's rays: the reference λ, then K λ of each band.
  std::vector<PassRay> pass_rays(const SampleDims& d, bool with_bands) const {
    std::vector<PassRay> rays = {pass_ray(d.v[2], d.v[3], lambda_ref_)};
    if (mono_ || !with_bands) return rays;
    for (int b = 0; b < nb_; ++b)
      for (int k = 0; k < kLambdasPerBand; ++k) {
        const double u = d.v[4] + double(k) / kLambdasPerBand;
        rays.push_back(pass_ray(d.v[2], d.v[3],
                                bands_.lo_nm[std::size_t(b)] + bands_.width_nm[std::size_t(b)] * (u - std::floor(u))));
      }
    return rays;
  }

  // One pass over grid g with in-point jitter (jx, jy) ∈ [0, 1)²: every source point (with the
  // margin the farthest collected ray can land away) traces rays[0]; the chroma nodes' points
  // also one λ of each band (rays[1 + b·K + k], k = (I + 2J) mod K at node (I, J)).
  void run_pass(const PassGrid& g, double jx, double jy, const std::vector<PassRay>& rays, Accumulators& acc) const {
    const int P = g.period;
    const int m = P * (int(std::ceil(reach_um_ / g.um / P)) + 1);
    const double cx = 0.5 * (g.nx - 1), cy = 0.5 * (g.ny - 1);
    const bool with_bands = rays.size() > 1;
    tbb::parallel_for(tbb::blocked_range<int>(-m, g.ny + m), [&](const tbb::blocked_range<int>& rows) {
      for (int j = rows.begin(); j < rows.end(); ++j) {
        while (o_.hold && o_.hold() && !cancelled()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
        if (cancelled()) break;
        for (int i = -m; i < g.nx + m; ++i) {
          const double fx = i - cx + jx - 0.5, fy = cy - j - jy + 0.5;  // frame offset, points
          if (g.disc_radius > 0.0 && fx * fx + fy * fy > (g.disc_radius + m) * (g.disc_radius + m)) continue;
          const glm::dvec3 off = rotate_z({fx * g.um, fy * g.um, 0.0}, cos_, sin_);
          const glm::dvec2 q = o_.light.centre_um + glm::dvec2(off.x, off.y);
          const bool node = with_bands && (i % P + P) % P == 0 && (j % P + P) % P == 0;
          const int ni = node ? (i - (i % P + P) % P) / P : 0, nj = node ? (j - (j % P + P) % P) / P : 0;
          const std::size_t k_lambda = std::size_t(((ni + 2 * nj) % kLambdasPerBand + kLambdasPerBand) % kLambdasPerBand);
          const int n_rays = node ? 1 + nb_ : 1;
          for (int k = 0; k < n_rays; ++k) {
            const PassRay& r = k == 0 ? rays[0] : rays[1 + std::size_t(k - 1) * kLambdasPerBand + k_lambda];
            if (!(r.empty_t > 0.0)) continue;
            const glm::dvec2 start = q - r.shift;
            const JonesPath p = trace(scene_, {start.x, start.y, z_source_}, r);
            if (p.n_exits == 0) continue;
            const std::array<MuellerBlock, kMaxJonesLeaves> share = exit_shares(p);
            for (int e = 0; e < p.n_exits; ++e) {
              const JonesExit& x = p.exits[std::size_t(e)];
              if (std::abs(x.dir.z) < 1e-9) continue;
              const glm::dvec2 land = to_grid(focal_point(x, z_air_), g);
              splat(share[std::size_t(e)], 1.0 / r.empty_t, k, node, land, g, acc);
            }
          }
        }
      }
    });
  }

 private:
  JonesPath trace(const SpecimenScene& sc, const glm::dvec3& origin, const PassRay& r) const {
    JonesPathRequest q;
    q.forward = true;
    q.forward_jones = true;
    q.origin = origin;
    q.dir = r.dir;
    q.wavelength_nm = r.wavelength_nm;
    q.objective_sin_max = na_;
    return trace_specimen_jones(sc, q, nullptr);
  }

  // Grid coordinates (points, y down) of a specimen point.
  glm::dvec2 to_grid(const glm::dvec2& p, const PassGrid& g) const {
    const glm::dvec3 f = rotate_z({p.x - o_.light.centre_um.x, p.y - o_.light.centre_um.y, 0.0}, cos_, -sin_);
    return {f.x / g.um + 0.5 * (g.nx - 1), 0.5 * (g.ny - 1) - f.y / g.um};
  }

  // Reference rays (k = 0) go to every grid point with a tent of radius 1, and from the chroma
  // nodes' sources also to the nodes; band rays to the nodes (tent of radius 1 in node units).
  static void splat(const MuellerBlock& m, double scale, int k, bool node, const glm::dvec2& land, const PassGrid& g,
                    Accumulators& acc) {
    for (double v : m)
      if (!std::isfinite(v)) return;
    const auto add_to = [&](std::vector<double>& dst, std::size_t base, std::size_t i, double wt) {
      double* d = &dst[(base + i) * 12];
      for (std::size_t c = 0; c < 12; ++c) atomic_add(d[c], m[c] * scale * wt);
    };
    const glm::dvec2 land_node = land / double(g.period);
    if (k == 0) {
      tent_splat(land, 1, g.nx, g.ny, 0.0, [&](std::size_t i, double wt) { add_to(acc.ref, 0, i, wt); });
      if (node)
        tent_splat(land_node, 1, g.cnx, g.cny, 0.0, [&](std::size_t i, double wt) { add_to(acc.ref_node, 0, i, wt); });
      return;
    }
    const std::size_t nb = acc.band_node.size() / acc.ref_node.size();
    const std::size_t b = std::size_t(k - 1);
    tent_splat(land_node, 1, g.cnx, g.cny, 0.0, [&](std::size_t i, double wt) {
      double* d = &acc.band_node[(i * nb + b) * 12];
      for (std::size_t c = 0; c < 12; ++c) atomic_add(d[c], m[c] * scale * wt);
    });
  }

  const SpecimenScene& scene_;
  const ResponseRenderOptions& o_;
  const std::atomic<bool>* cancel_;
  const SpecimenScene empty_;
  bool mono_ = false;
  int nb_ = 1;
  SpectralBands bands_;
  double lambda_ref_ = kReferenceNm;
  double na_ = 0.25, nac_ = 0.03, z_air_ = 0.0, z_source_ = 0.0, cos_ = 1.0, sin_ = 0.0, reach_um_ = 0.0;
};

// The developed response of the passes in `parts` (their sums added, over their passes).
std::shared_ptr<SpecimenResponse> develop(const ResponseTracer& t, const ResponseRenderOptions& o, const PassGrid& g,
                                          const std::vector<const Accumulators*>& parts) {
  auto r = std::make_shared<SpecimenResponse>();
  const PlaneLightOptions& l = o.light;
  r->image_width = l.width;
  r->image_height = l.height;
  r->um_per_px = l.um_per_px;
  r->centre_um = l.centre_um;
  r->nx = g.nx;
  r->ny = g.ny;
  r->grid_um = g.um;
  r->frame_stage_rad = l.stage_rad;
  r->coverage = o.coverage;
  r->chroma_period = g.period;
  r->cnx = g.cnx;
  r->cny = g.cny;
  r->bands = t.spectral();
  r->illuminant = l.illuminant;
  r->single_wavelength_nm = t.mono() ? t.lambda_ref() : 0.0;
  r->white = illuminant_white_xyz(l.illuminant);
  r->model_report = o.model_report;
  int n = 0;
  for (const Accumulators* a : parts) n += a->passes;
  r->passes = n;
  if (n == 0) return r;
  const double inv = 1.0 / n;
  const auto mean_of = [&](auto member) {
    const std::size_t size = (parts[0]->*member).size();
    std::vector<float> v(size);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, size, 1 << 14), [&](const tbb::blocked_range<std::size_t>& rg) {
      for (std::size_t i = rg.begin(); i < rg.end(); ++i) {
        double sum = 0.0;
        for (const Accumulators* a : parts) sum += (a->*member)[i];
        v[i] = float(sum * inv);
      }
    });
    return v;
  };
  r->ref = mean_of(&Accumulators::ref);
  if (t.mono()) return r;
  const std::vector<float> ref_node = mean_of(&Accumulators::ref_node);
  r->delta = mean_of(&Accumulators::band_node);
  const std::size_t nodes = std::size_t(g.cnx) * g.cny, nb = std::size_t(t.bands());
  r->delta_xyz.assign(nodes * 3 * 12, 0.0f);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nodes, 256), [&](const tbb::blocked_range<std::size_t>& rg) {
    for (std::size_t q = rg.begin(); q < rg.end(); ++q)
      for (std::size_t b = 0; b < nb; ++b) {
        float* d = &r->delta[(q * nb + b) * 12];
        for (std::size_t c = 0; c < 12; ++c) d[c] -= ref_node[q * 12 + c];
        const glm::dvec3& w = r->bands.weight[b];
        for (std::size_t k = 0; k < 3; ++k)
          for (std::size_t c = 0; c < 12; ++c) r->delta_xyz[(q * 3 + k) * 12 + c] += float(w[int(k)] * d[c]);
      }
  });
  // The reference block carries the whole white: each band's value is M_ref + (M_b − M_ref).
  return r;
}

}  // namespace

RenderImage compose_progress(const ResponseProgress& p, const InstrumentSettings& instrument) {
  RenderImage img = p.response ? compose_response(*p.response, instrument) : RenderImage{};
  img.error_estimate = p.error_estimate;
  img.converged = p.converged;
  img.stopped = p.stopped;
  return img;
}

RenderImage render_response_image(const SpecimenScene& scene, const PlaneLightOptions& options,
                                  const std::function<void(const RenderImage&)>& progress, InterfaceCounters*,
                                  const std::atomic<bool>* cancel) {
  ResponseRenderOptions o;
  o.light = options;
  o.coverage = ResponseCoverage::Field;
  o.estimate_at.stage_rad = options.stage_rad;
  o.estimate_at.polarizer_rad = options.polarizer_rad;
  o.estimate_at.analyzer_in = options.analyzer_in;
  o.estimate_at.analyzer_rad = options.analyzer_rad;
  const auto compose = [&](const ResponseProgress& p) { return compose_progress(p, o.estimate_at); };
  const ResponseProgress last = render_specimen_response(
      scene, o, [&](const ResponseProgress& p) { if (progress) progress(compose(p)); }, cancel);
  return compose(last);
}

ResponseProgress render_specimen_response(const SpecimenScene& scene, const ResponseRenderOptions& o,
                                          const std::function<void(const ResponseProgress&)>& progress,
                                          const std::atomic<bool>* cancel) {
  if (o.light.scalar_tracer) throw std::invalid_argument("render_specimen_response: the polarization-exact tracer only");
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsed_ms = [&] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  };
  const PlaneLightOptions& l = o.light;
  const ResponseTracer tracer(scene, o, cancel);
  const int P = l.chroma_period > 0 ? l.chroma_period : kDefaultChromaPeriod;
  // Field: the image's pixels; Disc: a square holding the circle through the image's corners,
  // of the image's parity so that at the frame's angle its points are the image's pixel centres.
  int nx = l.width, ny = l.height;
  double radius = 0.0;
  if (o.coverage == ResponseCoverage::Disc) {
    const double diag = std::sqrt(double(l.width) * l.width + double(l.height) * l.height);
    radius = 0.5 * diag + 1.5;
    // The margin a whole number of λ-pattern blocks (K·P points: chroma nodes and their 2×2 λ
    // pattern), so that at the frame's angle the Disc traces the Field's rays and its chroma nodes
    // sit where the Field's do: the two give one image there, and a turned stage differs from a
    // fresh render only by the resampling and the chroma subgrid's other phase.
    const int block = kLambdasPerBand * P;
    const auto margin = [&](int side) { return block * int(std::ceil(0.5 * (diag + 3.0 - side) / block)); };
    nx = l.width + 2 * margin(l.width);
    ny = l.height + 2 * margin(l.height);
  }
  const PassGrid grid = make_grid(nx, ny, l.um_per_px, P, radius);
  SampleDims shift;
  {
    SpecimenRandom rng(l.seed ^ 0xf0e1d2c3b4a59687ull);
    for (double& v : shift.v) v = rng.uniform();
  }
  ResponseProgress state;
  const auto finish = [&](const char* why) {
    state.stopped = why;
    if (progress) progress(state);
    return state;
  };

  int previewed = 0;  // the preview counts as a pass (as the image renderers count it)
  // The preview: about 48 points across, one pass, the bands on every other point (colour from
  // the first image: a grey preview of a coloured field would mislead).
  const int f = l.preview_factor > 1 ? std::max(l.preview_factor, int(std::ceil(std::max(nx, ny) / 48.0))) : 0;
  if (f > 1 && l.width >= 2 * f && l.height >= 2 * f) {
    const PassGrid pg = make_grid((nx + f - 1) / f + 1, (ny + f - 1) / f + 1, l.um_per_px * f, 2, radius / f);
    Accumulators pa;
    pa.assign(pg, tracer.bands());
    const SampleDims d = kronecker(shift, 0);
    tracer.run_pass(pg, d.v[0], d.v[1], tracer.pass_rays(d, true), pa);
    if (tracer.cancelled()) return finish("cancelled");
    pa.passes = 1;
    auto r = develop(tracer, o, pg, {&pa});
    r->time_ms = elapsed_ms();
    r->samples_per_pixel = 0.0;
    state.response = r;
    state.preview = true;
    previewed = 1;
    if (progress) progress(state);
  }

  Accumulators half[2];
  half[0].assign(grid, tracer.bands());
  half[1].assign(grid, tracer.bands());
  const double traces = tracer.mono() ? 1.0 : 1.0 + double(tracer.bands()) / (P * P);
  const int passes = std::max(1, int(std::ceil(l.spp / traces - 1e-9)));
  state.preview = false;
  for (int pass = 0; pass < passes; ++pass) {
    const SampleDims d = kronecker(shift, pass + 1);  // point 0 went to the preview
    Accumulators& acc = half[pass % 2];
    tracer.run_pass(grid, d.v[0], d.v[1], tracer.pass_rays(d, true), acc);
    if (tracer.cancelled()) return finish("cancelled");
    ++acc.passes;
    const int done = pass + 1;
    auto r = develop(tracer, o, grid, {&half[0], &half[1]});
    // Split half: the even and odd passes' responses composed at the estimate's settings, their
    // mean CIEDE2000 (not halved: conservative, as the image renderers).
    if (done >= 2 && done % 2 == 0) {
      const auto a = develop(tracer, o, grid, {&half[0]}), b = develop(tracer, o, grid, {&half[1]});
      state.error_estimate = response_difference_de2000(*a, *b, o.estimate_at);
    }
    r->samples_per_pixel = done * traces;
    r->passes = done + previewed;
    r->time_ms = elapsed_ms();
    state.response = r;
    state.converged = l.tolerance_de2000 > 0.0 && state.error_estimate && *state.error_estimate < l.tolerance_de2000;
    if (state.converged) return finish("tolerance");
    if (done == passes) return finish("cap");
    if (progress) progress(state);
  }
  return finish("cap");
}

}  // namespace pmsim
