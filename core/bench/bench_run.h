#pragma once
// pmsim-bench: every bench scene rendered with every strategy, each image compared per pixel with
// the scene's converged reference (CIEDE2000), plus the issue-5 targets and the lens-tracing
// throughput, as a table, JSON rows and the frontier plot/markdown.
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/bench/ebsd_load.h"
#include "core/bench/ebsd_render.h"
#include "core/bench/lens_throughput.h"
#include "core/bench/process_start.h"

namespace pmsim {

struct BenchOptions {
  bool quick = false;
  int size = 0;                 // image side in pixels (0: 512, quick 96)
  std::string cache_dir;        // reference cache ("" = none)
  int threads = 0;              // 0: all cores
  int throughput_rays = 0;      // 0: 2e6 (quick 2e5); < 0: skip
  std::string scene_filter;     // only scenes whose name contains this ("" = all)
  std::string strategy_filter;  // only strategies whose name contains this ("" = all)
  std::string images_dir;       // write every image (and the references) as PNG here ("" = none)
  int process_start_runs = 0;   // 8×8 pmsim-render processes timed (0: 21, quick 5; < 0: skip)
  std::string render_binary;    // pmsim-render to time ("": next to this executable)
  long ebsd_points = 0;         // EBSD map load, points per map (0: 10⁶, quick 10⁵; < 0: skip)
};

// One JSON row. The first eight keys are the contract of issue 5.
struct BenchRow {
  std::string scene, strategy;
  int width = 0, height = 0;
  double time_ms = 0.0, mean_de2000 = 0.0, p95_de2000 = 0.0, max_de2000 = 0.0;
  int wavelengths = 0;
  double cpu_ms = 0.0;  // process CPU time (all threads) spent in the strategy: on a shared
                        // machine, cpu_ms / cores estimates the unloaded wall time
  std::string code;     // "product" (the renderer) or "bench-side"
  double renderer_estimate = -1.0;
  std::string model_report;
};

struct SceneReferenceInfo {
  std::string scene, description, cache_file;
  double time_ms = 0.0;
  bool from_cache = false;
  double half_vs_full_mean_de2000 = 0.0;  // reference convergence check
};

struct BenchReport {
  BenchOptions options;
  std::vector<BenchRow> rows;
  std::vector<SceneReferenceInfo> references;
  std::vector<ThroughputResult> throughput;
  std::optional<ProcessStartResult> process_start;
  std::vector<EbsdLoadResult> ebsd_load;
  std::optional<EbsdRenderResult> ebsd_render;  // the same map size as a section: load, first, converged
  std::vector<std::string> notes;
  double total_s = 0.0;
  double load_average = 0.0;  // 1-minute load average at the end of the run (/proc/loadavg)
  int cores = 0;
};

BenchReport run_bench(const BenchOptions& options, std::ostream& log);

nlohmann::json bench_report_json(const BenchReport& report);
// Reads back what bench_report_json wrote (to redraw the plot and markdown without re-running).
// Throws InputError naming the file and key on a malformed report.
BenchReport bench_report_from_json(const nlohmann::json& j, const std::string& file);
std::string bench_table(const BenchReport& report);
// The target lines of issue 5 (met, or the distance to them), as text lines.
std::vector<std::string> bench_targets(const BenchReport& report);
// docs/bench/frontier.md contents (table, targets, recommended defaults).
std::string frontier_markdown(const BenchReport& report, const std::string& plot_file);

}  // namespace pmsim
