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
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"

#include <tbb/parallel_reduce.h>

namespace pmsim {

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kFirstBands = 8;      // first pass: 50 nm bands (a coarse preview)
constexpr int kMaxBands = 4096;     // ~0.1 nm: beyond this a level costs more than it can change

// Mean CIEDE2000 between two estimates of the units, weighted by the image area each unit covers,
// over units u with u % stride == 0.
double unit_error(const MicroscopeSetup& S, const std::vector<double>& area,
                  const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b,
                  std::size_t stride) {
  const glm::dvec3 white = illuminant_white_xyz(S.scene.illuminant);
  const bool mono = S.scene.render.single_wavelength_nm > 0;
  struct Acc {
    double sum = 0.0, weight = 0.0;
  };
  const std::size_t m = (a.size() + stride - 1) / stride;
  const Acc acc = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, m, 2048), Acc{},
      [&](const tbb::blocked_range<std::size_t>& r, Acc s) {
        for (std::size_t j = r.begin(); j != r.end(); ++j) {
          const std::size_t u = j * stride;
          if (area[u] <= 0) continue;
          const glm::dvec3 xa = mono ? white * a[u].y : a[u], xb = mono ? white * b[u].y : b[u];
          s.sum += area[u] * ciede2000(xyz_to_lab(xa, white), xyz_to_lab(xb, white));
          s.weight += area[u];
        }
        return s;
      },
      [](Acc x, const Acc& y) {
        x.sum += y.sum;
        x.weight += y.weight;
        return x;
      });
  return acc.weight > 0 ? acc.sum / acc.weight : 0.0;
}

// One render from a scene to convergence (or the requested sample counts), calling `publish`
// after every pass. Progressive (the UI): every level is a full image, starting coarse. Final
// (pmsim-render): the first level is only computed on a subset of the units, enough to estimate
// the error of the next, full level. Returns false when cancelled.
template <class Publish>
bool run_render(const Scene& scene, const std::atomic<bool>& cancel, Clock::time_point t0,
                std::uint64_t generation, bool progressive, Publish&& publish) {
  auto setup = build_setup(scene, &cancel);
  if (!setup) return false;
  const MicroscopeSetup& S = *setup;
  const int fixed = scene.render.wavelengths;
  const std::size_t n_units = S.units.size();
  std::vector<double> area(n_units, 0.0);
  for (const PixelRef& r : S.refs) area[r.unit] += r.weight;
  std::vector<glm::dvec3> prev(n_units), units(n_units);
  std::size_t prev_stride = 0;  // 0: no previous level
  int passes = 0;
  const bool mono = scene.render.single_wavelength_nm > 0;
  const bool one_level = fixed > 0 || mono;
  for (int bands = one_level ? std::max(1, fixed) : (progressive ? kFirstBands : 2 * kFirstBands);; bands *= 2) {
    const SpectralLevel level = make_spectral_level(S, bands);
    const bool partial = !progressive && !one_level && prev_stride == 0;
    const std::size_t stride = partial ? std::max<std::size_t>(1, n_units / 8192) : 1;
    std::atomic<bool> stopped{false};
    const std::size_t m = (n_units + stride - 1) / stride;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m, 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        if (cancel.load(std::memory_order_relaxed)) {
                          stopped = true;
                          return;
                        }
                        for (std::size_t j = r.begin(); j != r.end(); ++j)
                          units[j * stride] = evaluate_unit(S, level, static_cast<int>(j * stride));
                      });
    if (stopped || cancel) return false;
    double err = 100.0;
    if (prev_stride > 0) err = unit_error(S, area, units, prev, std::max(prev_stride, n_units / 65536 + 1));
    if (one_level) err = 0.0;
    const bool converged = one_level || (prev_stride > 0 && err < scene.render.tolerance_de2000);
    const bool last = converged || bands >= kMaxBands;
    if (!partial) {
      ++passes;
      RenderImage img;
      develop_image(S, units, level.monochromatic, img);
      img.error_estimate = err;
      img.wavelengths = level.n;
      img.passes = passes;
      img.generation = generation;
      img.samples_per_pixel = static_cast<double>(level.n) * S.spatial_samples *
                              std::max<std::size_t>(1, S.cone_dirs.size());
      img.model_report = S.model_report + "; spectrum: " + std::to_string(level.n) +
                         (level.monochromatic ? " line" : " bands");
      img.converged = converged;
      img.time_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      publish(std::move(img), last);
    }
    if (last) return true;
    std::swap(prev, units);
    prev_stride = stride;
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
        run_render(scene, im->cancel, t0, gen, true, [&](RenderImage&& img, bool last) {
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
    run_render(scene, never, Clock::now(), 0, false, [&](RenderImage&& img, bool) {
      if (progress) progress(img);
      result = std::move(img);
    });
  });
  return result;
}

}  // namespace pmsim
