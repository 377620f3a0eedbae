#include "core/render/progressive_renderer.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/ebsd/read_orientation_map.h"
#include "core/microscope/evaluation_plan.h"
#include "core/microscope/map_section.h"
#include "core/microscope/scene_check.h"
#include "core/render/buffer_pool.h"
#include "core/render/convergence_metric.h"
#include "core/render/image_develop.h"
#include "core/render/preview.h"
#include "core/render/spectral_level.h"

namespace pmsim {

namespace {

constexpr int kFirstBands = 8;  // first pass: 50 nm bands (a coarse preview)

// One render from a scene to convergence (or the requested sample counts), calling `publish`
// after every pass. Progressive (the UI): every level is a full image, starting coarse. Final
// (pmsim-render): the first level is only computed on a subset of the units, enough to estimate
// the error of the next, full level. Returns false when cancelled.
//
// How it stops (RenderImage::stopped, converged):
//   - "tolerance": the estimate (this level against the previous one) fell below
//     render.tolerance; converged.
//   - "cap": render.wavelengths fixes the one full level, or the levels reached
//     kProgressiveMaxBands first. With render.wavelengths = N ≥ 2 a subset of the units (a
//     partial level, as the final render's first) is evaluated at N/2 bands first, so the capped
//     image still carries an estimate ("the estimate at the stop"); converged only if that
//     estimate is below the tolerance too. N = 1 has no lower level: no estimate, not converged.
//   - A monochromatic render (render.single_wavelength_nm) is one spectral line: the levels
//     refine nothing else (the spatial sampling is the plan's, fixed), so its one level is the
//     exact image the estimate measures against: estimate 0, "tolerance", converged — whatever
//     render.wavelengths says.
// render.spp sets the plan's spatial samples, not a number of passes: it never stops this renderer.
template <class Publish>
bool run_render(const Scene& scene, const std::atomic<bool>& cancel, RenderClock::time_point t0,
                BufferPool* pool, std::uint64_t generation, bool progressive, Publish&& publish) {
  int passes = 0;
  if (progressive && wants_preview(scene)) {
    const int factor = preview_factor(scene);
    for (const int f : {kGlanceFactor * factor, factor}) {
      if (!run_preview(scene, f, passes + 1, cancel, t0, generation, pool, publish)) return false;
      ++passes;
    }
  }
  const auto compiled = compile_evaluation_plan(scene, &cancel);
  if (!compiled) return false;
  const EvaluationPlan& plan = *compiled;
  const int fixed = scene.render.wavelengths;
  const std::size_t n_units = plan.units().size();
  std::vector<double> area(n_units, 0.0);
  for (const PixelRef& r : plan.refs()) area[r.unit] += r.weight;
  std::vector<glm::dvec3> prev(n_units), units(n_units);
  std::size_t prev_stride = 0;  // 0: no previous level
  const bool mono = scene.render.single_wavelength_nm > 0;
  const bool capped = !mono && fixed > 0;                // one full level of `fixed` bands
  const bool estimate_first = capped && fixed >= 2;      // its estimate from a partial level at fixed/2
  int bands = mono ? std::max(1, fixed)
              : capped ? (estimate_first ? fixed / 2 : fixed)
                       : (progressive ? kFirstBands : 2 * kFirstBands);
  for (;;) {
    const SpectralLevel level = make_spectral_level(plan, bands);
    const bool partial = prev_stride == 0 && (estimate_first || (!progressive && !capped && !mono));
    const std::size_t stride = partial ? std::max<std::size_t>(1, n_units / 8192) : 1;
    std::atomic<bool> stopped{false};
    const std::size_t m = (n_units + stride - 1) / stride;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m, 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        if (cancel.load(std::memory_order_relaxed)) {
                          stopped = true;
                          return;
                        }
                        // Per unit as well: at thousands of bands a block of units takes
                        // milliseconds, and a restart waits for the block in flight.
                        for (std::size_t j = r.begin(); j != r.end(); ++j) {
                          if (cancel.load(std::memory_order_relaxed)) {
                            stopped = true;
                            return;
                          }
                          units[j * stride] = evaluate_unit(plan, level, static_cast<int>(j * stride));
                        }
                      });
    if (stopped || cancel) return false;
    // The error of this level against the previous one: unknown for the first level.
    std::optional<double> err;
    if (prev_stride > 0)
      err = unit_error(plan, area, units, prev, std::max(prev_stride, n_units / 65536 + 1), cancel);
    if (cancel) return false;
    if (mono) err = 0.0;  // exact (see above)
    const bool below = err && *err < scene.render.tolerance_de2000;
    const bool last = !partial && (mono || capped || below || bands >= kProgressiveMaxBands);
    if (!partial) {
      ++passes;
      RenderImage img = image_with_buffers(pool, plan.width(), plan.height());
      develop_image(plan, units, level.monochromatic, img, &cancel);
      if (cancel) return false;
      img.error_estimate = err;
      img.wavelengths = level.n;
      img.passes = passes;
      img.generation = generation;
      img.samples_per_pixel = static_cast<double>(level.n) * plan.spatial_samples() *
                              std::max<std::size_t>(1, plan.cone_dirs().size());
      img.model_report = plan.model_report() + "; spectrum: " + std::to_string(level.n) +
                         (level.monochromatic ? " line" : " bands");
      img.converged = below;
      if (last) img.stopped = (mono || (!capped && below)) ? "tolerance" : "cap";
      img.time_ms = std::chrono::duration<double, std::milli>(RenderClock::now() - t0).count();
      publish(std::move(img), last);
    }
    if (last) return true;
    std::swap(prev, units);
    prev_stride = stride;
    bands = capped ? fixed : 2 * bands;
  }
}

}  // namespace

// Each restart gets its own worker thread and cancel flag. A restart cancels the worker in flight
// and joins it before the new one starts: two renders in one TBB arena at once would make TBB's
// own (uninstrumented) task recycling race in ThreadSanitizer's eyes, and the set-up polls its
// flag often enough (every pixel row, unit block, ghost row and develop row) that the join is
// short. interrupt() raises the flag from any thread without waiting.
struct ProgressiveRenderer::Impl {
  int threads = 0;
  std::unique_ptr<tbb::task_arena> arena;
  BufferPool pool;
  std::thread worker;
  mutable std::mutex mu;  // the state below
  mutable std::condition_variable cv;
  std::shared_ptr<std::atomic<bool>> current_cancel;  // the flag of `worker`
  RenderImage latest;
  bool have_image = false;
  bool running = false;
  std::uint64_t generation = 0;

  void stop() {
    {
      std::lock_guard<std::mutex> lock(mu);
      if (current_cancel) current_cancel->store(true);
    }
    if (worker.joinable()) worker.join();
    std::lock_guard<std::mutex> lock(mu);
    running = false;
    cv.notify_all();
  }
};

ProgressiveRenderer::ProgressiveRenderer(int threads) : impl_(std::make_unique<Impl>()) {
  impl_->threads = threads;
  impl_->arena =
      std::make_unique<tbb::task_arena>(threads > 0 ? threads : static_cast<int>(tbb::task_arena::automatic));
}

ProgressiveRenderer::~ProgressiveRenderer() { impl_->stop(); }

void ProgressiveRenderer::restart(const Scene& scene) {
  check_scene(scene);  // throws before anything stops: the previous scene keeps rendering
  // An EBSD map is read (once: cached) here too, so that a bad map file or an unmapped phase is
  // refused like a bad key instead of rendering nothing. Not in check_scene: a scene file whose
  // map needs sample.phases must still load, for a --set or the UI to supply them.
  if (scene.sample_in && scene.sample.type == SampleType::Section && is_orientation_map_path(scene.sample.section))
    load_scene_section(scene);
  Impl* im = impl_.get();
  im->stop();
  auto cancel = std::make_shared<std::atomic<bool>>(false);
  std::uint64_t gen;
  {
    std::lock_guard<std::mutex> lock(im->mu);
    gen = ++im->generation;
    im->running = true;
    im->current_cancel = cancel;
  }
  im->worker = std::thread([im, scene, gen, cancel] {
    const auto t0 = RenderClock::now();
    im->arena->execute([&] {
      try {
        const bool finished = run_render(scene, *cancel, t0, &im->pool, gen, true, [&](RenderImage&& img, bool last) {
          std::lock_guard<std::mutex> lock(im->mu);
          std::swap(im->latest, img);
          im->pool.give(std::move(img.rgb));  // the replaced image's buffers
          im->pool.give(std::move(img.xyz));
          im->have_image = true;
          if (last) im->running = false;
          im->cv.notify_all();
        });
        if (!finished) {
          // Cancelled before the end: the last image of this work says so (a later restart's
          // images have their own generation and are not touched).
          std::lock_guard<std::mutex> lock(im->mu);
          if (im->have_image && im->latest.generation == gen) im->latest.stopped = "cancelled";
        }
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

void ProgressiveRenderer::interrupt() {
  std::lock_guard<std::mutex> lock(impl_->mu);
  if (impl_->current_cancel) impl_->current_cancel->store(true);
}

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
  const std::string& stopped = impl_->latest.stopped;
  return !impl_->running && impl_->have_image && (stopped == "tolerance" || stopped == "cap") &&
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
    run_render(scene, never, RenderClock::now(), nullptr, 0, false, [&](RenderImage&& img, bool) {
      if (progress) progress(img);
      result = std::move(img);
    });
  });
  return result;
}

}  // namespace pmsim
