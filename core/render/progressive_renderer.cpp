#include "core/render/progressive_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/crystal/crystal.h"
#include "core/microscope/microscope_setup.h"
#include "core/microscope/scene_check.h"
#include "core/microscope/view_geometry.h"
#include "core/render/image_develop.h"
#include "core/render/spectral_level.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"

#include <tbb/parallel_reduce.h>

namespace pmsim {

namespace {

using Clock = std::chrono::steady_clock;

// Image buffers handed back by the images a renderer replaces, for the next ones. A 512² image is
// two 3 MB buffers; fresh ones cost ~3 ms of page faults and zero-filling on these machines,
// which was half of a preview (a restart on every slider step makes a preview every frame).
class BufferPool {
 public:
  // A buffer of exactly n floats, contents unspecified (every element is written by the caller).
  std::vector<float> take(std::size_t n) {
    std::vector<float> v;
    {
      std::lock_guard<std::mutex> lock(mu_);
      for (auto it = spare_.begin(); it != spare_.end(); ++it)
        if (it->size() == n) {
          v = std::move(*it);
          spare_.erase(it);
          break;
        }
    }
    v.resize(n);  // no-op for a recycled buffer of that size
    return v;
  }
  void give(std::vector<float>&& v) {
    if (v.empty()) return;
    std::lock_guard<std::mutex> lock(mu_);
    if (spare_.size() < 6) spare_.push_back(std::move(v));
  }

 private:
  std::mutex mu_;
  std::vector<std::vector<float>> spare_;
};

// An image whose rgb and xyz buffers (w·h·3 floats each) come from the pool when there is one.
RenderImage image_with_buffers(BufferPool* pool, int w, int h) {
  RenderImage img;
  img.width = w;
  img.height = h;
  const std::size_t n = static_cast<std::size_t>(w) * h * 3;
  img.rgb = pool ? pool->take(n) : std::vector<float>(n);
  img.xyz = pool ? pool->take(n) : std::vector<float>(n);
  return img;
}

constexpr int kFirstBands = 8;      // first pass: 50 nm bands (a coarse preview)
constexpr int kMaxBands = 4096;     // ~0.1 nm: beyond this a level costs more than it can change

// Mean CIEDE2000 between two estimates of the units, weighted by the image area each unit covers,
// over units u with u % stride == 0.
double unit_error(const MicroscopeSetup& S, const std::vector<double>& area,
                  const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b,
                  std::size_t stride, const std::atomic<bool>& cancel) {
  const glm::dvec3 white = illuminant_white_xyz(S.scene.illuminant);
  const bool mono = S.scene.render.single_wavelength_nm > 0;
  struct Acc {
    double sum = 0.0, weight = 0.0;
  };
  const std::size_t m = (a.size() + stride - 1) / stride;
  const Acc acc = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, m, 2048), Acc{},
      [&](const tbb::blocked_range<std::size_t>& r, Acc s) {
        if (cancel.load(std::memory_order_relaxed)) return s;  // the caller checks it next
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
// The first pass of a large conoscopic figure, thin section or wedge (what a UI shows the moment a
// control moves): the per-pixel set-up (three mode solutions per pixel of a figure; the grain or
// thickness under every pixel and sub-pixel of a section or wedge) dominates it, so it runs on a
// grid 4× coarser each way with 16 bands and is spread bilinearly over the lit pixels; the
// full-resolution passes follow. A figure is smooth on that scale except near its dark isochromes,
// a section except along its grain boundaries, which the next pass restores. A uniform plate in
// parallel light is one spectral evaluation for the whole field and needs no preview.
constexpr int kPreviewFactor = 4;
constexpr int kPreviewBands = 16;
constexpr long long kPreviewMinPixels = 256LL * 256LL;

// A biaxial figure costs ~10x more per direction (the mode search), and its isochromes are far
// apart in a thin plate: its preview grid is 8x coarser each way.
constexpr int kPreviewFactorBiaxial = 8;

// Before that preview, a glance twice as coarse again (1/8, biaxial 1/16 each way: 64² for a 512²
// field): 4× less work, so the first image of a change comes 4–10 ms after it on two idle cores
// (in the UI, whose software-GL frames share those cores, in the second frame after the change);
// the 1/4 preview follows a few milliseconds later.
constexpr int kGlanceFactor = 2;

int preview_factor(const Scene& scene) {
  if (!scene.sample_in || scene.sample.type != SampleType::Plate) return kPreviewFactor;
  try {
    const CrystalSymmetry sym = scene.sample.crystal ? crystal_from_indices(*scene.sample.crystal).symmetry()
                                                     : find_mineral(scene.sample.mineral).symmetry();
    return sym == CrystalSymmetry::Biaxial ? kPreviewFactorBiaxial : kPreviewFactor;
  } catch (const std::exception&) {
    return kPreviewFactor;  // build_setup reports the error
  }
}

bool bfp_view(const Scene& scene) { return scene.mode == ViewMode::Cono && scene.bertrand_in; }

bool wants_preview(const Scene& scene) {
  const bool per_pixel = bfp_view(scene) || (scene.sample_in && scene.sample.type != SampleType::Plate);
  return per_pixel && static_cast<long long>(scene.render.width) * scene.render.height >= kPreviewMinPixels;
}

// Returns false when cancelled.
template <class Publish>
bool run_preview(const Scene& scene, int factor, int pass, const std::atomic<bool>& cancel,
                 Clock::time_point t0, std::uint64_t generation, BufferPool* pool, Publish&& publish) {
  Scene c = scene;
  // Without the lens ghosts (internal reflections, optics.lens_depth ≥ 2): a fraction of a percent
  // of the light whose tracing dominated the physical lenses' preview (70–95 ms with, 15 without).
  c.optics.lens_depth = std::min(c.optics.lens_depth, 1);
  const int W = scene.render.width, H = scene.render.height;
  c.render.width = std::max(1, (W + factor - 1) / factor);
  c.render.height = std::max(1, (H + factor - 1) / factor);
  const int cw = c.render.width, ch = c.render.height;
  auto setup = build_setup(c, &cancel);
  if (!setup || cancel) return false;
  const MicroscopeSetup& S = *setup;
  const int fixed = scene.render.wavelengths;
  const SpectralLevel level = make_spectral_level(S, fixed > 0 ? std::min(fixed, kPreviewBands) : kPreviewBands);
  std::vector<glm::dvec3> units(S.units.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, units.size(), 64),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      if (cancel.load(std::memory_order_relaxed)) return;
                      for (std::size_t u = r.begin(); u != r.end(); ++u)
                        units[u] = evaluate_unit(S, level, static_cast<int>(u));
                    });
  if (cancel) return false;
  RenderImage coarse;
  develop_image(S, units, level.monochromatic, coarse);
  // Spread over the full grid. field_from_pixel is separable (x from the column, y from the
  // row), so the coarse-grid position and bilinear weights are tabulated once per column and
  // row; the per-pixel work is the lit test and four weighted reads (the upsampling was over half
  // of the preview when every pixel recomputed its field point and direction).
  RenderImage img = image_with_buffers(pool, W, H);
  struct Axis {
    double f2 = 0.0;           // square of the field coordinate of the pixel centre
    int c0 = 0, c1 = 0;        // the two coarse cells around it (clamped into the grid)
    float w0 = 0.0f, w1 = 0.0f;  // their bilinear weights (0 for a cell outside the grid)
    int nearest = 0;           // nearest coarse cell (clamped)
  };
  const double half_c = 0.5 * std::min(cw, ch);
  auto make_axis = [&](int n_full, int n_coarse, bool is_x) {
    std::vector<Axis> a(n_full);
    for (int i = 0; i < n_full; ++i) {
      const glm::dvec2 f = is_x ? field_from_pixel(W, H, i + 0.5, 0.5) : field_from_pixel(W, H, 0.5, i + 0.5);
      const double fc = is_x ? f.x : f.y;
      // The same field point on the coarse grid (pixel centres at i + 0.5; y grows downwards).
      const double g = is_x ? fc * half_c + 0.5 * n_coarse - 0.5 : 0.5 * n_coarse - fc * half_c - 0.5;
      const int i0 = static_cast<int>(std::floor(g));
      const float t = static_cast<float>(g - i0);
      a[i].f2 = fc * fc;
      a[i].c0 = std::clamp(i0, 0, n_coarse - 1);
      a[i].c1 = std::clamp(i0 + 1, 0, n_coarse - 1);
      a[i].w0 = (i0 >= 0 && i0 < n_coarse) ? 1.0f - t : 0.0f;
      a[i].w1 = (i0 + 1 >= 0 && i0 + 1 < n_coarse) ? t : 0.0f;
      a[i].nearest = std::clamp(static_cast<int>(std::lround(g)), 0, n_coarse - 1);
    }
    return a;
  };
  const std::vector<Axis> ax = make_axis(W, cw, true), ay = make_axis(H, ch, false);
  // Coarse cells as 7 floats: rgb, xyz, lit (1 or 0).
  std::vector<float> cell(static_cast<std::size_t>(cw) * ch * 7);
  for (std::size_t i = 0; i < static_cast<std::size_t>(cw) * ch; ++i) {
    for (int k = 0; k < 3; ++k) {
      cell[7 * i + k] = coarse.rgb[3 * i + k];
      cell[7 * i + 3 + k] = coarse.xyz[3 * i + k];
    }
    cell[7 * i + 6] = S.pixel_offset[i + 1] > S.pixel_offset[i] ? 1.0f : 0.0f;
  }
  // Back focal plane: lit where bfp_direction is (|f| ≤ 1 and |f|·NA_objective ≤ NA_condenser);
  // surely lit well inside that radius.
  const bool bfp = bfp_view(scene);
  const double rho_lit = std::min(1.0, scene.condenser.na / scene.objective.na);
  const double lit_sure = 0.99 * rho_lit * rho_lit;
  tbb::parallel_for(tbb::blocked_range<int>(0, H, 8), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y) {
      const Axis& Y = ay[y];
      const float* row0 = cell.data() + 7 * static_cast<std::size_t>(Y.c0) * cw;
      const float* row1 = cell.data() + 7 * static_cast<std::size_t>(Y.c1) * cw;
      float* out_rgb = img.rgb.data() + 3 * static_cast<std::size_t>(y) * W;
      float* out_xyz = img.xyz.data() + 3 * static_cast<std::size_t>(y) * W;
      for (int x = 0; x < W; ++x) {
        const Axis& X = ax[x];
        if (bfp) {
          // The test of bfp_direction, with the square root only near the rim.
          const double s2 = X.f2 + Y.f2;
          if (s2 > lit_sure) {
            if (!bfp_lit(scene, std::sqrt(s2))) {  // unlit: black
              for (int c3 = 0; c3 < 3; ++c3) out_rgb[3 * x + c3] = out_xyz[3 * x + c3] = 0.0f;
              continue;
            }
          }
        }
        // Four neighbours; out-of-grid ones have weight 0, unlit ones carry lit = 0.
        const float* c[4] = {row0 + 7 * X.c0, row0 + 7 * X.c1, row1 + 7 * X.c0, row1 + 7 * X.c1};
        const float w[4] = {Y.w0 * X.w0 * c[0][6], Y.w0 * X.w1 * c[1][6], Y.w1 * X.w0 * c[2][6],
                            Y.w1 * X.w1 * c[3][6]};
        const float wsum = w[0] + w[1] + w[2] + w[3];
        float acc[6];
        if (wsum > 0.0f) {
          const float inv = 1.0f / wsum;
          for (int k = 0; k < 6; ++k) acc[k] = (w[0] * c[0][k] + w[1] * c[1][k] + w[2] * c[2][k] + w[3] * c[3][k]) * inv;
        } else {  // at the rim: the nearest coarse sample
          const float* n = cell.data() + 7 * (static_cast<std::size_t>(Y.nearest) * cw + X.nearest);
          for (int k = 0; k < 6; ++k) acc[k] = n[k];
        }
        for (int c3 = 0; c3 < 3; ++c3) {
          out_rgb[3 * x + c3] = acc[c3];
          out_xyz[3 * x + c3] = acc[3 + c3];
        }
      }
    }
  });
  img.error_estimate = 100.0;
  img.wavelengths = level.n;
  img.passes = pass;
  img.generation = generation;
  img.samples_per_pixel = static_cast<double>(level.n) / (factor * factor);
  img.model_report = "preview: 1/" + std::to_string(factor) + " resolution, " + std::to_string(level.n) +
                     " bands; " + S.model_report;
  img.converged = false;
  img.time_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  publish(std::move(img), false);
  return !cancel;
}

template <class Publish>
bool run_render(const Scene& scene, const std::atomic<bool>& cancel, Clock::time_point t0, BufferPool* pool,
                std::uint64_t generation, bool progressive, Publish&& publish) {
  int passes = 0;
  if (progressive && wants_preview(scene)) {
    const int factor = preview_factor(scene);
    for (const int f : {kGlanceFactor * factor, factor}) {
      if (!run_preview(scene, f, passes + 1, cancel, t0, generation, pool, publish)) return false;
      ++passes;
    }
  }
  auto setup = build_setup(scene, &cancel);
  if (!setup) return false;
  const MicroscopeSetup& S = *setup;
  const int fixed = scene.render.wavelengths;
  const std::size_t n_units = S.units.size();
  std::vector<double> area(n_units, 0.0);
  for (const PixelRef& r : S.refs) area[r.unit] += r.weight;
  std::vector<glm::dvec3> prev(n_units), units(n_units);
  std::size_t prev_stride = 0;  // 0: no previous level
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
                        // Per unit as well: at thousands of bands a block of units takes
                        // milliseconds, and a restart waits for the block in flight.
                        for (std::size_t j = r.begin(); j != r.end(); ++j) {
                          if (cancel.load(std::memory_order_relaxed)) {
                            stopped = true;
                            return;
                          }
                          units[j * stride] = evaluate_unit(S, level, static_cast<int>(j * stride));
                        }
                      });
    if (stopped || cancel) return false;
    double err = 100.0;
    if (prev_stride > 0) err = unit_error(S, area, units, prev, std::max(prev_stride, n_units / 65536 + 1), cancel);
    if (cancel) return false;
    if (one_level) err = 0.0;
    const bool converged = one_level || (prev_stride > 0 && err < scene.render.tolerance_de2000);
    const bool last = converged || bands >= kMaxBands;
    if (!partial) {
      ++passes;
      RenderImage img = image_with_buffers(pool, S.width(), S.height());
      develop_image(S, units, level.monochromatic, img, &cancel);
      if (cancel) return false;
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
  impl_->arena = std::make_unique<tbb::task_arena>(threads > 0 ? threads : static_cast<int>(tbb::task_arena::automatic));
}

ProgressiveRenderer::~ProgressiveRenderer() { impl_->stop(); }

void ProgressiveRenderer::restart(const Scene& scene) {
  check_scene(scene);  // throws before anything stops: the previous scene keeps rendering
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
    const auto t0 = Clock::now();
    im->arena->execute([&] {
      try {
        run_render(scene, *cancel, t0, &im->pool, gen, true, [&](RenderImage&& img, bool last) {
          std::lock_guard<std::mutex> lock(im->mu);
          std::swap(im->latest, img);
          im->pool.give(std::move(img.rgb));  // the replaced image's buffers
          im->pool.give(std::move(img.xyz));
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
    run_render(scene, never, Clock::now(), nullptr, 0, false, [&](RenderImage&& img, bool) {
      if (progress) progress(img);
      result = std::move(img);
    });
  });
  return result;
}

}  // namespace pmsim
