#include "core/bench/ebsd_render.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "core/bench/bench_strategy.h"
#include "core/bench/image_error.h"
#include "core/bench/scratch_dir.h"
#include "core/ebsd/example_map.h"
#include "core/ebsd/map_writer.h"
#include "core/microscope/map_section.h"
#include "core/render/progressive_renderer.h"
#include "core/spectrum/cie.h"

namespace pmsim {

EbsdRenderResult measure_ebsd_render(std::size_t points, int threads) {
  using Clock = std::chrono::steady_clock;
  const ScratchDir scratch("ebsd-render");
  const std::string path = (scratch.path() / "quartzite.ctf").string();
  EbsdRenderResult res;
  const int side = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(points)))));
  write_ctf(example_quartzite_map(side, side, 5.0), path);
  const auto t0 = Clock::now();
  const auto section = load_map_section(path, {}, NonIndexed::Medium);
  res.load_s = std::chrono::duration<double>(Clock::now() - t0).count();
  if (const MapSectionFacts* f = map_section_facts(*section)) {
    res.points = f->points;
    res.grains = f->grains;
    res.clusters = f->clusters;
  }
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = path;
  s.objective.magnification = 4.0;
  s.render.width = s.render.height = 1024;
  res.width = res.height = 1024;
  // First image: the interactive renderer, restarted on the loaded map.
  RenderImage first;
  {
    ProgressiveRenderer r(threads);
    const double cpu1 = process_cpu_ms();
    const auto t1 = Clock::now();
    r.restart(s);
    while (!r.snapshot(first)) std::this_thread::sleep_for(std::chrono::microseconds(100));
    res.first_ms = std::chrono::duration<double, std::milli>(Clock::now() - t1).count();
    res.first_cpu_ms = process_cpu_ms() - cpu1;
    r.cancel();
  }
  const double cpu2 = process_cpu_ms();
  const auto t2 = Clock::now();
  const RenderImage conv = ProgressiveRenderer::render(s, threads);
  res.converged_ms = std::chrono::duration<double, std::milli>(Clock::now() - t2).count();
  res.converged_cpu_ms = process_cpu_ms() - cpu2;
  res.converged_error_estimate = conv.error_estimate.value_or(-1.0);
  if (first.width == conv.width && first.height == conv.height)
    res.first_vs_converged_mean_de2000 =
        image_error_de2000(first.xyz, conv.xyz, {}, illuminant_white_xyz(s.illuminant)).mean_de2000;
  else
    res.first_vs_converged_mean_de2000 = -1.0;  // a reduced-size preview: not comparable pixel by pixel
  return res;
}

}  // namespace pmsim
