#include "core/bench/crossed_polar_grain_bench.h"

#include <algorithm>
#include <chrono>

#include "core/bench/bench_strategy.h"  // process_cpu_ms
#include "core/bench/image_error.h"
#include "core/specimen/grain_mount_render.h"
#include "core/spectrum/cie.h"

namespace pmsim {

std::vector<BenchRow> crossed_polar_grain_bench_rows(int size, std::ostream& log) {
  Scene scene;
  scene.sample.type = SampleType::Grains;
  scene.sample.mineral = "calcite";
  scene.sample.medium_index = 1.54;
  scene.analyzer_in = true;  // crossed polars: polarizer 0°, analyzer 90° (the Scene's defaults)
  scene.render.width = scene.render.height = std::min(size, 256);
  const int side = scene.render.width;
  const std::string name = "grain-mount-calcite-crossed";
  log << "scene " << name << ": specimen… " << std::flush;
  const auto t0 = std::chrono::steady_clock::now();
  const auto specimen = grain_mount_specimen(scene);
  const double build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  log << specimen->fragment_count() << " fragments, " << build_ms << " ms; reference… " << std::flush;

  constexpr int kReferenceSpp = 1024, kSpp = 64;
  PlaneLightOptions ref_opt = plane_light_options(scene);
  ref_opt.spp = kReferenceSpp;
  ref_opt.seed = 2;
  std::vector<float> half_xyz;
  double half_ms = 0.0, half_cpu_ms = 0.0;
  const double ref_cpu0 = process_cpu_ms();
  const RenderImage ref = render_plane_light(*specimen, ref_opt, [&](const RenderImage& img) {
    if (half_xyz.empty() && img.samples_per_pixel >= kReferenceSpp / 2)
      half_xyz = img.xyz, half_ms = img.time_ms, half_cpu_ms = process_cpu_ms() - ref_cpu0;
  });
  log << ref.time_ms << " ms\n";
  const glm::dvec3 white = illuminant_white_xyz(scene.illuminant);

  std::vector<BenchRow> rows;
  auto add = [&](const std::string& strategy, const std::vector<float>& xyz, double time_ms, double cpu_ms, int spp,
                 const std::string& code, const std::string& report) {
    const ImageError e = image_error_de2000(xyz, ref.xyz, {}, white);
    BenchRow row;
    row.scene = name;
    row.strategy = strategy;
    row.width = row.height = side;
    row.time_ms = time_ms;
    row.cpu_ms = cpu_ms;  // all threads: on a shared machine cpu_ms / cores estimates the unloaded wall time
    row.mean_de2000 = e.mean_de2000;
    row.p95_de2000 = e.p95_de2000;
    row.max_de2000 = e.max_de2000;
    row.wavelengths = ref.wavelengths;
    row.code = code;
    row.model_report = report + " (" + std::to_string(spp) + " samples a pixel; specimen build " +
                       std::to_string(int(build_ms)) + " ms not included)";
    log << "  " << strategy << ": " << time_ms << " ms, mean ΔE00 " << e.mean_de2000 << "\n";
    rows.push_back(row);
  };
  add("crossed-polars-reference-half", half_xyz, half_ms, half_cpu_ms, kReferenceSpp / 2, "bench-side",
      "the reference at half its samples");
  PlaneLightOptions opt = plane_light_options(scene);
  opt.spp = kSpp;
  RenderImage first;
  double first_cpu_ms = 0.0;
  const double cpu0 = process_cpu_ms();
  const RenderImage done = render_plane_light(*specimen, opt, [&](const RenderImage& img) {
    if (img.passes == 1) first = img, first_cpu_ms = process_cpu_ms() - cpu0;
  });
  const double done_cpu_ms = process_cpu_ms() - cpu0;
  add("crossed-polars-first-pass", first.xyz, first.time_ms, first_cpu_ms, int(first.samples_per_pixel), "product",
      done.model_report);
  add("crossed-polars-64spp", done.xyz, done.time_ms, done_cpu_ms, int(done.samples_per_pixel), "product",
      done.model_report);
  return rows;
}

}  // namespace pmsim
