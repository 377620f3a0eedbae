#pragma once
// The progressive renderer: accumulates spectral samples per pixel across passes in double,
// develops them to colour only when asked, and can be restarted the moment a setting changes.
// Work runs on TBB worker threads; restart() and snapshot() never block for a whole pass, so a UI
// thread can call them every frame.
#include <atomic>
#include <functional>
#include <memory>

#include "core/microscope/scene.h"
#include "core/render/render_image.h"

namespace pmsim {

// The finest spectral level (~0.1 nm bands: beyond this a level costs more than it can change):
// a render without render.wavelengths that has not met its tolerance by then stops here, "cap".
inline constexpr int kProgressiveMaxBands = 4096;

// Final images carry why they stopped (RenderImage::stopped): "tolerance" (the estimate fell below
// render.tolerance; converged), "cap" (render.wavelengths, or kProgressiveMaxBands first; converged
// only if the estimate is below the tolerance too), "cancelled" (the instance's last image when
// its work was cancelled or interrupted before the end). The rules, with a monochromatic render's
// (its one level is exact): progressive_renderer.cpp, run_render.
class ProgressiveRenderer {
 public:
  explicit ProgressiveRenderer(int threads = 0);  // 0: all cores
  ~ProgressiveRenderer();
  ProgressiveRenderer(const ProgressiveRenderer&) = delete;
  ProgressiveRenderer& operator=(const ProgressiveRenderer&) = delete;

  // Cancels the work in flight and starts accumulating the new scene. Throws InputError if the
  // scene is invalid (and then keeps rendering the previous one).
  void restart(const Scene& scene);
  void cancel();  // stops work; snapshot() keeps the last image
  // Asks the work in flight to stop and returns at once (thread-safe, never blocks): a UI calls
  // it the moment a control moves, so the cores are free before restart() (on another thread)
  // takes the new scene. Harmless if nothing runs; restart() clears it for the new work.
  void interrupt();

  // Copies the latest developed image into `out`; returns false if nothing new since `generation`
  // and `passes` of `out` (so a UI uploads a texture only when something changed).
  bool snapshot(RenderImage& out) const;

  // Blocks until the render of the current scene has finished (stopped at the tolerance or a cap),
  // been cancelled, or the timeout; returns whether it finished with its final image on hand
  // (stopped "tolerance" or "cap": a capped render counts, though its `converged` may be false).
  bool wait(double timeout_s = 1e30) const;

  // Renders a scene to convergence on the calling thread's TBB arena; what pmsim-render uses.
  static RenderImage render(const Scene& scene, int threads = 0);
  // The same, calling `progress` with each pass's image (on the calling thread) — the CLI's
  // progress bar.
  static RenderImage render(const Scene& scene, int threads,
                            const std::function<void(const RenderImage&)>& progress);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pmsim
