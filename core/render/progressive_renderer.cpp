#include "core/render/progressive_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <thread>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/microscope/microscope_setup.h"
#include "core/microscope/scene_check.h"
#include "core/render/image_develop.h"
#include "core/render/spectral_level.h"

namespace pmsim {

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kFirstBands = 8;      // first pass: 50 nm bands (a coarse preview)
constexpr int kMaxBands = 4096;     // ~0.1 nm: beyond this a level costs more than it can change

// One render from a scene to convergence (or the requested sample counts), calling `publish`
// after every pass. Returns false when cancelled.
template <class Publish>
bool run_render(const Scene& scene, const std::atomic<bool>& cancel, Clock::time_point t0,
                std::uint64_t generation, Publish&& publish) {
  auto setup = build_setup(scene, &cancel);
  if (!setup) return false;
  const MicroscopeSetup& S = *setup;
  const int fixed = scene.render.wavelengths;
  std::vector<glm::dvec3> prev_units, units(S.units.size());
  std::vector<float> prev_xyz;
  int passes = 0;
  for (int bands = fixed > 0 ? fixed : kFirstBands;; bands *= 2) {
    const SpectralLevel level = make_spectral_level(S, bands);
    std::atomic<bool> stopped{false};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, S.units.size(), 512),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        if (cancel.load(std::memory_order_relaxed)) {
                          stopped = true;
                          return;
                        }
                        for (std::size_t u = r.begin(); u != r.end(); ++u)
                          units[u] = evaluate_unit(S, level, static_cast<int>(u));
                      });
    if (stopped || cancel) return false;
    ++passes;
    RenderImage img;
    develop_image(S, units, level.monochromatic, img);
    const bool done_fixed = fixed > 0 || level.monochromatic;
    double err = 0.0;
    if (!prev_xyz.empty()) err = mean_ciede2000(S, img.xyz, prev_xyz);
    img.error_estimate = prev_xyz.empty() && !done_fixed ? 100.0 : err;
    img.wavelengths = level.n;
    img.passes = passes;
    img.generation = generation;
    img.samples_per_pixel =
        static_cast<double>(level.n) * S.spatial_samples * std::max<std::size_t>(1, S.cone_dirs.size());
    img.model_report = S.model_report + "; spectrum: " + std::to_string(level.n) +
                       (level.monochromatic ? " line" : " bands");
    const bool converged = done_fixed || (!prev_xyz.empty() && err < scene.render.tolerance_de2000);
    const bool last = converged || bands >= kMaxBands;
    img.converged = converged;
    img.time_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    prev_xyz = img.xyz;
    publish(std::move(img), last);
    if (last) return true;
  }
}

}  // namespace

struct ProgressiveRenderer::Impl {
  int threads = 0;
  std::unique_ptr<tbb::task_arena> arena;
  std::thread worker;
  std::atomic<bool> cancel{false};
  mutable std::mutex mu;
  mutable std::condition_variable cv;
  RenderImage latest;
  bool have_image = false;
  bool running = false;
  std::uint64_t generation = 0;

  void stop() {
    cancel = true;
    if (worker.joinable()) worker.join();
    std::lock_guard<std::mutex> lock(mu);
    running = false;
    cv.notify_all();
  }
};

ProgressiveRenderer::ProgressiveRenderer(int threads) : impl_(std::make_unique<Impl>()) {
  impl_->threads = threads;
  impl_->arena = std::make_unique<tbb::task_arena>(threads > 0 ? threads : static_cast<int>(tbb::task_arena::automatic));
}

ProgressiveRenderer::~ProgressiveRenderer() { impl_->stop(); }

void ProgressiveRenderer::restart(const Scene& scene) {
  check_scene(scene);  // throws before anything stops: the previous scene keeps rendering
  impl_->stop();
  std::uint64_t gen;
  {
    std::lock_guard<std::mutex> lock(impl_->mu);
    gen = ++impl_->generation;
    impl_->running = true;
  }
  impl_->cancel = false;
  Impl* im = impl_.get();
  im->worker = std::thread([im, scene, gen] {
    const auto t0 = Clock::now();
    im->arena->execute([&] {
      try {
        run_render(scene, im->cancel, t0, gen, [&](RenderImage&& img, bool last) {
          std::lock_guard<std::mutex> lock(im->mu);
          im->latest = std::move(img);
          im->have_image = true;
          if (last) im->running = false;
          im->cv.notify_all();
        });
      } catch (...) {
        // A scene that passed validation but failed to build (e.g. a section file removed since):
        // nothing to show; wait() returns.
      }
    });
    std::lock_guard<std::mutex> lock(im->mu);
    im->running = false;
    im->cv.notify_all();
  });
}

void ProgressiveRenderer::cancel() { impl_->stop(); }

bool ProgressiveRenderer::snapshot(RenderImage& out) const {
  std::lock_guard<std::mutex> lock(impl_->mu);
  if (!impl_->have_image) return false;
  if (out.generation == impl_->latest.generation && out.passes == impl_->latest.passes &&
      out.width == impl_->latest.width)
    return false;
  out = impl_->latest;
  return true;
}

bool ProgressiveRenderer::wait(double timeout_s) const {
  std::unique_lock<std::mutex> lock(impl_->mu);
  const auto pred = [&] { return !impl_->running; };
  if (timeout_s >= 1e9)
    impl_->cv.wait(lock, pred);
  else
    impl_->cv.wait_for(lock, std::chrono::duration<double>(timeout_s), pred);
  return !impl_->running && impl_->have_image && impl_->latest.converged &&
         impl_->latest.generation == impl_->generation;
}

RenderImage ProgressiveRenderer::render(const Scene& scene, int threads) {
  return render(scene, threads, nullptr);
}

RenderImage ProgressiveRenderer::render(const Scene& scene, int threads,
                                        const std::function<void(const RenderImage&)>& progress) {
  check_scene(scene);
  std::atomic<bool> never{false};
  RenderImage result;
  tbb::task_arena arena(threads > 0 ? threads : static_cast<int>(tbb::task_arena::automatic));
  arena.execute([&] {
    run_render(scene, never, Clock::now(), 0, [&](RenderImage&& img, bool) {
      if (progress) progress(img);
      result = std::move(img);
    });
  });
  return result;
}

}  // namespace pmsim
