#include "core/microscope/lens_polarization.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include <glm/geometric.hpp>

#include "core/base/conventions.h"
#include "core/crystal/plate.h"
#include "core/lens/lens.h"
#include "core/lens/lens_tracer.h"
#include "core/microscope/sample_source.h"

namespace pmsim {

LensSpec physical_lens_spec(int side) {
  LensSpec spec = load_lens_spec(asset_dir() + "/lenses/paper_rl425_rs43.json");
  const double half = 0.5 * Lens(spec).geometry().thickness_mm();
  spec.thickness_mm.reset();
  spec.center = {0.0, 0.0, side * (kLensWorkingDistanceMm + half)};
  spec.axis = kLightDirection;
  return spec;
}

namespace {
constexpr double kLensNm = kPhysicalLensNm;

LensPolarizationTable trace_table(FresnelModel fresnel) {
  const Lens lens(physical_lens_spec(+1));
  const LensMedia media = lens.media(kLensNm);
  LensTraceOptions opt;
  opt.max_depth = 0;
  opt.fresnel = fresnel;
  LensPolarizationTable t;
  const int n = LensPolarizationTable::kSamples;
  t.tau_s.resize(n);
  t.tau_p.resize(n);
  LensBundle bundle;
  for (int i = 0; i < n; ++i) {
    const double s = t.max_sin * i / (n - 1), c = std::sqrt(1.0 - s * s);
    const glm::dvec3 k{s, 0.0, c};
    const glm::dvec3 pols[2] = {{0.0, 1.0, 0.0}, {c, 0.0, -s}};  // s (⟂ meridional plane), p
    double tau[2];
    for (int j = 0; j < 2; ++j) {
      PolarizedRay r;
      r.origin = glm::dvec3(0.0);
      r.dir = k;
      r.pol = pols[j];
      r.wavelength_nm = kLensNm;
      r.intensity = 1.0;
      bundle.clear();
      trace_lens(lens.geometry(), media, r, opt, bundle);
      double I = 0.0;
      for (const PolarizedRay& o : bundle.rays)
        if (o.depth == 0 && o.dir.z > 0) I += o.intensity;  // the refracted main path
      tau[j] = std::sqrt(std::max(0.0, I));
    }
    t.tau_s[i] = tau[0];
    t.tau_p[i] = tau[1];
  }
  const double axis = t.tau_s[0] > 0 ? t.tau_s[0] : 1.0;
  for (int i = 0; i < n; ++i) {
    t.tau_s[i] /= axis;
    t.tau_p[i] /= axis;
  }
  return t;
}
}  // namespace

glm::dmat2 LensPolarizationTable::jones(const glm::dvec3& k) const {
  const double s = std::sqrt(k.x * k.x + k.y * k.y);  // |k| = 1: no overflow to guard against
  const double u = std::min(s / max_sin, 1.0) * (kSamples - 1);
  const int i = std::min(static_cast<int>(u), kSamples - 2);
  const double f = u - i;
  const double ts = (1 - f) * tau_s[i] + f * tau_s[i + 1], tp = (1 - f) * tau_p[i] + f * tau_p[i + 1];
  if (s < 1e-12) return glm::dmat2(ts, 0.0, 0.0, ts);
  const double cphi = k.x / s, sphi = k.y / s, cth = k.z;
  const glm::dvec3 p3{cth * cphi, cth * sphi, -s}, s3{-sphi, cphi, 0.0};
  glm::dvec3 a, b;
  transverse_basis(k, a, b);
  const glm::dvec2 p{glm::dot(p3, a), glm::dot(p3, b)}, q{glm::dot(s3, a), glm::dot(s3, b)};
  // J = τp·p pᵀ + τs·s sᵀ (glm matrices are column-major: m[col][row]).
  glm::dmat2 m;
  for (int col = 0; col < 2; ++col)
    for (int row = 0; row < 2; ++row) m[col][row] = tp * p[row] * p[col] + ts * q[row] * q[col];
  return m;
}

glm::dmat2 aplanatic_frame(const glm::dvec3& k) {
  const double s = std::sqrt(k.x * k.x + k.y * k.y);  // |k| = 1: no overflow to guard against
  if (s < 1e-12) return glm::dmat2(1.0);
  const double cphi = k.x / s, sphi = k.y / s, cth = k.z;
  const glm::dvec3 p3{cth * cphi, cth * sphi, -s}, s3{-sphi, cphi, 0.0};
  glm::dvec3 a, b;
  transverse_basis(k, a, b);
  // (x, y) → (radial, azimuthal) components → p3·radial + s3·azimuthal, in (a, b).
  // glm is column-major: m[col][row]; column j is the image of the lab basis vector j.
  const glm::dvec2 p{glm::dot(p3, a), glm::dot(p3, b)}, q{glm::dot(s3, a), glm::dot(s3, b)};
  const glm::dvec2 image_x = cphi * p - sphi * q, image_y = sphi * p + cphi * q;
  return glm::dmat2(image_x, image_y);
}

const LensPolarizationTable& lens_polarization_table(FresnelModel fresnel) {
  static LensPolarizationTable tables[2];
  static std::once_flag once[2];
  const int k = fresnel == FresnelModel::Schlick ? 1 : 0;
  std::call_once(once[k], [&] { tables[k] = trace_table(fresnel); });
  return tables[k];
}

}  // namespace pmsim
