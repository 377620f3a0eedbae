// pmsim-bench --apply-settings [--size N] [--threads N]: only the responses' apply-settings timing (a frame's work:
// the traced granite's Disc response and its flat view's).
// pmsim-bench --rocks: only the rock-growth row (every recipe grown at 20 × 15 mm, time and memory).
// pmsim-bench [--quick] [--json FILE] [--out-dir DIR] [--size N] [--threads N] [--cache-dir DIR]
//             [--no-throughput] [--scene SUBSTR] [--strategy SUBSTR] [--images DIR] [--from-json FILE]
// Renders the bench scenes with every strategy, measures wall time and per-pixel CIEDE2000
// against cached converged references, prints the table and the issue-5 targets, and writes JSON
// rows, docs-ready markdown (frontier.md) and the frontier plot (frontier.png) into --out-dir.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <unistd.h>

#include <tbb/global_control.h>

#include "core/io/cli_policy.h"
#include "core/bench/bench_run.h"
#include "core/bench/frontier_plot.h"
#include "core/bench/response_bench.h"
#include "core/bench/rock_growth_bench.h"
#include "core/io/atomic_file.h"
#include "core/base/input_error.h"
#include "core/base/install_layout.h"

namespace {

constexpr const char* kProgram = "pmsim-bench";

// In a build tree (CMakeCache.txt beside app/): <build>/bench-cache, as the tests expect. Installed
// (/usr/bin is not writable): $XDG_CACHE_HOME/pmsim/bench-cache, else ~/.cache/pmsim/bench-cache.
std::string default_cache_dir() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path prefix = pmsim::install_prefix();
  if (fs::exists(prefix / "CMakeCache.txt", ec)) return (prefix / "bench-cache").string();
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg == '/')
    return (fs::path(xdg) / "pmsim" / "bench-cache").string();
  if (const char* home = std::getenv("HOME"); home && *home)
    return (fs::path(home) / ".cache" / "pmsim" / "bench-cache").string();
  return "bench-cache";
}

int parse_int(const std::string& flag, const char* v) {
  try {
    std::size_t pos = 0;
    const int n = std::stoi(v, &pos);
    if (pos != std::string(v).size()) throw std::invalid_argument("trailing");
    return n;
  } catch (const std::exception&) {
    throw pmsim::InputError("", flag, v, "expected an integer");
  }
}

}  // namespace

int main(int argc, char** argv) {
  pmsim::BenchOptions opt;
  opt.cache_dir = default_cache_dir();
  std::string json_path, out_dir, from_json, size, threads;
  bool no_throughput = false, apply_settings = false, rocks = false;
  CLI::App app{
      "Renders the bench scenes with every strategy and measures time and CIEDE2000 against "
      "converged references.",
      kProgram};
  pmsim::cli::last_value_wins(app);
  app.add_flag("--quick", opt.quick, "smaller images and fewer throughput rays");
  app.add_option("--json", json_path, "write the rows as JSON")->type_name("FILE");
  app.add_option("--out-dir", out_dir, "write frontier.md and frontier.png there")->type_name("DIR");
  app.add_option("--size", size, "image side in pixels, 8..4096 (default 512, quick 96)")->type_name("N");
  app.add_option("--threads", threads, "worker threads (0: all cores)")->type_name("N");
  // The default is not printed: it depends on where the program runs, and --help becomes the man page.
  app.add_option("--cache-dir", opt.cache_dir,
                 "folder of the cached references (default: <build>/bench-cache in a build tree, "
                 "else $XDG_CACHE_HOME/pmsim/bench-cache or ~/.cache/pmsim/bench-cache)")
      ->type_name("DIR");
  app.add_flag("--no-throughput", no_throughput, "skip the ray-throughput measurement");
  app.add_flag("--apply-settings", apply_settings,
               "only time applying the settings to a --size² Disc response of the granite (stage 30°, and "
               "with the gypsum plate; median of 15 frames each), and to its flat view's response (a stage drag "
               "without an accessory, with the gypsum plate and with the quartz wedge)");
  app.add_flag("--rocks", rocks,
               "only time growing every rock recipe of assets/rocks at 20 × 15 mm and reading it as a "
               "section (issue 22's target: ≤ 2 s and ≤ 1 GB each)");
  app.add_option("--scene", opt.scene_filter, "only the scenes whose name contains it")->type_name("SUBSTR");
  app.add_option("--strategy", opt.strategy_filter, "only the strategies whose name contains it")
      ->type_name("SUBSTR");
  app.add_option("--images", opt.images_dir, "write every image (and the references) as PNG there")
      ->type_name("DIR");
  app.add_option("--from-json", from_json, "redraw table, plot and markdown from its rows (no run)")
      ->type_name("FILE");
  pmsim::cli::parse_or_exit(app, argc, argv);
  try {
    if (app.count("--size")) {
      opt.size = parse_int("--size", size.c_str());
      if (opt.size < 8 || opt.size > 4096)
        throw pmsim::InputError("", "--size", std::to_string(opt.size), "must be in 8…4096");
    }
    if (app.count("--threads")) {
      opt.threads = parse_int("--threads", threads.c_str());
      if (opt.threads < 0)
        throw pmsim::InputError("", "--threads", std::to_string(opt.threads), "must be ≥ 0");
    }
    if (no_throughput) opt.throughput_rays = -1;
  } catch (const pmsim::InputError& e) {
    pmsim::cli::usage_error(kProgram, e.what());
  }
  try {
    // --threads caps every parallel loop of the run, the ones that take no thread count of their
    // own (the response's tracer and composer, rock growth) included.
    std::optional<tbb::global_control> thread_cap;
    if (opt.threads > 0) thread_cap.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(opt.threads));
    if (rocks) {
      std::cout << pmsim::rock_growth_table(pmsim::measure_rock_growth(20.0, 15.0));
      return 0;
    }
    if (apply_settings) {
      const int side = opt.size > 0 ? opt.size : 512;
      std::cout << pmsim::response_apply_note(side, 15, std::cerr) << "\n"
                << pmsim::flat_apply_note(side, 15, std::cerr) << "\n"
                << pmsim::figure_apply_note(side, 15, std::cerr) << "\n";
      return 0;
    }
    pmsim::BenchReport rep;
    if (!from_json.empty()) {
      std::ifstream in(from_json);
      if (!in) throw pmsim::InputError(from_json, "--from-json", from_json, "cannot read the file");
      nlohmann::json j;
      try {
        j = nlohmann::json::parse(in);
      } catch (const nlohmann::json::exception& e) {
        throw pmsim::InputError(from_json, "--from-json", from_json, e.what());
      }
      rep = pmsim::bench_report_from_json(j, from_json);
    } else {
      rep = pmsim::run_bench(opt, std::cerr);
    }
    std::cout << pmsim::bench_table(rep);
    if (!json_path.empty())
      pmsim::write_text_atomically(json_path, pmsim::bench_report_json(rep).dump(1) + "\n");
    if (!out_dir.empty()) {
      std::filesystem::create_directories(out_dir);
      pmsim::write_frontier_plot(rep, (std::filesystem::path(out_dir) / "frontier.png").string());
      pmsim::write_text_atomically((std::filesystem::path(out_dir) / "frontier.md").string(),
                                   pmsim::frontier_markdown(rep, "frontier.png"));
    }
    std::cerr << "total " << rep.total_s << " s\n";
  } catch (const pmsim::InputError& e) {
    std::cerr << "pmsim-bench: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "pmsim-bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
