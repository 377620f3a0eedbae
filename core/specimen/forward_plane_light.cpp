#include "core/specimen/forward_plane_light.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/base/units.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"
#include "core/specimen/forward_source.h"
#include "core/specimen/jones_path.h"
#include "core/specimen/plane_light_passes.h"
#include "core/spectrum/spectral_bands.h"
#include "core/specimen/specimen_random.h"

namespace pmsim {

namespace {

// The bands' rays start from every P-th source point in x and y and are splatted with a tent of
// radius P: the colour's difference to the reference at 1/P of the resolution (still exact where
// light is only translated), every band every pass. Plane light: 8 bands on P = 3, 8/9 of a trace
// a pixel; analyzer in: 32 bands (interference colours) on P = 4, 2 traces a pixel.
constexpr int kChromaPeriodPlane = 3, kChromaPeriodCrossed = 4;
// λ within a band: K values a pass, stratified (a shared jitter + k/K), one per subgrid point in
// a 2×2 pattern, so a pixel's colour averages sin²(πΓ/λ) over K points of each band a pass.
constexpr int kLambdasPerBand = 4;

// Tent weights of radius r pixels on pixel centres (forward_source.h).
template <class Add>
void tent(const glm::dvec2& f, int r, int ww, int hh, const Add& add) {
  tent_splat(f, r, ww, hh, 0.5, add);
}

// One forward render's state, shared by its phases: the spectrum, the condenser's and the
// objective's geometry, the empty stack that says where a pass's direction lands, the source
// grid, and the passes' accumulators.
struct ForwardRender {
  const SpecimenScene& scene;
  const PlaneLightOptions& o;
  InterfaceCounters* counters;
  const std::atomic<bool>* cancel;
  std::mutex counter_mutex;

  bool mono;
  int nb, chroma_period;
  SpectralBands bands;
  glm::dvec3 white;
  double lambda_ref;

  double na, nac, z_air, z_source;
  double c, s;  // cos, sin of −stage
  glm::dvec3 vibration, analyzer;
  glm::dvec2 centre;
  // The empty stack: the shift and transmittance of a pass's direction at its λ (plane faces:
  // one ray says it for every start point).
  const SpecimenScene empty;
  double reach_um;
  int w, h;
  std::size_t npx;
  SampleDims shift;  // the passes' Kronecker sequence's random shift

  // Accumulators per half (even/odd passes): the reference's splats; the subgrid's reference
  // splats and each band's, both with the chroma tent (a band's value is the reference plus the
  // difference of those two).
  std::vector<double> ref_acc[2], ref_sub[2], band_sub[2];

  ForwardRender(const SpecimenScene& scene_, const PlaneLightOptions& o_, InterfaceCounters* counters_,
                const std::atomic<bool>* cancel_)
      : scene(scene_),
        o(o_),
        counters(counters_),
        cancel(cancel_),
        mono(o.single_wavelength_nm > 0.0),
        nb(mono ? 1 : std::max(o.analyzer_in ? kCrossedPolarBands : 1, o.bands)),
        chroma_period(o.chroma_period > 0 ? o.chroma_period
                      : o.analyzer_in     ? kChromaPeriodCrossed
                                          : kChromaPeriodPlane),
        bands(spectral_bands(nb, o.illuminant, !mono)),
        white(illuminant_white_xyz(o.illuminant)),
        lambda_ref(mono ? o.single_wavelength_nm : 555.0),
        na(o.objective_na),
        nac(effective_condenser_na(o.condenser_aperture_na)),
        z_air(objective_focus_z_air_um(scene, o.focus_um)),
        z_source(-scene.layers().slide_um - 5.0),  // in the air below the slide
        c(std::cos(-o.stage_rad)),
        s(std::sin(-o.stage_rad)),
        vibration(rotate_z({std::cos(o.polarizer_rad), std::sin(o.polarizer_rad), 0.0}, c, s)),
        analyzer(rotate_z({std::cos(o.analyzer_rad), std::sin(o.analyzer_rad), 0.0}, c, s)),
        centre(o.centre_um),
        empty({}, scene.mineral(), scene.liquid(), scene.glass(), scene.air(), scene.layers()),
        reach_um(collection_reach_um()),
        w(o.width),
        h(o.height),
        npx(std::size_t(w) * h) {
    SpecimenRandom rng(o.seed ^ 0xf0e1d2c3b4a59687ull);
    for (double& v : shift.v) v = rng.uniform();
  }

  bool cancelled() const { return cancel_raised(cancel); }

  // How far from its start's image point a collected ray can land: a deviation within the
  // objective's NA over the specimen's depth seen from the focal plane, plus the defocus.
  double collection_reach_um() const {
    const SpecimenLayers& L = scene.layers();
    const double tan_na = std::min(na, 0.95) / std::sqrt(1.0 - std::min(na, 0.95) * std::min(na, 0.95));
    return (L.liquid_um + std::abs(o.focus_um) + 5.0) * tan_na + 2.0;
  }

  JonesPath trace(const SpecimenScene& sc, const glm::dvec3& origin, const PassRay& r, bool with_analyzer,
                  InterfaceCounters* ic) const {
    JonesPathRequest q;
    q.forward = true;
    q.origin = origin;
    q.dir = r.dir;
    q.wavelength_nm = r.wavelength_nm;
    q.starts = 1;
    q.start_vibration = vibration;
    q.polarizer = vibration;
    q.objective_sin_max = na;
    q.forward_analyzer_in = with_analyzer;
    q.forward_analyzer = analyzer;
    return trace_specimen_jones(sc, q, ic);
  }

  PassRay pass_ray(double u1, double u2, double wavelength_nm) const {
    PassRay r;
    r.dir = cone_direction(nac, u1, u2);
    r.wavelength_nm = wavelength_nm;
    // The exposure: the empty field with the analyzer out is 1.
    const JonesPath p = trace(empty, {0.0, 0.0, z_source}, r, false, nullptr);
    if (p.n_exits > 0) {
      r.shift = focal_point(p.exits[0], z_air);
      r.empty_t = p.exits[0].power;
    }
    return r;
  }

  // Specimen point of image position (fx, fy) (pixels from the top left) on a grid of ww × hh
  // pixels of `um` µm, and back.
  glm::dvec2 to_specimen(double fx, double fy, double um, int ww, int hh) const {
    const glm::dvec3 p = rotate_z({(fx - 0.5 * ww) * um, (0.5 * hh - fy) * um, 0.0}, c, s);
    return centre + glm::dvec2(p.x, p.y);
  }
  glm::dvec2 to_image(const glm::dvec2& q, double um, int ww, int hh) const {
    const glm::dvec3 f = rotate_z({q.x - centre.x, q.y - centre.y, 0.0}, c, -s);
    return glm::dvec2(f.x / um + 0.5 * ww, 0.5 * hh - f.y / um);
  }

  // One pass over a ww × hh grid: every source pixel (with the margin) traces the reference
  // rays[0], those of the subgrid of period chroma_period also one ray of each band, rays[1 + b·K
  // + k] with k = (i + 2j) mod K at subgrid point (i, j) (K = kLambdasPerBand: each 2×2 block of
  // subgrid points takes the band's K stratified λ); each collected branch goes to
  // `splat(band + 1 or 0 for the reference, on the subgrid, image position, weight)`.
  void run_pass(int ww, int hh, double um, double jx, double jy, const std::vector<PassRay>& rays,
                const std::function<void(int, bool, const glm::dvec2&, double)>& splat) {
    const int m = chroma_period * (int(std::ceil(reach_um / um / chroma_period)) + 1);
    const int sw = ww + 2 * m, sh = hh + 2 * m;
    tbb::parallel_for(tbb::blocked_range<int>(0, sh), [&](const tbb::blocked_range<int>& rows) {
      InterfaceCounters local;
      InterfaceCounters* lc = counters ? &local : nullptr;
      for (int sy = rows.begin(); sy < rows.end(); ++sy) {
        if (cancelled()) break;
        for (int sx = 0; sx < sw; ++sx) {
          const glm::dvec2 q = to_specimen(sx - m + jx, sy - m + jy, um, ww, hh);
          const bool sub = sx % chroma_period == 0 && sy % chroma_period == 0;
          const std::size_t k_lambda =
              std::size_t((sx / chroma_period + 2 * (sy / chroma_period)) % kLambdasPerBand);
          const std::size_t n_rays = sub ? 1 + (rays.size() - 1) / kLambdasPerBand : 1;
          for (std::size_t k = 0; k < n_rays; ++k) {
            const PassRay& r = k == 0 ? rays[0] : rays[1 + (k - 1) * kLambdasPerBand + k_lambda];
            if (!(r.empty_t > 0.0)) continue;
            const glm::dvec2 start = q - r.shift;
            const JonesPath p = trace(scene, {start.x, start.y, z_source}, r, o.analyzer_in, lc);
            for (int e = 0; e < p.n_exits; ++e) {
              const JonesExit& x = p.exits[std::size_t(e)];
              const double v = x.power / r.empty_t;
              // (< 0: an exit's share of a coherent sum with the analyzer in)
              if (v == 0.0 || !std::isfinite(v) || std::abs(x.dir.z) < 1e-9) continue;
              splat(int(k), sub, to_image(focal_point(x, z_air), um, ww, hh), v);
            }
          }
        }
      }
      if (counters) {
        std::lock_guard<std::mutex> lock(counter_mutex);
        counters->add(local);
      }
    });
  }

  // The preview: 1/f of the size, one pass at λ_ref, grey, spread bilinearly. False: cancelled
  // (img is to be returned as it is).
  bool preview(RenderImage& img, const RenderClock& clock, const std::function<void(const RenderImage&)>& progress) {
    const glm::dvec3 open_xyz = mono ? white : bands.sum;
    const glm::dvec3 open_rgb = mono ? glm::dvec3(1.0) : xyz_to_linear_srgb(bands.sum);
    // At most ~80 source pixels across (a 512² image: 1/7), so that it comes within 50 ms on 2
    // idle cores through the granite slab's 1.5 M triangles (measured at 512²: 1/6 took 51 ms wall,
    // 116 ms CPU).
    const int f = o.preview_factor > 1 ? std::max(o.preview_factor, int(std::ceil(std::max(w, h) / 80.0))) : 0;
    if (!(f > 1 && w >= 2 * f && h >= 2 * f)) return true;
    const int cw = (w + f - 1) / f, ch = (h + f - 1) / f;
    const double cum = o.um_per_px * double(w) / cw;
    std::vector<double> coarse(std::size_t(cw) * ch, 0.0);
    const SampleDims d = kronecker(shift, 0);
    run_pass(cw, ch, cum, d.v[0], d.v[1], {pass_ray(d.v[2], d.v[3], lambda_ref)},
             [&](int, bool, const glm::dvec2& p, double v) {
               tent(p, 1, cw, ch, [&](std::size_t i, double wt) { atomic_add(coarse[i], v * wt); });
             });
    return show_preview(coarse, cw, ch, f, open_xyz, open_rgb, img, clock, progress, cancel);
  }

  void allocate_accumulators() {
    for (auto& r : ref_acc) r.assign(npx, 0.0);
    if (!mono)
      for (int hf = 0; hf < 2; ++hf) {
        ref_sub[hf].assign(npx, 0.0);
        band_sub[hf].assign(npx * std::size_t(nb), 0.0);
      }
  }

  // A pass's rays: the reference direction at λ_ref, then each band's at its K stratified λ.
  std::vector<PassRay> pass_rays(const SampleDims& d) const {
    std::vector<PassRay> rays = {pass_ray(d.v[2], d.v[3], lambda_ref)};
    if (!mono)
      for (int b = 0; b < nb; ++b)
        for (int k = 0; k < kLambdasPerBand; ++k) {
          const double u = d.v[4] + double(k) / kLambdasPerBand;
          rays.push_back(pass_ray(d.v[2], d.v[3],
                                  bands.lo_nm[std::size_t(b)] + bands.width_nm[std::size_t(b)] * (u - std::floor(u))));
        }
    return rays;
  }

  // Pass `pass` over the full grid, splatted into the pass's half: the reference with the pixel
  // tent (and the subgrid's again with the chroma tent), the bands with the chroma tent.
  void trace_pass(int pass) {
    const int half = pass % 2;
    const SampleDims d = kronecker(shift, pass + 1);  // point 0 went to the preview
    const std::vector<PassRay> rays = pass_rays(d);
    double* ref = ref_acc[half].data();
    double* rsub = mono ? nullptr : ref_sub[half].data();
    double* bsub = mono ? nullptr : band_sub[half].data();
    run_pass(w, h, o.um_per_px, d.v[0], d.v[1], rays, [&](int k, bool sub, const glm::dvec2& p, double v) {
      if (k == 0) {
        tent(p, 1, w, h, [&](std::size_t i, double wt) { atomic_add(ref[i], v * wt); });
        if (sub && rsub) tent(p, chroma_period, w, h, [&](std::size_t i, double wt) { atomic_add(rsub[i], v * wt); });
      } else {
        const std::size_t b = std::size_t(k - 1);
        tent(p, chroma_period, w, h,
             [&](std::size_t i, double wt) { atomic_add(bsub[i * std::size_t(nb) + b], v * wt); });
      }
    });
  }

  // One half's (0, 1) or both halves' (2) colour of pixel pix after `passes` passes.
  glm::dvec3 develop(std::size_t pix, int passes, int half) const {
    const int h0 = half == 2 ? 0 : half, h1 = half == 2 ? 1 : half;
    int n = 0;
    double ref = 0.0, sub = 0.0;
    for (int hh = h0; hh <= h1; ++hh) {
      n += (passes + 1 - hh) / 2;
      ref += ref_acc[hh][pix];
      if (!mono) sub += ref_sub[hh][pix];
    }
    if (n == 0) return glm::dvec3(0.0);
    if (mono) return std::max(0.0, ref / n) * white;
    glm::dvec3 xyz(0.0);
    for (int b = 0; b < nb; ++b) {
      double band = 0.0;
      for (int hh = h0; hh <= h1; ++hh) band += band_sub[hh][pix * std::size_t(nb) + std::size_t(b)];
      // ≥ 0: the splats of a coherent sum's shares and the control variate can undershoot 0 by noise.
      xyz += std::max(0.0, (ref + band - sub) / n) * bands.weight[std::size_t(b)];
    }
    return xyz;
  }

  void develop_image(RenderImage& img, int done) const {
    develop_pixels(
        img, npx, 1024, [](std::size_t pix) { return pix; }, [&](std::size_t pix) { return develop(pix, done, 2); },
        mono, white);
  }

  // Split half, as render_plane_light: the halves' mean CIEDE2000 (not halved: conservative),
  // over at most 65536 pixels.
  std::optional<double> split_half_estimate(int done) const {
    if (done >= 2 && done % 2 == 0)
      return split_half_de2000(npx, [&](std::size_t pix, int hf) { return develop(pix, done, hf); }, white);
    return std::nullopt;
  }
};

}  // namespace

std::string forward_model_report(bool analyzer_in) {
  return analyzer_in ? "forward-traced refraction from the condenser (Embree, exact Fresnel, eigenmode splitting, "
                       "coherent sum at the analyzer, tent splats), analyzer in"
                     : "forward-traced refraction from the condenser (Embree, exact Fresnel, eigenmode splitting, "
                       "tent splats), plane-polarized light";
}

RenderImage render_plane_light_forward_as(const std::string& report, const SpecimenScene& scene,
                                          const PlaneLightOptions& options,
                                          const std::function<void(const RenderImage&)>& progress,
                                          const std::atomic<bool>* cancel) {
  RenderImage img = render_plane_light_forward(
      scene, options,
      [&](const RenderImage& i) {
        if (!progress) return;
        RenderImage copy = i;
        copy.model_report = report;
        progress(copy);
      },
      nullptr, cancel);
  img.model_report = report;
  return img;
}

RenderImage render_plane_light_forward(const SpecimenScene& scene, const PlaneLightOptions& o,
                                       const std::function<void(const RenderImage&)>& progress,
                                       InterfaceCounters* counters, const std::atomic<bool>* cancel) {
  if (o.scalar_tracer)
    throw std::invalid_argument("render_plane_light_forward: the polarization-exact tracer only");
  const RenderClock clock;
  ForwardRender r(scene, o, counters, cancel);
  RenderImage img = blank_plane_light_image(r.w, r.h, r.nb, forward_model_report(o.analyzer_in));
  if (!r.preview(img, clock, progress)) return img;
  r.allocate_accumulators();

  ProgressivePasses p;
  const double traces = r.mono ? 1.0 : 1.0 + double(r.nb) / (r.chroma_period * r.chroma_period);
  p.passes = std::max(1, int(std::ceil(o.spp / traces - 1e-9)));
  p.preview_passes = o.preview_factor > 1 ? 1 : 0;
  p.samples_per_pass = traces;
  p.tolerance_de2000 = o.tolerance_de2000;
  p.trace_pass = [&](int pass) { r.trace_pass(pass); };
  p.develop_image = [&](int done) { r.develop_image(img, done); };
  p.split_half_estimate = [&](int done) { return r.split_half_estimate(done); };
  run_progressive_passes(p, img, clock, progress, cancel);
  return img;
}

}  // namespace pmsim
