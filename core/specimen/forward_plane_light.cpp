#include "core/specimen/forward_plane_light.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "core/base/units.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"
#include "core/specimen/jones_path.h"
#include "core/specimen/spectral_bands.h"
#include "core/specimen/specimen_random.h"

namespace pmsim {

namespace {

glm::dvec3 rotate_z(const glm::dvec3& v, double c, double s) { return {c * v.x - s * v.y, s * v.x + c * v.y, v.z}; }

template <class T>
void atomic_add(T& slot, T v) {
  std::atomic_ref<T>(slot).fetch_add(v, std::memory_order_relaxed);
}

// Where the focal plane z_air meets the line of a branch leaving the cover glass (the point the
// objective images it onto).
glm::dvec2 focal_point(const JonesExit& e, double z_air) {
  const glm::dvec3 q = e.point + ((z_air - e.point.z) / e.dir.z) * e.dir;
  return {q.x, q.y};
}

// One pass's ray: its direction and its λ's empty-stack shift and transmittance.
struct PassRay {
  glm::dvec3 dir{0.0, 0.0, 1.0};
  double wavelength_nm = 555.0;
  glm::dvec2 shift{0.0};  // focal point − start point in the empty stack
  double empty_t = 0.0;   // the empty stack's collected power for this ray
};

}  // namespace

RenderImage render_plane_light_forward(const SpecimenScene& scene, const PlaneLightOptions& o,
                                       const std::function<void(const RenderImage&)>& progress,
                                       InterfaceCounters* counters, const std::atomic<bool>* cancel) {
  if (o.analyzer_in || o.scalar_tracer)
    throw std::invalid_argument("render_plane_light_forward: plane light with the polarization-exact tracer only");
  const auto cancelled = [cancel] { return cancel && cancel->load(std::memory_order_relaxed); };
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsed_ms = [&] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  };
  const bool mono = o.single_wavelength_nm > 0.0;
  const int nb = mono ? 1 : std::max(1, o.bands);
  const SpectralBands bands = spectral_bands(nb, o.illuminant, !mono);
  const glm::dvec3 white = illuminant_white_xyz(o.illuminant);
  const double lambda_ref = mono ? o.single_wavelength_nm : 555.0;

  const double na = o.objective_na;
  const double nac = effective_condenser_na(o.condenser_aperture_na);
  const double z_air = objective_focus_z_air_um(scene, o.focus_um);
  const SpecimenLayers& L = scene.layers();
  const double z_source = -L.slide_um - 5.0;  // in the air below the slide
  const double c = std::cos(-o.stage_rad), s = std::sin(-o.stage_rad);
  const glm::dvec3 vibration = rotate_z({std::cos(o.polarizer_rad), std::sin(o.polarizer_rad), 0.0}, c, s);
  const glm::dvec2 centre = o.centre_um;

  // The empty stack: the shift and transmittance of a pass's direction at its λ (plane faces:
  // one ray says it for every start point).
  const SpecimenScene empty({}, scene.mineral(), scene.liquid(), scene.glass(), scene.air(), L);
  const auto trace = [&](const SpecimenScene& sc, const glm::dvec3& origin, const PassRay& r,
                         InterfaceCounters* ic) {
    JonesPathRequest q;
    q.forward = true;
    q.origin = origin;
    q.dir = r.dir;
    q.wavelength_nm = r.wavelength_nm;
    q.starts = 1;
    q.start_vibration = vibration;
    q.polarizer = vibration;
    q.objective_sin_max = na;
    return trace_specimen_jones(sc, q, ic);
  };
  const auto pass_ray = [&](double u1, double u2, double wavelength_nm) {
    PassRay r;
    const double sin_t = nac * std::sqrt(u1), phi = 2.0 * kPi * u2;
    r.dir = {sin_t * std::cos(phi), sin_t * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - sin_t * sin_t))};
    r.wavelength_nm = wavelength_nm;
    const JonesPath p = trace(empty, {0.0, 0.0, z_source}, r, nullptr);
    if (p.n_exits > 0) {
      r.shift = focal_point(p.exits[0], z_air);
      r.empty_t = p.exits[0].power;
    }
    return r;
  };

  // How far from its start's image point a collected ray can land: a deviation within the
  // objective's NA over the specimen's depth seen from the focal plane, plus the defocus.
  const double tan_na = std::min(na, 0.95) / std::sqrt(1.0 - std::min(na, 0.95) * std::min(na, 0.95));
  const double reach_um = (L.liquid_um + std::abs(o.focus_um) + 5.0) * tan_na + 2.0;

  const int w = o.width, h = o.height;
  const std::size_t npx = std::size_t(w) * h;
  RenderImage img;
  img.width = w;
  img.height = h;
  img.rgb.assign(npx * 3, 0.0f);
  img.xyz.assign(npx * 3, 0.0f);
  img.wavelengths = nb;
  img.model_report =
      "forward-traced refraction from the condenser (Embree, exact Fresnel, eigenmode splitting, tent splats), "
      "plane-polarized light";
  std::mutex counter_mutex;

  // Specimen point of image position (fx, fy) (pixels from the top left) on a grid of ww × hh
  // pixels of `um` µm, and back.
  const auto to_specimen = [&](double fx, double fy, double um, int ww, int hh) {
    const glm::dvec3 p = rotate_z({(fx - 0.5 * ww) * um, (0.5 * hh - fy) * um, 0.0}, c, s);
    return centre + glm::dvec2(p.x, p.y);
  };
  const auto to_image = [&](const glm::dvec2& q, double um, int ww, int hh) {
    const glm::dvec3 f = rotate_z({q.x - centre.x, q.y - centre.y, 0.0}, c, -s);
    return glm::dvec2(f.x / um + 0.5 * ww, 0.5 * hh - f.y / um);
  };

  // One pass over a ww × hh grid: every source pixel (with the margin) traces `rays` (the
  // reference first), each splatted by `splat(ray index, image position, weight)`.
  const auto run_pass = [&](int ww, int hh, double um, double jx, double jy, const std::vector<PassRay>& rays,
                            const std::function<void(int, const glm::dvec2&, double)>& splat) {
    const int m = int(std::ceil(reach_um / um)) + 1;
    const int sw = ww + 2 * m, sh = hh + 2 * m;
    tbb::parallel_for(tbb::blocked_range<int>(0, sh), [&](const tbb::blocked_range<int>& rows) {
      InterfaceCounters local;
      InterfaceCounters* lc = counters ? &local : nullptr;
      for (int sy = rows.begin(); sy < rows.end(); ++sy) {
        if (cancelled()) break;
        for (int sx = 0; sx < sw; ++sx) {
          const glm::dvec2 q = to_specimen(sx - m + jx, sy - m + jy, um, ww, hh);
          for (std::size_t k = 0; k < rays.size(); ++k) {
            const PassRay& r = rays[k];
            if (!(r.empty_t > 0.0)) continue;
            const glm::dvec2 start = q - r.shift;
            const JonesPath p = trace(scene, {start.x, start.y, z_source}, r, lc);
            for (int e = 0; e < p.n_exits; ++e) {
              const JonesExit& x = p.exits[std::size_t(e)];
              const double v = x.power / r.empty_t;
              if (!(v > 0.0) || !std::isfinite(v) || std::abs(x.dir.z) < 1e-9) continue;
              splat(int(k), to_image(focal_point(x, z_air), um, ww, hh), v);
            }
          }
        }
      }
      if (counters) {
        std::lock_guard<std::mutex> lock(counter_mutex);
        counters->add(local);
      }
    });
  };
  // Tent weights of image position f (pixel units) on pixel centres: the four pixels and weights.
  const auto tent = [](const glm::dvec2& f, int ww, int hh, const auto& add) {
    const double ux = f.x - 0.5, uy = f.y - 0.5;
    if (!(ux > -1.0 && uy > -1.0 && ux < ww && uy < hh)) return;
    const int x0 = int(std::floor(ux)), y0 = int(std::floor(uy));
    const double tx = ux - x0, ty = uy - y0;
    const double wx[2] = {1.0 - tx, tx}, wy[2] = {1.0 - ty, ty};
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const int x = x0 + dx, y = y0 + dy;
        if (x < 0 || y < 0 || x >= ww || y >= hh) continue;
        add(std::size_t(y) * ww + x, wx[dx] * wy[dy]);
      }
  };

  SampleDims shift;
  {
    SpecimenRandom rng(o.seed ^ 0xf0e1d2c3b4a59687ull);
    for (double& v : shift.v) v = rng.uniform();
  }

  // The preview: 1/f of the size, one pass at λ_ref, grey, spread bilinearly.
  const glm::dvec3 open_xyz = mono ? white : bands.sum;
  const glm::dvec3 open_rgb = mono ? glm::dvec3(1.0) : xyz_to_linear_srgb(bands.sum);
  if (o.preview_factor > 1 && w >= 2 * o.preview_factor && h >= 2 * o.preview_factor) {
    const int f = o.preview_factor;
    const int cw = (w + f - 1) / f, ch = (h + f - 1) / f;
    const double cum = o.um_per_px * double(w) / cw;
    std::vector<double> coarse(std::size_t(cw) * ch, 0.0);
    const SampleDims d = kronecker(shift, 0);
    run_pass(cw, ch, cum, d.v[0], d.v[1], {pass_ray(d.v[2], d.v[3], lambda_ref)},
             [&](int, const glm::dvec2& p, double v) {
               tent(p, cw, ch, [&](std::size_t i, double wt) { atomic_add(coarse[i], v * wt); });
             });
    if (cancelled()) {
      img.converged = false;
      return img;
    }
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
      for (int y = rows.begin(); y < rows.end(); ++y) {
        const double cy = std::clamp((y + 0.5) / f - 0.5, 0.0, ch - 1.0);
        const int y0 = std::min(int(cy), ch - 1), y1 = std::min(y0 + 1, ch - 1);
        const double ty = cy - y0;
        for (int x = 0; x < w; ++x) {
          const double cx = std::clamp((x + 0.5) / f - 0.5, 0.0, cw - 1.0);
          const int x0 = std::min(int(cx), cw - 1), x1 = std::min(x0 + 1, cw - 1);
          const double tx = cx - x0;
          const auto at = [&](int xx, int yy) { return coarse[std::size_t(yy) * cw + xx]; };
          const double v =
              (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x1, y0)) + ty * ((1 - tx) * at(x0, y1) + tx * at(x1, y1));
          const std::size_t pix = std::size_t(y) * w + x;
          const glm::dvec3 xyz = v * open_xyz, rgb = v * open_rgb;
          for (int k = 0; k < 3; ++k) img.xyz[pix * 3 + k] = float(xyz[k]), img.rgb[pix * 3 + k] = float(rgb[k]);
        }
      }
    });
    img.passes = 1;
    img.samples_per_pixel = 1.0 / (f * f);
    img.converged = false;
    img.time_ms = elapsed_ms();
    if (progress) progress(img);
  }

  // Accumulators per half (even/odd passes): the reference's splats, and per band the
  // difference splats of the passes that traced it.
  std::vector<double> ref_acc[2] = {std::vector<double>(npx, 0.0), std::vector<double>(npx, 0.0)};
  std::vector<double> diff_acc[2];
  if (!mono)
    for (auto& d : diff_acc) d.assign(npx * std::size_t(nb), 0.0);
  const auto band_of = [nb](int pass) { return (pass / 2) % nb; };
  // Passes of half `hf` among the first `passes` that traced band b.
  const auto band_passes = [&](int passes, int hf, int b) {
    int n = 0;
    for (int p = hf; p < passes; p += 2) n += band_of(p) == b ? 1 : 0;
    return n;
  };

  const auto develop = [&](std::size_t pix, int passes, int half) {
    const int h0 = half == 2 ? 0 : half, h1 = half == 2 ? 1 : half;
    int n_ref = 0;
    double ref = 0.0;
    for (int hh = h0; hh <= h1; ++hh) {
      n_ref += (passes + 1 - hh) / 2;
      ref += ref_acc[hh][pix];
    }
    if (n_ref == 0) return glm::dvec3(0.0);
    ref /= n_ref;
    if (mono) return ref * white;
    glm::dvec3 xyz(0.0);
    for (int b = 0; b < nb; ++b) {
      int n_b = 0;
      double diff = 0.0;
      for (int hh = h0; hh <= h1; ++hh) {
        n_b += band_passes(passes, hh, b);
        diff += diff_acc[hh][pix * std::size_t(nb) + std::size_t(b)];
      }
      xyz += (ref + (n_b > 0 ? diff / n_b : 0.0)) * bands.weight[std::size_t(b)];
    }
    return xyz;
  };

  const int traces = mono ? 1 : 2;
  const int passes = std::max(1, (o.spp + traces - 1) / traces);
  const int min_passes_for_estimate = mono ? 2 : 2 * nb;
  std::optional<double> last_err;
  for (int pass = 0; pass < passes; ++pass) {
    const int half = pass % 2;
    const SampleDims d = kronecker(shift, pass + 1);  // point 0 went to the preview
    std::vector<PassRay> rays = {pass_ray(d.v[2], d.v[3], lambda_ref)};
    const int b = band_of(pass);
    if (!mono)
      rays.push_back(pass_ray(d.v[2], d.v[3],
                              bands.lo_nm[std::size_t(b)] + bands.width_nm[std::size_t(b)] * d.v[4]));
    std::vector<double>& ref = ref_acc[half];
    double* diff = mono ? nullptr : diff_acc[half].data();
    run_pass(w, h, o.um_per_px, d.v[0], d.v[1], rays, [&](int k, const glm::dvec2& p, double v) {
      tent(p, w, h, [&](std::size_t i, double wt) {
        if (k == 0) {
          atomic_add(ref[i], v * wt);
          if (diff) atomic_add(diff[i * std::size_t(nb) + std::size_t(b)], -v * wt);
        } else {
          atomic_add(diff[i * std::size_t(nb) + std::size_t(b)], v * wt);
        }
      });
    });
    if (cancelled()) {
      img.converged = false;
      return img;
    }
    const int done = pass + 1;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, npx, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t pix = r.begin(); pix < r.end(); ++pix) {
        const glm::dvec3 xyz = develop(pix, done, 2);
        const glm::dvec3 rgb = mono ? glm::dvec3(xyz.y / white.y) : xyz_to_linear_srgb(xyz);
        for (int k = 0; k < 3; ++k) img.xyz[pix * 3 + k] = float(xyz[k]), img.rgb[pix * 3 + k] = float(rgb[k]);
      }
    });
    // Split half, as render_plane_light: the halves' mean CIEDE2000 (not halved: conservative),
    // over at most 65536 pixels.
    std::optional<double> err;
    if (done >= min_passes_for_estimate && done % 2 == 0) {
      const std::size_t stride = npx / 65536 + 1;
      const std::size_t m = (npx + stride - 1) / stride;
      const double sum = tbb::parallel_reduce(
          tbb::blocked_range<std::size_t>(0, m, 256), 0.0,
          [&](const tbb::blocked_range<std::size_t>& r, double acc) {
            for (std::size_t i = r.begin(); i < r.end(); ++i) {
              const std::size_t pix = i * stride;
              acc += ciede2000(xyz_to_lab(develop(pix, done, 0), white), xyz_to_lab(develop(pix, done, 1), white));
            }
            return acc;
          },
          std::plus<double>());
      err = sum / double(m);
    }
    if (err) last_err = err;
    img.error_estimate = last_err;
    img.passes = done + (o.preview_factor > 1 ? 1 : 0);
    img.samples_per_pixel = double(done * traces);
    const bool good_enough = o.tolerance_de2000 > 0.0 && err && *err < o.tolerance_de2000;
    img.converged = done == passes || good_enough;
    img.time_ms = elapsed_ms();
    if (progress) progress(img);
    if (good_enough) break;
  }
  return img;
}

}  // namespace pmsim
