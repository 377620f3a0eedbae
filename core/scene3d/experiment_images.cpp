#include "core/scene3d/experiment_images.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "core/lens/lens_tracer.h"
#include "core/scene3d/pinhole_camera.h"
#include "core/scene3d/scene3d_world.h"

namespace pmsim {

LensMask lens_mask(const Scene3dDescription& desc) {
  const Scene3dWorld world(desc);
  const PinholeCamera cam(desc.camera);
  LensMask m;
  m.width = desc.camera.width;
  m.height = desc.camera.height;
  m.inside.assign(static_cast<std::size_t>(m.width) * m.height, 0);
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      Scene3dHit h;
      const bool hit = world.intersect(cam.position(), cam.direction(x + 0.5, y + 0.5), 0.0,
                                       std::numeric_limits<double>::infinity(), h);
      if (hit && h.kind == Scene3dSurfaceKind::Lens) {
        m.inside[static_cast<std::size_t>(y) * m.width + x] = 1;
        ++m.count;
      }
    }
  return m;
}

DifferenceStats difference_stats(const std::vector<float>& a, const std::vector<float>& b,
                                 const LensMask& mask) {
  DifferenceStats s;
  double sum_in = 0.0, sum_out = 0.0;
  std::size_t n_in = 0, n_out = 0;
  const std::size_t n = std::min(a.size(), b.size()) / 3;
  for (std::size_t i = 0; i < n; ++i) {
    double d = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double e = std::abs(static_cast<double>(a[3 * i + c]) - b[3 * i + c]);
      d += e / 3.0;
      s.max = std::max(s.max, e);
    }
    if (i < mask.inside.size() && mask.inside[i]) {
      sum_in += d;
      ++n_in;
    } else {
      sum_out += d;
      ++n_out;
    }
  }
  s.mean_inside = n_in ? sum_in / n_in : 0.0;
  s.mean_outside = n_out ? sum_out / n_out : 0.0;
  return s;
}

std::vector<float> difference_image(const std::vector<float>& a, const std::vector<float>& b, double gain,
                                    bool negative) {
  std::vector<float> out(std::min(a.size(), b.size()));
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double d = std::min(1.0, gain * std::abs(static_cast<double>(a[i]) - b[i]));
    out[i] = static_cast<float>(negative ? 1.0 - d : d);
  }
  return out;
}

TirSpotStats tir_spot_stats(const Scene3dDescription& desc, const std::vector<float>& rgb,
                            const LensMask& mask, double threshold) {
  TirSpotStats s;
  s.threshold = threshold;
  const Scene3dWorld world(desc);
  const PinholeCamera cam(desc.camera);
  LensTraceOptions opt;
  opt.max_depth = desc.render.lens_depth;
  opt.tir = TirMode::Stop;
  opt.direction = TraceDirection::Backward;  // natural light: both halves
  LensBundle b;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * mask.width + x;
      if (!mask.inside[i]) continue;
      const glm::dvec3 d = cam.direction(x + 0.5, y + 0.5);
      Scene3dHit h;
      world.intersect(cam.position(), d, 0.0, std::numeric_limits<double>::infinity(), h);
      const Lens& lens = *world.lenses()[h.lens];
      PolarizedRay in;
      in.origin = cam.position();
      in.dir = d;
      in.wavelength_nm = 587.5618;
      b.clear();
      trace_lens(lens.geometry(), lens.media(in.wavelength_nm), in, opt, b);
      double tir = 0.0, entered = 0.0;
      for (const LensEvent& e : b.events)
        if (e.type == LensEvent::Type::Tir) tir += e.intensity;
      // Light that entered the glass: all but the depth-0 reflection at the entry point P1.
      LensHit p1;
      lens.geometry().intersect(in.origin, d, std::numeric_limits<double>::infinity(), LensSurface::None, p1);
      entered = b.incident;
      for (const PolarizedRay& r : b.rays)
        if (r.depth == 0 && glm::length(r.origin - p1.point) < 1e-9 * lens.geometry().size_mm())
          entered -= r.intensity;
      const bool tir_dominated = entered > 0.0 && tir > 0.5 * entered;
      if (tir_dominated) ++s.tir_pixels;
      if (luminance(&rgb[3 * i]) < threshold) {
        ++s.dark_pixels;
        if (tir_dominated) ++s.dark_with_tir;
      }
    }
  return s;
}

}  // namespace pmsim
