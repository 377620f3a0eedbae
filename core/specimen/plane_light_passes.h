#pragma once
// What the two plane-light renderers (backward: plane_light_image.h, forward:
// forward_plane_light.h) share of their progressive passes: the image they fill, the grey preview
// spread over the full grid, the developed colours, the split-half estimate, and the pass loop
// around them (cancel, the stop rule, progress).
#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/render/render_image.h"

namespace pmsim {

// Raised by the client (polled every pixel row or every 64 pixels): the pass in flight is abandoned.
inline bool cancel_raised(const std::atomic<bool>* cancel) {
  return cancel && cancel->load(std::memory_order_relaxed);
}

// Wall time since the render started, for RenderImage::time_ms.
class RenderClock {
 public:
  double elapsed_ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count();
  }

 private:
  std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
};

// A black w × h image of `bands` spectral bands, its model_report set.
RenderImage blank_plane_light_image(int w, int h, int bands, std::string model_report);

// Spreads a grey image of cw × ch (1/f of img's size, row-major) bilinearly over img, each pixel
// v·open_xyz and v·open_rgb (v ≥ 0: a splatted estimate may undershoot 0); img then counts one
// pass of 1/f² samples a pixel, not converged.
void spread_preview(const std::vector<double>& coarse, int cw, int ch, int f, const glm::dvec3& open_xyz,
                    const glm::dvec3& open_rgb, RenderImage& img);

// The preview's end: if cancel was raised while it was traced, img stays unconverged, stopped
// "cancelled", and false is returned (the caller returns img); else the coarse image is spread over img (spread_preview),
// timed and shown to `progress`.
bool show_preview(const std::vector<double>& coarse, int cw, int ch, int f, const glm::dvec3& open_xyz,
                  const glm::dvec3& open_rgb, RenderImage& img, const RenderClock& clock,
                  const std::function<void(const RenderImage&)>& progress, const std::atomic<bool>* cancel);

// Writes the developed colour `xyz_of(i)` of n items into img at pixel `pixel_of(i)`, with its
// display RGB (mono: grey, Y relative to the illuminant's white).
void develop_pixels(RenderImage& img, std::size_t n, std::size_t grain,
                    const std::function<std::size_t(std::size_t)>& pixel_of,
                    const std::function<glm::dvec3(std::size_t)>& xyz_of, bool mono, const glm::dvec3& white);

// Mean CIEDE2000 between the even and odd passes' colours (`half_xyz(i, 0 or 1)`) of n items,
// over at most 65536 of them taken at an even stride.
double split_half_de2000(std::size_t n, const std::function<glm::dvec3(std::size_t, int)>& half_xyz,
                         const glm::dvec3& white);

// The progressive loop: `passes` passes, each traced by trace_pass(pass), then (unless cancel was
// raised: img is left unconverged, stopped "cancelled") developed into img by develop_image(done)
// and judged by split_half_estimate(done) (none: the halves are not comparable yet). img counts
// the preview as a pass. It is converged only once an estimate is below the tolerance (> 0),
// which ends the render early (stopped "tolerance"); the last pass without that ends it unconverged,
// stopped "cap" (RenderImage::converged, ::stopped).
struct ProgressivePasses {
  int passes = 1;
  int preview_passes = 0;        // 1 when the options asked for a preview
  double samples_per_pass = 1;   // RenderImage::samples_per_pixel per pass
  double tolerance_de2000 = 0;   // > 0: stop once the split-half estimate is below it
  std::function<void(int pass)> trace_pass;
  std::function<void(int done)> develop_image;
  std::function<std::optional<double>(int done)> split_half_estimate;
};
void run_progressive_passes(const ProgressivePasses& p, RenderImage& img, const RenderClock& clock,
                            const std::function<void(const RenderImage&)>& progress,
                            const std::atomic<bool>* cancel);

}  // namespace pmsim
