#include "core/specimen/plane_light_passes.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "core/spectrum/color.h"

namespace pmsim {

void spread_preview(const std::vector<double>& coarse, int cw, int ch, int f, const glm::dvec3& open_xyz,
                    const glm::dvec3& open_rgb, RenderImage& img) {
  const int w = img.width, h = img.height;
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
        const double v = std::max(
            0.0, (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x1, y0)) + ty * ((1 - tx) * at(x0, y1) + tx * at(x1, y1)));
        const std::size_t pix = std::size_t(y) * w + x;
        const glm::dvec3 xyz = v * open_xyz, rgb = v * open_rgb;
        for (int c = 0; c < 3; ++c) img.xyz[pix * 3 + c] = float(xyz[c]), img.rgb[pix * 3 + c] = float(rgb[c]);
      }
    }
  });
  img.passes = 1;
  img.samples_per_pixel = 1.0 / (f * f);
  img.converged = false;
}

double split_half_de2000(std::size_t n, const std::function<glm::dvec3(std::size_t, int)>& half_xyz,
                         const glm::dvec3& white) {
  if (n == 0) return 0.0;
  const std::size_t stride = n / 65536 + 1;
  const std::size_t m = (n + stride - 1) / stride;
  const double sum = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, m, 256), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double acc) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
          const std::size_t k = i * stride;
          acc += ciede2000(xyz_to_lab(half_xyz(k, 0), white), xyz_to_lab(half_xyz(k, 1), white));
        }
        return acc;
      },
      std::plus<double>());
  return sum / double(m);
}

}  // namespace pmsim
