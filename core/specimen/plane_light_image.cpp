#include "core/specimen/plane_light_image.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <vector>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/base/units.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"
#include "core/specimen/specimen_random.h"

namespace pmsim {

namespace {

constexpr double kLambdaD_nm = 589.26;  // the D line of the liquid series' n_D

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

// The radical inverse in base 2 (van der Corput): a stratified offset for pass k of any prefix.
double van_der_corput(std::uint32_t k) {
  k = (k << 16) | (k >> 16);
  k = ((k & 0x00ff00ffu) << 8) | ((k & 0xff00ff00u) >> 8);
  k = ((k & 0x0f0f0f0fu) << 4) | ((k & 0xf0f0f0f0u) >> 4);
  k = ((k & 0x33333333u) << 2) | ((k & 0xccccccccu) >> 2);
  k = ((k & 0x55555555u) << 1) | ((k & 0xaaaaaaaau) >> 1);
  return double(k) * 0x1.0p-32;
}

}  // namespace

RenderImage render_plane_light(const SpecimenScene& scene, const PlaneLightOptions& o,
                               const std::function<void(const RenderImage&)>& progress,
                               InterfaceCounters* counters, const std::atomic<bool>* cancel) {
  const auto cancelled = [cancel] { return cancel && cancel->load(std::memory_order_relaxed); };
  const auto t0 = std::chrono::steady_clock::now();
  const bool mono = o.single_wavelength_nm > 0.0;
  const bool analyzer_in = o.analyzer_in && !o.scalar_tracer;
  const int nb = mono ? 1 : std::max(analyzer_in ? kCrossedPolarBands : 1, o.bands);
  // Band weights W_b = ∫_band w(λ) dλ with w the observer × illuminant weight (Y = 1 for T ≡ 1),
  // by the midpoint rule at ≤ 1 nm steps that tile the band exactly (a band of 12.5 nm is 13 steps
  // of 0.96 nm: 1 nm steps from its start would cover 12 of its 12.5 nm, and the bands' weights
  // would sum to Y = 0.96).
  std::vector<glm::dvec3> W(nb, glm::dvec3(0.0));
  std::vector<double> band_lo(nb), band_width(nb);
  const double span = kVisibleMaxNm - kVisibleMinNm;
  for (int b = 0; b < nb; ++b) {
    band_lo[b] = kVisibleMinNm + span * b / nb;
    band_width[b] = span / nb;
    if (!mono) {
      const int steps = int(std::ceil(band_width[b] - 1e-9));
      const double dl = band_width[b] / steps;
      for (int k = 0; k < steps; ++k) W[b] += dl * observer_weight(o.illuminant, band_lo[b] + (k + 0.5) * dl);
    }
  }
  const glm::dvec3 white = illuminant_white_xyz(o.illuminant);

  Geometry g;
  g.na = o.objective_na;
  g.nac = effective_condenser_na(o.condenser_aperture_na);
  g.r_in = std::min(g.nac, g.na);
  g.a_in = (g.r_in / g.na) * (g.r_in / g.na);
  g.annulus = g.r_in < g.na;
  const SpecimenLayers& L = scene.layers();
  g.z_air = scene.cover_top_z_um() - L.cover_um / scene.glass().n(kLambdaD_nm) -
            (L.liquid_um - scene.mid_plane_z_um()) / scene.liquid().n(kLambdaD_nm) + o.focus_um;
  g.z_start = scene.cover_top_z_um() + 10.0 + std::max(0.0, g.z_air - scene.cover_top_z_um());
  g.c = std::cos(-o.stage_rad);
  g.s = std::sin(-o.stage_rad);
  g.vibration = rotate_z({std::cos(o.polarizer_rad), std::sin(o.polarizer_rad), 0.0}, g.c, g.s);
  g.analyzer = rotate_z({std::cos(o.analyzer_rad), std::sin(o.analyzer_rad), 0.0}, g.c, g.s);
  g.analyzer_in = analyzer_in;
  g.scalar = o.scalar_tracer;
  const int strata = g.annulus ? 2 : 1;
  const double stratum_weight[2] = {g.annulus ? g.a_in : 1.0, 1.0 - g.a_in};

  // Exposure: the same stack without fragments, at the same λ and strata (4096 paths a band).
  std::vector<double> background(nb, 0.0);
  {
    SpecimenLayers bl = L;
    const SpecimenScene empty({}, scene.mineral(), scene.liquid(), scene.glass(), scene.air(), bl);
    for (int b = 0; b < nb; ++b) {
      SpecimenRandom rng(o.seed ^ 0xb9c3ull ^ (std::uint64_t(b) << 32));
      for (int st = 0; st < strata; ++st) {
        double sum = 0.0;
        constexpr int kPaths = 4096;
        for (int k = 0; k < kPaths; ++k) {
          const double lambda = mono ? o.single_wavelength_nm : band_lo[b] + band_width[b] * rng.uniform();
          const double u1 = rng.uniform(), u2 = rng.uniform();
          sum += sample_path(empty, g, {0.0, 0.0}, st, lambda, u1, u2, false, nullptr);
        }
        background[b] += stratum_weight[st] * sum / kPaths;
      }
    }
  }

  const int w = o.width, h = o.height;
  const std::size_t npx = std::size_t(w) * h;
  std::vector<float> acc(npx * nb, 0.0f);  // per band, the strata already weighted
  // A pass traces at most kBandsPerPass bands, one of every G = nb / kBandsPerPass neighbours in
  // turn (band b in the passes ≡ b mod G), so the first image costs what 8 bands cost: with the
  // analyzer in its 32 bands take 4 passes, and until a band has been traced its value is its
  // traced neighbour's.
  constexpr int kBandsPerPass = 8;
  const int G = std::max(1, nb / kBandsPerPass);
  const int per_pass = (nb + G - 1) / G;
  const int passes = std::max(G, ((o.spp + per_pass * strata - 1) / (per_pass * strata) + G - 1) / G * G);
  RenderImage img;
  img.width = w;
  img.height = h;
  img.rgb.assign(npx * 3, 0.0f);
  img.xyz.assign(npx * 3, 0.0f);
  img.wavelengths = nb;
  img.model_report = o.scalar_tracer ? "grain mount: backward-traced refraction (Embree, Fresnel), plane-polarized "
                                       "light, one linear vibration"
                     : analyzer_in ? "grain mount: backward-traced refraction (Embree, exact Fresnel, eigenmode "
                                     "splitting, coherent sum), analyzer in"
                                   : "grain mount: backward-traced refraction (Embree, exact Fresnel, eigenmode "
                                     "splitting), plane-polarized light";
  std::mutex counter_mutex;
  for (int pass = 0; pass < passes; ++pass) {
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
      InterfaceCounters local;
      for (int py = rows.begin(); py < rows.end() && !cancelled(); ++py)
        for (int px = 0; px < w; ++px) {
          const std::size_t pix = std::size_t(py) * w + px;
          SpecimenRandom rng(o.seed ^ splitmix64(pix * 0x100000001b3ull + std::uint64_t(pass) * 0x9e3779b9ull));
          // One point of the pixel and one pupil direction per stratum, shared by every band: the
          // bands' estimates are then correlated, so the noise is mostly of brightness, not of
          // hue, and what differs between bands is the dispersion (the paths bend by λ).
          for (int st = 0; st < strata; ++st) {
            const double jx = rng.uniform(), jy = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
            const glm::dvec3 f{(px + jx - 0.5 * w) * o.um_per_px, (0.5 * h - (py + jy)) * o.um_per_px, 0.0};
            const glm::dvec3 p = rotate_z(f, g.c, g.s);
            // The band offset: this pass's van der Corput point, rotated by a per-pixel (not per
            // pass) random shift, so every prefix of passes covers each band evenly.
            double band_jitter = van_der_corput(std::uint32_t(pass / G)) +
                                 SpecimenRandom(o.seed ^ splitmix64(pix * 4 + std::uint64_t(st) + 0x6a09e667ull)).uniform();
            band_jitter -= std::floor(band_jitter);
            for (int b = pass % G; b < nb; b += G) {
              const double lambda = mono ? o.single_wavelength_nm : band_lo[b] + band_width[b] * band_jitter;
              acc[pix * nb + b] += float(stratum_weight[st] * sample_path(scene, g, o.centre_um + glm::dvec2(p.x, p.y),
                                                                          st, lambda, u1, u2, g.analyzer_in,
                                                                          counters ? &local : nullptr));
            }
          }
        }
      if (counters) {
        std::lock_guard<std::mutex> lock(counter_mutex);
        counters->add(local);
      }
    });
    if (cancelled()) {
      img.converged = false;
      return img;
    }
    // Develop: per band the stratified estimate over the empty field's, then XYZ and linear sRGB.
    for (std::size_t pix = 0; pix < npx; ++pix) {
      glm::dvec3 xyz(0.0);
      double mono_value = 0.0;
      for (int b = 0; b < nb; ++b) {
        // The band itself once traced, else the latest traced one of its group of G.
        const int r = b % G, bt = r <= pass ? b : b - r + pass;
        const int count = (pass - bt % G) / G + 1;
        double v = acc[pix * nb + bt] / count;
        v = background[bt] > 0.0 ? v / background[bt] : 0.0;
        if (mono)
          mono_value = v;
        else
          xyz += v * W[b];
      }
      glm::dvec3 rgb;
      if (mono) {
        xyz = mono_value * white;
        rgb = glm::dvec3(mono_value);
      } else {
        rgb = xyz_to_linear_srgb(xyz);
      }
      for (int c = 0; c < 3; ++c) {
        img.xyz[pix * 3 + c] = float(xyz[c]);
        img.rgb[pix * 3 + c] = float(rgb[c]);
      }
    }
    img.passes = pass + 1;
    img.samples_per_pixel = double((pass + 1) * per_pass * strata);
    img.converged = pass + 1 == passes;
    img.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (progress) progress(img);
  }
  return img;
}

}  // namespace pmsim
