#pragma once
// The ways of rendering a bench scene that pmsim-bench compares. "Product" strategies call the
// renderer itself (ProgressiveRenderer with scene settings); "bench-side" ones are spectral
// sampling schemes the renderer does not offer (RGB, stratified and hero wavelengths per pixel),
// evaluated here on the renderer's own evaluation plan (compile_evaluation_plan: domains, units, pixel
// references) and the crystal's exact Jones matrix, then developed with the renderer's develop_image, so that
// only the choice of wavelengths differs.
#include <string>
#include <vector>

#include "core/bench/bench_scenes.h"

namespace pmsim {

enum class StrategyKind {
  Product,       // ProgressiveRenderer::render of the scene with `settings` applied
  FirstPass,     // the first progressive pass of ProgressiveRenderer (interactive preview)
  SecondPass,    // its second pass (for a large field: the 1/4-resolution preview after the glance)
  StageDrag,     // a scripted stage drag: each frame's restart waited on to its converged image
  FigureDrag,    // the same drag composed from the figure's response (figure_response.h)
  Rgb,           // bench-side: 3 wavelengths (610, 550, 465 nm) as the linear sRGB channels
  Stratified,    // bench-side: n strata of 400/n nm, one jittered wavelength each, per unit
  Hero,          // bench-side: hero wavelength + n−1 equally spaced companions, per unit
  PhysicalLens,  // bench-side: condenser and objective as SML lenses (physical_lens_model.h)
};

struct BenchStrategy {
  std::string name;
  StrategyKind kind = StrategyKind::Product;
  std::vector<std::string> settings;  // "key=value" applied to the scene first
  int wavelengths = 0;                // bench-side sample count
  bool product() const {
    return kind == StrategyKind::Product || kind == StrategyKind::FirstPass ||
           kind == StrategyKind::SecondPass || kind == StrategyKind::StageDrag || kind == StrategyKind::FigureDrag;
  }
};

// Frames of the stage drag (1° each).
constexpr int kStageDragFrames = 30;

struct StrategyResult {
  std::vector<float> xyz;        // width·height·3
  double time_ms = 0.0;          // wall time of the whole render (set-up included); stage drag:
                                 // the mean per frame
  int wavelengths = 0;           // spectral samples per unit (renderer: its band count)
  double error_estimate = -1.0;  // the renderer's own estimate (product strategies); -1: none
  double cpu_ms = -1.0;          // ≥ 0: process CPU time of the measured part alone (the first
                                 // pass excludes its warm-up); < 0: the caller measures it
  std::string model_report;
};

// quick: fewer strategies. Strategies that do not apply to a scene are left out.
std::vector<BenchStrategy> bench_strategies(const BenchScene& scene, bool quick);

// CPU time of this process so far (all threads, user + system), ms: what the rows' cpu_ms count.
double process_cpu_ms();

// threads: 0 = all cores. Throws InputError if a setting is rejected.
StrategyResult run_strategy(const Scene& scene, const BenchStrategy& strategy, int threads);

}  // namespace pmsim
