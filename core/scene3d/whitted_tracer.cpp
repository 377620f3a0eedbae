#include "core/base/units.h"
#include "core/scene3d/whitted_tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "core/base/input_error.h"
#include "core/materials/medium.h"
#include "core/optics/beer_lambert.h"
#include "core/optics/interaction.h"
#include "core/optics/polarization_frame.h"
#include "core/scene3d/rgb_reflectance_spectrum.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"
#include "core/spectrum/wavelength_sampling.h"

namespace pmsim {
namespace {

constexpr double kRgbWavelengthNm = 587.5618;  // helium d line: n_d, the catalogue index
constexpr double kInvPi = 1.0 / kPi;

// Σ_i w_i·S(λ_i)·ȳ(λ_i) over the paper's 81 wavelengths: the luminance of illuminant S.
struct SpectralFrame {
  SampledWavelengths wl;
  double k_d65 = 1.0;
};

const SpectralFrame& frame81() {
  static const SpectralFrame f = [] {
    SpectralFrame s;
    s.wl = uniform_wavelengths(81);
    double k = 0.0;
    for (int i = 0; i < s.wl.size(); ++i)
      k += s.wl.weight_nm[i] * illuminant_spd(Illuminant::D65, s.wl.nm[i]) * cie1931_xyz_bar(s.wl.nm[i]).y;
    s.k_d65 = k;
    return s;
  }();
  return f;
}

// Linear sRGB of a reflectance spectrum ρ(λ) lit by illuminant `illum` with Y(white) = 1.
glm::dvec3 rgb_under(const std::vector<double>& rho81, Illuminant illum) {
  const SpectralFrame& f = frame81();
  glm::dvec3 xyz(0.0);
  for (int i = 0; i < f.wl.size(); ++i)
    xyz += f.wl.weight_nm[i] * rho81[i] * illuminant_spd(illum, f.wl.nm[i]) * cie1931_xyz_bar(f.wl.nm[i]);
  return xyz_to_linear_srgb(xyz / f.k_d65);
}

}  // namespace

WhittedTracer::WhittedTracer(const Scene3dWorld& world) : world_(world), desc_(world.description()) {
  const Scene3dRenderSettings& rs = desc_.render;
  spectral_ = rs.mode == Scene3dMode::Spectral;
  eps_ = 1e-6 * world.scene_size_mm() + 1e-7;
  fresnel_ = rs.fresnel;
  lens_options_.max_depth = rs.lens_depth;
  lens_options_.tir = rs.tir;
  lens_options_.ledge = LedgeMode::Stop;
  // The eye ray carries the linear state being traced (see the header), so the SML traces it as
  // a polarized ray; G is the same both ways.
  lens_options_.direction = TraceDirection::Forward;
  lens_options_.fresnel = fresnel_;

  if (spectral_) {
    const SampledWavelengths wl = uniform_wavelengths(rs.wavelengths);
    double k = 0.0;
    for (int i = 0; i < wl.size(); ++i)
      k += wl.weight_nm[i] * illuminant_spd(Illuminant::D65, wl.nm[i]) * cie1931_xyz_bar(wl.nm[i]).y;
    for (int i = 0; i < wl.size(); ++i) {
      nm_.push_back(wl.nm[i]);
      // XYZ = Σ w_i·L(λ_i)·x̄(λ_i)/K: a white diffuser under D65 of unit strength has Y = 1.
      to_rgb_.push_back(xyz_to_linear_srgb(wl.weight_nm[i] * cie1931_xyz_bar(wl.nm[i]) / k));
    }
  } else {
    nm_ = {kRgbWavelengthNm, kRgbWavelengthNm, kRgbWavelengthNm};
    to_rgb_ = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  }
  const int nc = channels();

  for (const Scene3dMaterial& m : desc_.materials) {
    std::vector<std::vector<double>> per_colour;
    for (const glm::dvec3& c : m.colors) {
      std::vector<double> v(nc);
      if (spectral_) {
        for (int i = 0; i < nc; ++i) v[i] = smits_reflectance(c, nm_[i]);
      } else {
        const glm::dvec3 e = effective_rgb(c);
        v = {e.x, e.y, e.z};
      }
      per_colour.push_back(std::move(v));
    }
    reflectance_.push_back(std::move(per_colour));
    std::vector<double> n(nc, 1.0), mu(nc, 0.0);
    if (m.type == Scene3dMaterial::Type::Glass) {
      const Medium& med = find_medium(m.medium);
      try {
        for (int i = 0; i < nc; ++i) {
          n[i] = med.n(nm_[i]);
          mu[i] = med.attenuation_per_mm(nm_[i]);
        }
      } catch (const std::out_of_range& e) {
        throw InputError(desc_.file, "materials." + m.name + ".medium", m.medium, e.what());
      }
    }
    glass_n_.push_back(std::move(n));
    glass_mu_.push_back(std::move(mu));
  }
  for (const Scene3dLight& l : desc_.lights) {
    std::vector<double> e(nc);
    const double strength = l.type == Scene3dLight::Type::Point ? l.intensity : l.radiance;
    if (spectral_) {
      for (int i = 0; i < nc; ++i) e[i] = strength * illuminant_spd(l.emission, nm_[i]);
    } else {
      const glm::dvec3 w = xyz_to_linear_srgb(illuminant_white_xyz(l.emission));
      e = {strength * w.x, strength * w.y, strength * w.z};
    }
    emission_.push_back(std::move(e));
  }
  background_ = spectrum_of_rgb(rs.background_rgb, Illuminant::D65);
  ambient_ = spectrum_of_rgb(glm::dvec3(rs.ambient), Illuminant::D65);
  for (std::size_t k = 0; k < world.lenses().size(); ++k) {
    std::vector<LensMedia> m(nc);
    try {
      for (int i = 0; i < nc; ++i) m[i] = world.lenses()[k]->media(nm_[i]);
    } catch (const std::out_of_range& e) {
      throw InputError(desc_.file, "lens " + std::to_string(k) + ".glass", world.lenses()[k]->spec().glass,
                       e.what());
    }
    lens_media_.push_back(std::move(m));
  }
}

std::vector<double> WhittedTracer::spectrum_of_rgb(const glm::dvec3& rgb, Illuminant illum) const {
  std::vector<double> v(channels());
  if (spectral_) {
    for (int i = 0; i < channels(); ++i)
      v[i] = smits_reflectance(rgb, nm_[i]) * illuminant_spd(illum, nm_[i]);
  } else {
    v = {rgb.x, rgb.y, rgb.z};
  }
  return v;
}

glm::dvec3 WhittedTracer::effective_rgb(const glm::dvec3& rgb) const {
  const SpectralFrame& f = frame81();
  std::vector<double> rho(f.wl.size());
  for (int i = 0; i < f.wl.size(); ++i) rho[i] = smits_reflectance(rgb, f.wl.nm[i]);
  return rgb_under(rho, Illuminant::D65);
}

glm::dvec3 WhittedTracer::trace(const glm::dvec3& origin, const glm::dvec3& dir,
                                const glm::dvec3* filter_axis) const {
  Acc acc;
  std::fill(acc, acc + kMaxChannels, 0.0);
  if (filter_axis) {
    // Behind a polarizer the eye sees the filter's state only: ½·|J v|²·L (see the header).
    radiance(origin, dir, 0, -1, filter_axis, 0.5, acc);
  } else {
    radiance(origin, dir, 0, -1, nullptr, 1.0, acc);
  }
  glm::dvec3 rgb(0.0);
  for (int i = 0; i < channels(); ++i) rgb += acc[i] * to_rgb_[i];
  return rgb;
}

void WhittedTracer::radiance(const glm::dvec3& origin, const glm::dvec3& dir, int depth, int ch,
                             const glm::dvec3* pol, double w, Acc acc) const {
  // Branches carrying less than 1e-9 of the camera ray's weight are cut: a Whitted tree with
  // TIR splitting grows as 2^depth, and what is cut is below any displayable difference.
  if (!(w > 1e-9)) return;
  Scene3dHit hit;
  if (!world_.intersect(origin, dir, eps_, std::numeric_limits<double>::infinity(), hit)) {
    if (ch >= 0) {
      acc[ch] += w * background_[ch];
    } else {
      for (int i = 0; i < channels(); ++i) acc[i] += w * background_[i];
    }
    return;
  }
  shade(origin, dir, hit, depth, ch, pol, w, acc);
}

void WhittedTracer::shade(const glm::dvec3& origin, const glm::dvec3& dir, const Scene3dHit& hit, int depth,
                          int ch, const glm::dvec3* pol, double w, Acc acc) const {
  switch (hit.kind) {
    case Scene3dSurfaceKind::Diffuse:
      shade_diffuse(dir, hit, ch, w, acc);
      return;
    case Scene3dSurfaceKind::Emitter: {
      const Scene3dLight& l = desc_.lights[hit.light];
      if (glm::dot(dir, l.normal) >= 0.0) return;  // one-sided emitter seen from behind
      const auto& e = emission_[hit.light];
      if (ch >= 0) {
        acc[ch] += w * e[ch];
      } else {
        for (int i = 0; i < channels(); ++i) acc[i] += w * e[i];
      }
      return;
    }
    case Scene3dSurfaceKind::Glass:
    case Scene3dSurfaceKind::Lens:
      break;
  }
  if (depth >= desc_.render.max_depth) return;
  if (spectral_ && ch < 0 && channels() > 1) {
    // Dispersion: from here on every wavelength has its own tree.
    for (int c = 0; c < channels(); ++c) shade(origin, dir, hit, depth, c, pol, w, acc);
    return;
  }
  if (!pol) {
    if (fresnel_ == FresnelModel::Schlick) {
      // Schlick is polarization-blind: both halves would get the same throughput, so one tree
      // of full weight is traced (this, not the formula, is where Schlick saves time).
      const glm::dvec3 v = any_perpendicular(dir);
      shade_glass(origin, dir, hit, depth, ch, v, w, acc);
    } else {
      // Natural light: two incoherent orthogonal linear halves (paper §5), chosen as the s and p
      // directions of this interface so that each stays linear through the first G.
      const glm::dvec3 v1 = perpendicular_axis(dir, hit.normal);
      const glm::dvec3 v2 = glm::normalize(glm::cross(dir, v1));
      shade_glass(origin, dir, hit, depth, ch, v1, 0.5 * w, acc);
      shade_glass(origin, dir, hit, depth, ch, v2, 0.5 * w, acc);
    }
    return;
  }
  shade_glass(origin, dir, hit, depth, ch, *pol, w, acc);
}

void WhittedTracer::shade_diffuse(const glm::dvec3& dir, const Scene3dHit& hit, int ch, double w,
                                  Acc acc) const {
  const Scene3dMaterial& m = desc_.materials[hit.material];
  int colour = 0;
  if (m.pattern != Scene3dMaterial::Pattern::Solid) {
    const Scene3dObject& o = desc_.objects[hit.object];
    double u, v;
    if (o.type == Scene3dObject::Type::Plane) {
      const glm::dvec3 d = hit.point - o.center;
      u = glm::dot(d, o.u_axis);
      v = glm::dot(d, glm::cross(o.normal, o.u_axis));
    } else {
      u = hit.point.x;
      v = hit.point.z;
    }
    const long long iu = static_cast<long long>(std::floor(u / m.period_mm));
    const long long iv = static_cast<long long>(std::floor(v / m.period_mm));
    const long long k = m.pattern == Scene3dMaterial::Pattern::Stripes ? iu : iu + iv;
    const long long n = static_cast<long long>(m.colors.size());
    colour = static_cast<int>(((k % n) + n) % n);
  }
  const std::vector<double>& rho = reflectance_[hit.material][colour];
  const glm::dvec3 N = glm::dot(dir, hit.normal) < 0.0 ? hit.normal : -hit.normal;
  const glm::dvec3 p = hit.point + eps_ * N;
  const int c0 = ch >= 0 ? ch : 0, c1 = ch >= 0 ? ch + 1 : channels();
  // Whitted's ambient term: a fraction of a D65 white, reflected by ρ.
  for (int c = c0; c < c1; ++c) acc[c] += w * rho[c] * ambient_[c];
  for (std::size_t li = 0; li < desc_.lights.size(); ++li) {
    const Scene3dLight& l = desc_.lights[li];
    // g: geometric factor of the Lambertian BRDF ρ/π times the light's strength-free flux.
    double g = 0.0;
    if (l.type == Scene3dLight::Type::Point) {
      const glm::dvec3 d = l.position - p;
      const double r2 = glm::dot(d, d);
      const double cos_s = glm::dot(N, d) / std::sqrt(r2);
      if (cos_s <= 0.0 || world_.opaque_between(p, l.position)) continue;
      g = kInvPi * cos_s / r2;  // L = ρ/π · I·cosθ/r²
    } else {
      // Stratified samples over the rectangle: L = ρ/π · Le · ∫ cosθ cosθ'/r² dA.
      const glm::dvec3 vax = glm::cross(l.normal, l.u_axis);
      const int n = l.samples;
      const double area = l.size_mm.x * l.size_mm.y;
      // Deterministic jitter from the shading point, so images are repeatable and the
      // stratification does not print a visible grid into soft shadows.
      std::uint64_t h =
          std::hash<double>()(hit.point.x * 73856093.0 + hit.point.y * 19349663.0 + hit.point.z * 83492791.0);
      auto rnd = [&h] {
        h ^= h >> 33;
        h *= 0xff51afd7ed558ccdULL;
        h ^= h >> 33;
        h *= 0xc4ceb9fe1a85ec53ULL;
        h ^= h >> 33;
        return static_cast<double>(h >> 11) * 0x1.0p-53;
      };
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          const double su = ((a + rnd()) / n - 0.5) * l.size_mm.x;
          const double sv = ((b + rnd()) / n - 0.5) * l.size_mm.y;
          const glm::dvec3 q = l.center + su * l.u_axis + sv * vax;
          const glm::dvec3 d = q - p;
          const double r2 = glm::dot(d, d);
          const double r = std::sqrt(r2);
          const double cos_s = glm::dot(N, d) / r;
          const double cos_l = -glm::dot(l.normal, d) / r;
          if (cos_s <= 0.0 || cos_l <= 0.0 || world_.opaque_between(p, q)) continue;
          g += kInvPi * cos_s * cos_l / r2 * area / (n * n);
        }
    }
    if (g <= 0.0) continue;
    const auto& e = emission_[li];
    for (int c = c0; c < c1; ++c) acc[c] += w * g * rho[c] * e[c];
  }
}

void WhittedTracer::shade_glass(const glm::dvec3& origin, const glm::dvec3& dir, const Scene3dHit& hit,
                                int depth, int ch, const glm::dvec3& pol, double w, Acc acc) const {
  const int c = std::max(ch, 0);
  const double lambda = nm_[c];
  if (hit.kind == Scene3dSurfaceKind::Lens) {
    // The SML: one linear ray in, the bundle out; TIR and ledge branches end here (black).
    thread_local std::vector<LensBundle> pool;
    if (static_cast<int>(pool.size()) <= depth) pool.resize(depth + 1);
    LensBundle& b = pool[depth];
    b.clear();
    PolarizedRay in;
    in.origin = origin;
    in.dir = dir;
    in.wavelength_nm = lambda;
    in.intensity = 1.0;
    in.pol = pol;
    trace_lens(world_.lenses()[hit.lens]->geometry(), lens_media_[hit.lens][c], in, lens_options_, b);
    // Copy: deeper levels may grow the pool and move this bundle.
    const std::vector<PolarizedRay> rays = b.rays;
    for (const PolarizedRay& o : rays) radiance(o.origin, o.dir, depth + 1, ch, &o.pol, w * o.intensity, acc);
    return;
  }
  const double n_glass = glass_n_[hit.material][c];
  const bool entering = glm::dot(dir, hit.normal) < 0.0;
  if (!entering) w *= beer_lambert_transmittance(glass_mu_[hit.material][c], hit.t);
  PolarizedRay in;
  in.origin = origin;
  in.dir = dir;
  in.wavelength_nm = lambda;
  in.intensity = 1.0;
  in.pol = pol;
  InteractionResult res;
  interact(in, hit.point, hit.normal, entering ? 1.0 : n_glass, entering ? n_glass : 1.0, fresnel_, res);
  for (int k = 0; k < res.reflected_count; ++k)
    radiance(hit.point, res.reflected[k].dir, depth + 1, ch, &res.reflected[k].pol,
             w * res.reflected[k].intensity, acc);
  if (res.has_refracted)
    radiance(hit.point, res.refracted.dir, depth + 1, ch, &res.refracted.pol, w * res.refracted.intensity,
             acc);
}

}  // namespace pmsim
