#include "core/bench/grain_mount_bench.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <string>
#include <cstdio>

#include "core/bench/bench_strategy.h"  // process_cpu_ms
#include "core/bench/image_error.h"
#include "core/specimen/forward_plane_light.h"
#include "core/specimen/grain_mount_render.h"
#include "core/specimen/section_slab.h"
#include "core/spectrum/cie.h"

namespace pmsim {

namespace {

// The rows of one refracting specimen, rendered as the product renders it; `prefix` names the
// polars ("plane-light", "crossed-polars") in the strategy names.
using Renderer = RenderImage (*)(const SpecimenScene&, const PlaneLightOptions&,
                                 const std::function<void(const RenderImage&)>&, InterfaceCounters*,
                                 const std::atomic<bool>*);

std::vector<BenchRow> specimen_rows(const std::string& name, const std::string& prefix, const Scene& scene,
                                    const SpecimenScene& specimen, double build_ms, std::ostream& log,
                                    Renderer render) {
  const int size = scene.render.width;
  // The reference: 256 traces a pixel with another seed (its own split-half estimate is logged
  // and recorded on its row), so the rows below are measured against an independent image.
  PlaneLightOptions ref_opt = plane_light_options(scene);
  // 256 traces a pixel. Plane light: the colour traced from every point (chroma_period 1, 9
  // traces a pixel a pass), since the product's comes from a subgrid (forward_plane_light.h) and a
  // reference sharing it would not see its blur (granite 256²: the product's rows measured the
  // same, 0.18–0.21, against both). With the analyzer in every point would trace 33 (8 passes in
  // 256: split-half estimate 4.3 on the granite), so that reference keeps the subgrid (0.90).
  ref_opt.spp = 256;
  ref_opt.chroma_period = ref_opt.analyzer_in ? 0 : 1;
  ref_opt.tolerance_de2000 = 0.0;
  ref_opt.preview_factor = 0;
  ref_opt.seed = 2;
  const double ref_cpu0 = process_cpu_ms();
  const RenderImage ref = render(specimen, ref_opt, nullptr, nullptr, nullptr);
  const double ref_cpu_ms = process_cpu_ms() - ref_cpu0;
  log << ref.time_ms << " ms, its split-half estimate ΔE00 " << ref.error_estimate.value_or(-1.0) << "\n";
  const glm::dvec3 white = illuminant_white_xyz(scene.illuminant);

  std::vector<BenchRow> rows;
  auto add = [&](const std::string& strategy, const RenderImage& img, double cpu_ms, const std::string& code,
                 const std::string& report) {
    const ImageError e = image_error_de2000(img.xyz, ref.xyz, {}, white);
    BenchRow row;
    row.scene = name;
    row.strategy = strategy;
    row.width = row.height = size;
    row.time_ms = img.time_ms;
    row.cpu_ms = cpu_ms;  // all threads: on a shared machine cpu_ms / cores estimates the unloaded wall time
    row.mean_de2000 = e.mean_de2000;
    row.p95_de2000 = e.p95_de2000;
    row.max_de2000 = e.max_de2000;
    row.wavelengths = ref.wavelengths;
    row.renderer_estimate = img.error_estimate.value_or(-1.0);
    row.code = code;
    row.model_report = report + " (" + std::to_string(img.samples_per_pixel) + " paths a pixel; specimen build " +
                       std::to_string(int(build_ms)) + " ms not included)";
    log << "  " << strategy << ": " << img.time_ms << " ms (cpu " << cpu_ms << " ms), mean ΔE00 " << e.mean_de2000
        << ", estimate " << img.error_estimate.value_or(-1.0) << "\n";
    rows.push_back(row);
  };
  add(prefix + "-reference", ref, ref_cpu_ms, "bench-side", "the reference against itself (0 by definition)");
  // The product's progressive render as the app runs it (preview, passes, stop at a split-half
  // estimate below 1), capped at 256 paths a pixel; the image at 64 paths is taken on the way.
  PlaneLightOptions opt = plane_light_options(scene);
  opt.spp = 256;
  opt.tolerance_de2000 = 1.0;
  RenderImage preview, first, at64;
  double preview_cpu_ms = 0.0, first_cpu_ms = 0.0, at64_cpu_ms = 0.0;
  const double cpu0 = process_cpu_ms();
  const RenderImage done = render(specimen, opt, [&](const RenderImage& img) {
    if (img.passes == 1) preview = img, preview_cpu_ms = process_cpu_ms() - cpu0;
    if (img.passes == 2) first = img, first_cpu_ms = process_cpu_ms() - cpu0;
    // The first image with 64 paths a pixel or more (a crossed-polar pass traces 18).
    if (at64.passes == 0 && img.samples_per_pixel >= 64) at64 = img, at64_cpu_ms = process_cpu_ms() - cpu0;
  }, nullptr, nullptr);
  const double done_cpu_ms = process_cpu_ms() - cpu0;
  // Stopped at the tolerance before 64 paths: the 64-path image is the final one.
  if (at64.passes == 0) at64 = done, at64_cpu_ms = done_cpu_ms;
  add(prefix + "-preview", preview, preview_cpu_ms, "product", "1/4-size preview, one path a pixel");
  add(prefix + "-first-pass", first, first_cpu_ms, "product", done.model_report);
  add(prefix + "-64spp", at64, at64_cpu_ms, "product", done.model_report);
  add(prefix + "-256spp-or-tolerance-1", done, done_cpu_ms, "product",
      done.model_report + (done.samples_per_pixel < 256 ? ", stopped at estimate < 1" : ", estimate not below 1"));
  return rows;
}

// Times the build of a specimen and logs it (`what` counts its parts), then its rows.
template <class Build, class Count>
std::vector<BenchRow> timed_specimen_rows(const std::string& name, const std::string& prefix, const Scene& scene,
                                          Build build, Count count, std::ostream& log,
                                          Renderer render) {
  log << "scene " << name << ": specimen… " << std::flush;
  const auto t0 = std::chrono::steady_clock::now();
  const auto specimen = build(scene);
  const double build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  log << count(*specimen) << ", " << build_ms << " ms; reference… " << std::flush;
  return specimen_rows(name, prefix, scene, *specimen, build_ms, log, render);
}

Scene grain_mount_scene(const std::string& mineral, int size) {
  Scene scene;
  scene.sample.type = SampleType::Grains;
  scene.sample.mineral = mineral;
  scene.sample.medium_index = 1.54;
  scene.render.width = scene.render.height = size;
  return scene;
}

std::string fragments(const SpecimenScene& s) { return std::to_string(s.fragment_count()) + " fragments"; }

}  // namespace

const std::vector<std::string>& specimen_bench_strategy_suffixes() {
  static const std::vector<std::string> suffixes = {"reference", "preview", "first-pass", "64spp",
                                                    "256spp-or-tolerance-1"};
  return suffixes;
}

std::vector<BenchRow> grain_mount_bench_rows(int size, std::ostream& log) {
  Scene scene = grain_mount_scene("garnet", size);
  scene.focus_um = 5.0;
  scene.analyzer_in = false;  // plane light (a default Scene has the analyzer in)
  return timed_specimen_rows("grain-mount-garnet-1.54", "plane-light", scene, grain_mount_specimen, fragments, log,
                             render_plane_light_forward);
}

std::vector<BenchRow> crossed_polar_grain_bench_rows(int size, std::ostream& log) {
  // Crossed polars: polarizer 0°, analyzer 90° (the Scene's defaults); at most 256² (32 bands).
  const Scene scene = grain_mount_scene("calcite", std::min(size, 256));
  return timed_specimen_rows("grain-mount-calcite-crossed", "crossed-polars", scene, grain_mount_specimen, fragments,
                             log, render_plane_light_forward);
}

std::vector<BenchRow> section_relief_bench_rows(int size, std::ostream& log) {
  Scene scene;
  scene.sample.type = SampleType::Section;
  scene.sample.section = "granite_hand_placed";
  scene.analyzer_in = false;
  scene.render.width = scene.render.height = size;
  return timed_specimen_rows(
      "section-granite-plane-light", "plane-light", scene, section_slab,
      [](const SpecimenScene& s) { return std::to_string(s.triangle_count()) + " triangles"; }, log,
      render_plane_light_forward);
}

std::vector<BenchRow> section_crossed_bench_rows(int size, std::ostream& log) {
  Scene scene;  // crossed polars: the Scene's defaults
  scene.sample.type = SampleType::Section;
  scene.sample.section = "granite_hand_placed";
  scene.render.width = scene.render.height = std::min(size, 256);
  return timed_specimen_rows(
      "section-granite-crossed", "crossed-polars", scene, section_slab,
      [](const SpecimenScene& s) { return std::to_string(s.triangle_count()) + " triangles"; }, log,
      render_plane_light_forward);
}

}  // namespace pmsim
