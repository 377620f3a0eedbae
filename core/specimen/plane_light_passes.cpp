#include "core/specimen/plane_light_passes.h"

#include <algorithm>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "core/spectrum/color.h"

namespace pmsim {

RenderImage blank_plane_light_image(int w, int h, int bands, std::string model_report) {
  const std::size_t npx = std::size_t(w) * h;
  RenderImage img;
  img.width = w;
  img.height = h;
  img.rgb.assign(npx * 3, 0.0f);
  img.xyz.assign(npx * 3, 0.0f);
  img.wavelengths = bands;
  img.model_report = std::move(model_report);
  return img;
}

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

bool show_preview(const std::vector<double>& coarse, int cw, int ch, int f, const glm::dvec3& open_xyz,
                  const glm::dvec3& open_rgb, RenderImage& img, const RenderClock& clock,
                  const std::function<void(const RenderImage&)>& progress, const std::atomic<bool>* cancel) {
  if (cancel_raised(cancel)) {
    img.converged = false;
    img.stopped = "cancelled";
    return false;
  }
  spread_preview(coarse, cw, ch, f, open_xyz, open_rgb, img);
  img.time_ms = clock.elapsed_ms();
  if (progress) progress(img);
  return true;
}

void develop_pixels(RenderImage& img, std::size_t n, std::size_t grain,
                    const std::function<std::size_t(std::size_t)>& pixel_of,
                    const std::function<glm::dvec3(std::size_t)>& xyz_of, bool mono, const glm::dvec3& white) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      const glm::dvec3 xyz = xyz_of(i);
      const glm::dvec3 rgb = mono ? glm::dvec3(xyz.y / white.y) : xyz_to_linear_srgb(xyz);
      const std::size_t pix = pixel_of(i);
      for (int c = 0; c < 3; ++c) img.xyz[pix * 3 + c] = float(xyz[c]), img.rgb[pix * 3 + c] = float(rgb[c]);
    }
  });
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

void run_progressive_passes(const ProgressivePasses& p, RenderImage& img, const RenderClock& clock,
                            const std::function<void(const RenderImage&)>& progress,
                            const std::atomic<bool>* cancel) {
  std::optional<double> last_err;
  for (int pass = 0; pass < p.passes; ++pass) {
    p.trace_pass(pass);
    if (cancel_raised(cancel)) {
      img.converged = false;
      img.stopped = "cancelled";
      return;
    }
    const int done = pass + 1;
    p.develop_image(done);
    const std::optional<double> err = p.split_half_estimate(done);
    // An odd pass keeps the last even pass's estimate (the halves are only balanced after even ones).
    if (err) last_err = err;
    img.error_estimate = last_err;
    img.passes = done + p.preview_passes;
    img.samples_per_pixel = done * p.samples_per_pass;
    const bool good_enough = p.tolerance_de2000 > 0.0 && err && *err < p.tolerance_de2000;
    // Converged means the estimate is below the tolerance, nothing else (RenderImage::converged,
    // issue 21): a render the pass cap ends is not converged, and `stopped` says it was the cap.
    img.converged = good_enough;
    if (good_enough)
      img.stopped = "tolerance";
    else if (done == p.passes)
      img.stopped = "cap";
    img.time_ms = clock.elapsed_ms();
    if (progress) progress(img);
    if (good_enough) break;
  }
}

}  // namespace pmsim
