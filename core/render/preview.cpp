#include "core/render/preview.h"

#include <algorithm>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/crystal/crystal.h"
#include "core/microscope/evaluation_plan.h"
#include "core/render/image_develop.h"
#include "core/render/preview_upsample.h"
#include "core/render/spectral_level.h"

namespace pmsim {

int preview_factor(const Scene& scene) {
  if (!scene.sample_in || scene.sample.type != SampleType::Plate) return kPreviewFactor;
  try {
    const CrystalSymmetry sym = scene.sample.crystal ? crystal_from_indices(*scene.sample.crystal).symmetry()
                                                     : find_mineral(scene.sample.mineral).symmetry();
    return sym == CrystalSymmetry::Biaxial ? kPreviewFactorBiaxial : kPreviewFactor;
  } catch (const std::exception&) {
    return kPreviewFactor;  // compile_evaluation_plan reports the error
  }
}

bool wants_preview(const Scene& scene) {
  const bool back_focal_plane = scene.mode == ViewMode::Cono && scene.bertrand_in;
  const bool per_pixel = back_focal_plane || (scene.sample_in && scene.sample.type != SampleType::Plate);
  return per_pixel && static_cast<long long>(scene.render.width) * scene.render.height >= kPreviewMinPixels;
}

bool run_preview(const Scene& scene, int factor, int pass, const std::atomic<bool>& cancel,
                 RenderClock::time_point t0, std::uint64_t generation, BufferPool* pool,
                 const std::function<void(RenderImage&&, bool)>& publish) {
  Scene c = scene;
  // Without the lens ghosts (internal reflections, optics.lens_depth ≥ 2): a fraction of a percent
  // of the light whose tracing dominated the physical lenses' preview (70–95 ms with, 15 without).
  c.optics.lens_depth = std::min(c.optics.lens_depth, 1);
  const int W = scene.render.width, H = scene.render.height;
  c.render.width = std::max(1, (W + factor - 1) / factor);
  c.render.height = std::max(1, (H + factor - 1) / factor);
  const auto compiled = compile_evaluation_plan(c, &cancel);
  if (!compiled || cancel) return false;
  const EvaluationPlan& plan = *compiled;
  const int fixed = scene.render.wavelengths;
  const SpectralLevel level =
      make_spectral_level(plan, fixed > 0 ? std::min(fixed, kPreviewBands) : kPreviewBands);
  std::vector<glm::dvec3> units(plan.units().size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, units.size(), 64),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      if (cancel.load(std::memory_order_relaxed)) return;
                      for (std::size_t u = r.begin(); u != r.end(); ++u)
                        units[u] = evaluate_unit(plan, level, static_cast<int>(u));
                    });
  if (cancel) return false;
  RenderImage coarse;
  develop_image(plan, units, level.monochromatic, coarse);
  RenderImage img = image_with_buffers(pool, W, H);
  upsample_preview(scene, plan, coarse, img);
  img.wavelengths = level.n;
  img.passes = pass;
  img.generation = generation;
  img.samples_per_pixel = static_cast<double>(level.n) / (factor * factor);
  img.model_report = "preview: 1/" + std::to_string(factor) + " resolution, " + std::to_string(level.n) +
                     " bands; " + plan.model_report();
  img.converged = false;
  img.time_ms = std::chrono::duration<double, std::milli>(RenderClock::now() - t0).count();
  publish(std::move(img), false);
  return !cancel;
}

}  // namespace pmsim
