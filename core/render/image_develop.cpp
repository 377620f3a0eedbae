#include "core/render/image_develop.h"

#include <cmath>

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"

namespace pmsim {

void develop_image(const EvaluationPlan& plan, const std::vector<glm::dvec3>& units, bool mono,
                   RenderImage& out, const std::atomic<bool>* cancel) {
  const int W = plan.width(), H = plan.height();
  out.width = W;
  out.height = H;
  // Every pixel is written below: buffers handed in (a renderer recycles them) are not cleared.
  out.rgb.resize(static_cast<std::size_t>(W) * H * 3);
  out.xyz.resize(static_cast<std::size_t>(W) * H * 3);
  const glm::dvec3 white = illuminant_white_xyz(plan.scene().illuminant);
  tbb::parallel_for(tbb::blocked_range<int>(0, H, 8), [&](const tbb::blocked_range<int>& r) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    for (int y = r.begin(); y != r.end(); ++y)
      for (int x = 0; x < W; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * W + x;
        glm::dvec3 v(0.0);
        for (int k = plan.pixel_offset()[i]; k < plan.pixel_offset()[i + 1]; ++k)
          v += units[plan.refs()[k].unit] * static_cast<double>(plan.refs()[k].weight);
        if (!plan.ghost_xyz().empty())  // internal reflections of the physical lenses, precomputed
          v += glm::dvec3(plan.ghost_xyz()[3 * i], plan.ghost_xyz()[3 * i + 1], plan.ghost_xyz()[3 * i + 2]);
        glm::dvec3 xyz, rgb;
        if (mono) {
          xyz = white * v.y;
          rgb = glm::dvec3(v.y);
        } else {
          xyz = v;
          rgb = xyz_to_linear_srgb(v);
        }
        for (int c = 0; c < 3; ++c) {
          // No NaN or Inf ever reaches an image.
          out.xyz[3 * i + c] = std::isfinite(xyz[c]) ? static_cast<float>(xyz[c]) : 0.0f;
          out.rgb[3 * i + c] = std::isfinite(rgb[c]) ? static_cast<float>(rgb[c]) : 0.0f;
        }
      }
  });
}

double mean_ciede2000(const EvaluationPlan& plan, const std::vector<float>& a, const std::vector<float>& b) {
  const std::size_t n = static_cast<std::size_t>(plan.width()) * plan.height();
  const std::size_t stride = std::max<std::size_t>(1, n / 65536);
  const glm::dvec3 white = illuminant_white_xyz(plan.scene().illuminant);
  struct Acc {
    double sum = 0.0;
    std::size_t count = 0;
  };
  const std::size_t m = (n + stride - 1) / stride;
  const Acc acc = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, m, 4096), Acc{},
      [&](const tbb::blocked_range<std::size_t>& r, Acc s) {
        for (std::size_t j = r.begin(); j != r.end(); ++j) {
          const std::size_t i = j * stride;
          if (plan.pixel_offset()[i] == plan.pixel_offset()[i + 1]) continue;  // unlit
          const glm::dvec3 xa(a[3 * i], a[3 * i + 1], a[3 * i + 2]), xb(b[3 * i], b[3 * i + 1], b[3 * i + 2]);
          s.sum += ciede2000(xyz_to_lab(xa, white), xyz_to_lab(xb, white));
          ++s.count;
        }
        return s;
      },
      [](Acc x, const Acc& y) {
        x.sum += y.sum;
        x.count += y.count;
        return x;
      });
  return acc.count ? acc.sum / acc.count : 0.0;
}

}  // namespace pmsim
