#include "core/specimen/plane_light_image.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/base/units.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"
#include "core/specimen/plane_light_passes.h"
#include "core/spectrum/spectral_bands.h"
#include "core/specimen/specimen_random.h"
#include "core/spectrum/reference_wavelengths.h"

namespace pmsim {

namespace {

struct Geometry {
  double na, nac, r_in, a_in;  // objective NA, condenser cone NA, inner stratum radius, its pupil fraction
  bool annulus;
  double z_air, z_start;
  glm::dvec3 vibration;  // polarizer direction in the specimen frame
  glm::dvec3 analyzer;   // analyzer direction in the specimen frame
  bool analyzer_in = false, scalar = false;
  double c, s;           // cos, sin of −stage
};

glm::dvec3 rotate_z(const glm::dvec3& v, double c, double s) { return {c * v.x - s * v.y, s * v.x + c * v.y, v.z}; }

// One sample: stratum 0 = inner disk, 1 = annulus; returns the light the ray finds (0 if it
// leaves outside the condenser's cone). `analyzer_in` false: the analyzer out whatever g says
// (the exposure of the empty field).
double sample_path(const SpecimenScene& scene, const Geometry& g, const glm::dvec2& point_um, int stratum,
                   double wavelength_nm, double u1, double u2, bool analyzer_in, InterfaceCounters* counters) {
  const double sin_t = stratum == 0 ? g.r_in * std::sqrt(u1)
                                    : std::sqrt(g.r_in * g.r_in + (g.na * g.na - g.r_in * g.r_in) * u1);
  const double phi = 2.0 * kPi * u2;
  const double cos_t = std::sqrt(std::max(0.0, 1.0 - sin_t * sin_t));
  const glm::dvec3 d = rotate_z({sin_t * std::cos(phi), sin_t * std::sin(phi), -cos_t}, g.c, g.s);
  const glm::dvec3 focus{point_um, g.z_air};
  const glm::dvec3 origin = focus + ((g.z_start - g.z_air) / d.z) * d;
  if (g.scalar) {
    PolarizedRay ray;
    ray.dir = d;
    ray.origin = origin;
    ray.wavelength_nm = wavelength_nm;
    ray.intensity = 1.0;
    ray.pol = g.vibration;
    const SpecimenPath p = trace_specimen(scene, ray, counters);
    if (!p.left_below) return 0.0;
    const double sin_exit = std::sqrt(p.exit_dir.x * p.exit_dir.x + p.exit_dir.y * p.exit_dir.y);
    return sin_exit <= g.nac ? p.throughput : 0.0;
  }
  JonesPathRequest q;
  q.origin = origin;
  q.dir = d;
  q.wavelength_nm = wavelength_nm;
  q.starts = analyzer_in ? 1 : 2;
  q.start_vibration = analyzer_in ? g.analyzer : g.vibration;
  q.polarizer = g.vibration;
  q.condenser_sin_max = g.nac;
  const JonesPath p = trace_specimen_jones(scene, q, counters);
  const double I = p.intensity(q.starts);
  return std::isfinite(I) ? I : 0.0;
}


// The pupil-sampling shift of (pixel, stratum): fixed for the render, so that pass k takes the
// k-th point of one sequence.
SampleDims pixel_shift(std::uint64_t seed, std::size_t pix, int stratum) {
  SpecimenRandom rng(seed ^ splitmix64(pix * 0x100000001b3ull + std::uint64_t(stratum) * 0x9e3779b9ull));
  SampleDims s;
  for (double& v : s.v) v = rng.uniform();
  return s;
}

// How many j in [0, m) have (j + offset) % n == b: the passes of one half that traced band b.
int band_count(int m, int offset, int b, int n) {
  const int r = ((b - offset) % n + n) % n;
  return m > r ? (m - r - 1) / n + 1 : 0;
}

// The farthest (µm) any traced ray of a pixel strays horizontally from the pixel's focus point
// while it crosses the liquid layer, in the empty stack (a ray is in it until it meets a fragment):
// by Snell's law through the plane faces, offset(z) = A·tan θ_air − t_cover·tan θ_glass −
// (z_liquid_top − z)·tan θ_liquid along the ray's azimuth, A the height of the cover glass's top
// above the focus in air. The paraxial terms cancel near the focused plane; what is left is the
// defocus and the spherical aberration of the cover glass, maximised over the pupil (256 radii)
// and the ends of the visible (normal dispersion: the extremes of n).
double cone_reach_um(const SpecimenScene& scene, double na, double z_air, double lambda_lo, double lambda_hi) {
  const SpecimenLayers& L = scene.layers();
  const double a = scene.cover_top_z_um() - z_air;
  const auto tan_of = [](double s) { return s / std::sqrt(std::max(1e-12, 1.0 - s * s)); };
  double reach = 0.0;
  for (const double lambda : {lambda_lo, lambda_hi}) {
    const double n_air = scene.air().n(lambda), n_g = scene.glass().n(lambda), n_l = scene.liquid().n(lambda);
    for (int i = 0; i <= 256; ++i) {
      const double s_air = na * i / 256.0;  // sin θ in the air above (n_air ≈ 1, the pupil's)
      const double t_a = tan_of(s_air), t_g = tan_of(s_air * n_air / n_g), t_l = tan_of(s_air * n_air / n_l);
      const double top = a * t_a - L.cover_um * t_g;  // at the liquid's top
      const double bottom = top - L.liquid_um * t_l;  // at the slide
      reach = std::max({reach, std::abs(top), std::abs(bottom)});
    }
  }
  return reach;
}

// Pixels some ray of which may meet a fragment (1) and those that see the empty stack only (0),
// tested by 16-pixel tiles against the fragments' boxes, then pixel by pixel against the tile's.
std::vector<std::uint8_t> pixels_near_fragments(const SpecimenScene& scene, int w, int h, double um_per_px,
                                                const glm::dvec2& centre, double c, double s, double reach_um) {
  std::vector<std::uint8_t> near(std::size_t(w) * h, 0);
  const auto& boxes = scene.fragment_boxes();
  const auto to_specimen = [&](double fx, double fy) {
    const glm::dvec3 f{(fx - 0.5 * w) * um_per_px, (0.5 * h - fy) * um_per_px, 0.0};
    const glm::dvec3 p = rotate_z(f, c, s);
    return centre + glm::dvec2(p.x, p.y);
  };
  const auto box_distance = [](const FragmentBox& b, const glm::dvec2& p) {
    const glm::dvec2 d = glm::max(glm::max(b.lo - p, p - b.hi), glm::dvec2(0.0));
    return glm::length(d);
  };
  constexpr int kTile = 16;
  const int tx_n = (w + kTile - 1) / kTile, ty_n = (h + kTile - 1) / kTile;
  tbb::parallel_for(tbb::blocked_range<int>(0, tx_n * ty_n), [&](const tbb::blocked_range<int>& r) {
    std::vector<int> cand;
    for (int t = r.begin(); t < r.end(); ++t) {
      const int x0 = (t % tx_n) * kTile, y0 = (t / tx_n) * kTile;
      const int x1 = std::min(w, x0 + kTile), y1 = std::min(h, y0 + kTile);
      const glm::dvec2 tc = to_specimen(0.5 * (x0 + x1), 0.5 * (y0 + y1));
      const double tile_r = reach_um + 0.5 * std::hypot(x1 - x0, y1 - y0) * um_per_px + 1.0;
      cand.clear();
      for (std::size_t k = 0; k < boxes.size(); ++k)
        if (box_distance(boxes[k], tc) <= tile_r) cand.push_back(int(k));
      if (cand.empty()) continue;
      const double px_r = reach_um + 0.7072 * um_per_px + 1.0;  // 1 µm: float hits and nudges
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const glm::dvec2 p = to_specimen(x + 0.5, y + 0.5);
          for (const int k : cand)
            if (box_distance(boxes[std::size_t(k)], p) <= px_r) {
              near[std::size_t(y) * w + x] = 1;
              break;
            }
        }
    }
  });
  return near;
}

// One backward render's state, shared by its phases: the spectral plan, the pupil's geometry and
// strata, the empty field's exposure and colours, the pixels that can see a fragment and the
// passes' accumulators.
struct BackwardRender {
  const SpecimenScene& scene;
  const PlaneLightOptions& o;
  InterfaceCounters* counters;
  const std::atomic<bool>* cancel;
  std::mutex counter_mutex;

  // The spectrum: nb bands; a pass traces the reference λ and bands_per_pass bands, one of every
  // G neighbours in turn.
  bool mono = false, analyzer_in = false;
  int nb = 1, bands_per_pass = 1, G = 1;
  SpectralBands bands;
  glm::dvec3 white{0.0};
  double lambda_ref = 555.0;

  Geometry g{};
  int strata = 1;
  double stratum_weight[2] = {1.0, 0.0};

  // The empty field per band (and at λ_ref) with the analyzer out (the exposure) and in.
  std::vector<double> background, empty_polars;
  double background_ref = 0.0, empty_polars_ref = 0.0;
  glm::dvec3 empty_xyz{0.0}, empty_rgb{0.0}, open_xyz{0.0}, open_rgb{0.0};
  double empty_ref = 0.0;

  int w = 0, h = 0;
  std::size_t npx = 0;
  glm::dvec2 centre{0.0};
  double reach = 0.0;

  // Per active pixel (one that can see a fragment) and half: the passes' sums (see find_active_pixels).
  std::vector<std::uint32_t> active;
  std::size_t na = 0;
  std::vector<double> ref_acc[2];
  std::vector<float> diff_acc[2];
  std::vector<int> band_offset;

  BackwardRender(const SpecimenScene& scene_, const PlaneLightOptions& o_, InterfaceCounters* counters_,
                 const std::atomic<bool>* cancel_)
      : scene(scene_), o(o_), counters(counters_), cancel(cancel_) {
    plan_spectrum();
    set_up_pupil();
    expose_empty_field();
    w = o.width;
    h = o.height;
    npx = std::size_t(w) * h;
    centre = o.centre_um;
    reach = mono ? cone_reach_um(scene, g.na, g.z_air, o.single_wavelength_nm, o.single_wavelength_nm)
                 : cone_reach_um(scene, g.na, g.z_air, kVisibleMinNm, kVisibleMaxNm);
    empty_field_colours();
  }

  bool cancelled() const { return cancel_raised(cancel); }

  void plan_spectrum() {
    mono = o.single_wavelength_nm > 0.0;
    analyzer_in = o.analyzer_in && !o.scalar_tracer;
    nb = mono ? 1 : std::max(analyzer_in ? kCrossedPolarBands : 1, o.bands);
    // Bands traced a pass besides the reference: one in plane light (the control variate's
    // difference is small there), 8 with the analyzer in (the colour oscillates across the bands),
    // one of every G neighbours in turn.
    bands_per_pass = mono ? 1 : std::min(nb, analyzer_in ? 8 : 1);
    G = std::max(1, nb / bands_per_pass);
    bands = spectral_bands(nb, o.illuminant, !mono);
    white = illuminant_white_xyz(o.illuminant);
    // The control variate's wavelength: the photopic peak (mono: the line itself, traced once).
    lambda_ref = mono ? o.single_wavelength_nm : 555.0;
  }

  void set_up_pupil() {
    g.na = o.objective_na;
    g.nac = effective_condenser_na(o.condenser_aperture_na);
    g.r_in = std::min(g.nac, g.na);
    g.a_in = (g.r_in / g.na) * (g.r_in / g.na);
    g.annulus = g.r_in < g.na;
    g.z_air = objective_focus_z_air_um(scene, o.focus_um);
    g.z_start = scene.cover_top_z_um() + 10.0 + std::max(0.0, g.z_air - scene.cover_top_z_um());
    g.c = std::cos(-o.stage_rad);
    g.s = std::sin(-o.stage_rad);
    g.vibration = rotate_z({std::cos(o.polarizer_rad), std::sin(o.polarizer_rad), 0.0}, g.c, g.s);
    g.analyzer = rotate_z({std::cos(o.analyzer_rad), std::sin(o.analyzer_rad), 0.0}, g.c, g.s);
    g.analyzer_in = analyzer_in;
    g.scalar = o.scalar_tracer;
    strata = g.annulus ? 2 : 1;
    stratum_weight[0] = g.annulus ? g.a_in : 1.0;
    stratum_weight[1] = 1.0 - g.a_in;
  }

  // Exposure: the same stack without fragments, at the same λ and strata. Its paths cross plane
  // faces only, so T is a smooth function of the pupil point and λ: a midpoint rule (16 radii ×
  // 4 azimuths × 2 λ a band) is exact far below any visible difference.
  // With the analyzer in, the empty field between the polars (about 0 when crossed: what the
  // plane faces' Fresnel terms turn of the vibration) is what a pixel far from every fragment shows.
  void expose_empty_field() {
    background.assign(nb, 0.0);
    empty_polars.assign(nb, 0.0);
    const SpecimenScene empty({}, scene.mineral(), scene.liquid(), scene.glass(), scene.air(), scene.layers());
    const auto empty_field = [&](double lo, double width, int n_lambda, bool with_analyzer) {
      constexpr int kRadii = 16, kAzimuths = 4;
      double v = 0.0;
      for (int st = 0; st < strata; ++st) {
        double sum = 0.0;
        for (int il = 0; il < n_lambda; ++il)
          for (int i = 0; i < kRadii; ++i)
            for (int j = 0; j < kAzimuths; ++j)
              sum += sample_path(empty, g, {0.0, 0.0}, st, lo + width * (il + 0.5) / n_lambda, (i + 0.5) / kRadii,
                                 (j + 0.5) / kAzimuths, with_analyzer, nullptr);
        v += stratum_weight[st] * sum / (n_lambda * kRadii * kAzimuths);
      }
      return v;
    };
    for (const bool with_analyzer : {false, true}) {
      if (with_analyzer && !analyzer_in) break;
      std::vector<double>& field = with_analyzer ? empty_polars : background;
      for (int b = 0; b < nb; ++b)
        field[b] = mono ? empty_field(o.single_wavelength_nm, 0.0, 1, with_analyzer)
                        : empty_field(bands.lo_nm[b], bands.width_nm[b], 2, with_analyzer);
      (with_analyzer ? empty_polars_ref : background_ref) =
          mono ? field[0] : empty_field(lambda_ref, 0.0, 1, with_analyzer);
    }
    if (!analyzer_in) {
      empty_polars = background;
      empty_polars_ref = background_ref;
    }
  }

  void empty_field_colours() {
    // The empty field's colour: 1 in plane light (the exposure), the polars' own value with the
    // analyzer in.
    for (int b = 0; b < nb; ++b) {
      const double v = background[b] > 0.0 ? empty_polars[b] / background[b] : 0.0;
      empty_xyz += mono ? v * white : v * bands.weight[b];
    }
    empty_rgb = mono ? glm::dvec3(empty_xyz.y / white.y) : xyz_to_linear_srgb(empty_xyz);
    empty_ref = background_ref > 0.0 ? empty_polars_ref / background_ref : 0.0;
    // The grey preview's white: the empty field with the analyzer out.
    open_xyz = mono ? white : bands.sum;
    open_rgb = mono ? glm::dvec3(1.0) : xyz_to_linear_srgb(bands.sum);
  }

  const char* model_report() const {
    return o.scalar_tracer ? "grain mount: backward-traced refraction (Embree, Fresnel), plane-polarized "
                             "light, one linear vibration"
           : analyzer_in   ? "grain mount: backward-traced refraction (Embree, exact Fresnel, eigenmode "
                             "splitting, coherent sum), analyzer in"
                           : "grain mount: backward-traced refraction (Embree, exact Fresnel, eigenmode "
                             "splitting), plane-polarized light";
  }

  glm::dvec2 point_of(int px, int py, double jx, double jy, double um_per_px, int ww, int hh) const {
    const glm::dvec3 f{(px + jx - 0.5 * ww) * um_per_px, (0.5 * hh - (py + jy)) * um_per_px, 0.0};
    const glm::dvec3 p = rotate_z(f, g.c, g.s);
    return centre + glm::dvec2(p.x, p.y);
  }

  // The preview: 1/f of the size, one inner-stratum path a pixel at λ_ref, grey, spread bilinearly.
  // False: cancelled (img is to be returned as it is).
  bool preview(RenderImage& img, const RenderClock& clock, const std::function<void(const RenderImage&)>& progress) {
    if (!(o.preview_factor > 1 && w >= 2 * o.preview_factor && h >= 2 * o.preview_factor)) return true;
    const int f = o.preview_factor;
    const int cw = (w + f - 1) / f, ch = (h + f - 1) / f;
    const double cum = o.um_per_px * double(w) / cw;
    const auto cnear = pixels_near_fragments(scene, cw, ch, cum, centre, g.c, g.s, reach);
    std::vector<double> coarse(std::size_t(cw) * ch, empty_ref);
    tbb::parallel_for(tbb::blocked_range<int>(0, ch), [&](const tbb::blocked_range<int>& rows) {
      for (int py = rows.begin(); py < rows.end() && !cancelled(); ++py)
        for (int px = 0; px < cw; ++px) {
          const std::size_t pix = std::size_t(py) * cw + px;
          if (!cnear[pix]) continue;
          const SampleDims d = kronecker(pixel_shift(o.seed ^ 0x5eedull, pix, 0), 0);
          coarse[pix] = stratum_weight[0] *
                        sample_path(scene, g, point_of(px, py, d.v[0], d.v[1], cum, cw, ch), 0, lambda_ref, d.v[2],
                                    d.v[3], g.analyzer_in, nullptr) /
                        background_ref;
        }
    });
    return show_preview(coarse, cw, ch, f, open_xyz, open_rgb, img, clock, progress, cancel);
  }

  // The pixels that can see a fragment; every other one is the empty field (1 in plane light) from
  // the start.
  void find_active_pixels() {
    const auto near = pixels_near_fragments(scene, w, h, o.um_per_px, centre, g.c, g.s, reach);
    for (std::size_t pix = 0; pix < npx; ++pix)
      if (near[pix]) active.push_back(std::uint32_t(pix));
    na = active.size();
    // Accumulators per half (even/odd passes), per active pixel: Σ T(λ_ref) per stratum, and per
    // band and stratum Σ (T(λ_b) − T(λ_ref)) over the passes that traced band b (pass j traces the
    // bands b ≡ j + offset mod G).
    for (auto& r : ref_acc) r.assign(na * strata, 0.0);
    if (!mono)
      for (auto& d : diff_acc) d.assign(na * nb * strata, 0.0f);
    band_offset.resize(na);
    for (std::size_t a = 0; a < na; ++a) band_offset[a] = int(splitmix64(o.seed ^ (active[a] * 0x2545f4914f6cdd1dull)) % G);
  }

  // One half's (h = 0, 1) or both halves' (h = 2) colour of active pixel a after `passes` passes.
  glm::dvec3 develop(std::size_t a, int passes, int half) const {
    const int m[2] = {(passes + 1) / 2, passes / 2};
    glm::dvec3 xyz(0.0);
    const int h0 = half == 2 ? 0 : half, h1 = half == 2 ? 1 : half;
    int n_ref = 0;
    for (int hh = h0; hh <= h1; ++hh) n_ref += m[hh];
    if (n_ref == 0) return empty_xyz;
    for (int b = 0; b < nb; ++b) {
      int n_b = 0;
      if (!mono)
        for (int hh = h0; hh <= h1; ++hh) n_b += band_count(m[hh], band_offset[a], b % G, G);
      double v = 0.0;
      for (int st = 0; st < strata; ++st) {
        double ref = 0.0, diff = 0.0;
        for (int hh = h0; hh <= h1; ++hh) {
          ref += ref_acc[hh][a * strata + st];
          if (!mono) diff += diff_acc[hh][(a * nb + b) * strata + st];
        }
        v += stratum_weight[st] * (ref / n_ref + (n_b > 0 ? diff / n_b : 0.0));
      }
      v = background[b] > 0.0 ? v / background[b] : 0.0;
      xyz += mono ? v * white : v * bands.weight[b];
    }
    return xyz;
  }

  // Pass `pass`: every active pixel's strata at the pass's Kronecker point, traced at λ_ref and at
  // the bands of the pixel's group this pass, into the pass's half.
  void trace_pass(int pass) {
    const int half = pass % 2, j = pass / 2;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, na, 64), [&](const tbb::blocked_range<std::size_t>& r) {
      InterfaceCounters local;
      InterfaceCounters* lc = counters ? &local : nullptr;
      for (std::size_t a = r.begin(); a < r.end(); ++a) {
        if ((a & 63) == 0 && cancelled()) break;
        const std::size_t pix = active[a];
        const int px = int(pix % std::size_t(w)), py = int(pix / std::size_t(w));
        const int group = (j + band_offset[a]) % G;
        for (int st = 0; st < strata; ++st) {
          const SampleDims d = kronecker(pixel_shift(o.seed, pix, st), pass);
          const glm::dvec2 p = point_of(px, py, d.v[0], d.v[1], o.um_per_px, w, h);
          const double t_ref = sample_path(scene, g, p, st, lambda_ref, d.v[2], d.v[3], g.analyzer_in, lc);
          ref_acc[half][a * strata + st] += t_ref;
          if (!mono)
            for (int b = group; b < nb; b += G) {
              const double t_b = sample_path(scene, g, p, st, bands.lo_nm[b] + bands.width_nm[b] * d.v[4], d.v[2],
                                             d.v[3], g.analyzer_in, lc);
              diff_acc[half][(a * nb + b) * strata + st] += float(t_b - t_ref);
            }
        }
      }
      if (counters) {
        std::lock_guard<std::mutex> lock(counter_mutex);
        counters->add(local);
      }
    });
  }

  // Develop: the empty field where no ray can meet a fragment, the estimate elsewhere.
  void develop_image(RenderImage& img, int done) const {
    if (done == 1)
      for (std::size_t pix = 0; pix < npx; ++pix)
        for (int c = 0; c < 3; ++c) img.xyz[pix * 3 + c] = float(empty_xyz[c]), img.rgb[pix * 3 + c] = float(empty_rgb[c]);
    develop_pixels(
        img, na, 256, [&](std::size_t a) { return std::size_t(active[a]); },
        [&](std::size_t a) { return develop(a, done, 2); }, mono, white);
  }

  // Split half: mean ΔE00 between the halves over the whole image (inactive pixels: 0), over at
  // most 65536 active pixels. For Gaussian noise the whole's error would be half of it; the light
  // a stopped-down condenser lets through the annulus is heavy-tailed (rare rays of ~68 empty
  // fields), and half of it was measured 2–3× below the error against a 16× longer render, so
  // the estimate is the halves' difference itself: a render stops late rather than early.
  std::optional<double> split_half_estimate(int done) const {
    // A split-half estimate means something once each half has traced every band.
    const int min_passes_for_estimate = mono ? 2 : 2 * G;
    if (na == 0) return 0.0;
    if (done >= min_passes_for_estimate && done % 2 == 0)
      return split_half_de2000(na, [&](std::size_t a, int hf) { return develop(a, done, hf); }, white) *
             (double(na) / double(npx));
    return std::nullopt;
  }
};

}  // namespace

double objective_focus_z_air_um(const SpecimenScene& scene, double focus_um) {
  const SpecimenLayers& L = scene.layers();
  return scene.cover_top_z_um() - L.cover_um / scene.glass().n(kLiquidDNm) -
         (L.liquid_um - scene.mid_plane_z_um()) / scene.liquid().n(kLiquidDNm) + focus_um;
}

RenderImage render_plane_light(const SpecimenScene& scene, const PlaneLightOptions& o,
                               const std::function<void(const RenderImage&)>& progress,
                               InterfaceCounters* counters, const std::atomic<bool>* cancel) {
  const RenderClock clock;
  BackwardRender r(scene, o, counters, cancel);
  RenderImage img = blank_plane_light_image(r.w, r.h, r.nb, r.model_report());
  if (!r.preview(img, clock, progress)) return img;
  r.find_active_pixels();

  ProgressivePasses p;
  const int traces = r.mono ? 1 : 1 + r.bands_per_pass;
  const int spp_per_pass = r.strata * traces;
  p.passes = std::max(1, (o.spp + spp_per_pass - 1) / spp_per_pass);
  p.preview_passes = o.preview_factor > 1 ? 1 : 0;
  p.samples_per_pass = spp_per_pass;
  p.tolerance_de2000 = o.tolerance_de2000;
  p.trace_pass = [&](int pass) { r.trace_pass(pass); };
  p.develop_image = [&](int done) { r.develop_image(img, done); };
  p.split_half_estimate = [&](int done) { return r.split_half_estimate(done); };
  run_progressive_passes(p, img, clock, progress, cancel);
  return img;
}

}  // namespace pmsim
