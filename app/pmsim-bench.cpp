// pmsim-bench [--quick] [--json FILE] [--out-dir DIR] [--size N] [--threads N] [--cache-dir DIR]
//             [--no-throughput] [--scene SUBSTR] [--strategy SUBSTR] [--images DIR] [--from-json FILE]
// Renders the bench scenes with every strategy, measures wall time and per-pixel CIEDE2000
// against cached converged references, prints the table and the issue-5 targets, and writes JSON
// rows, docs-ready markdown (frontier.md) and the frontier plot (frontier.png) into --out-dir.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <unistd.h>

#include "core/bench/bench_run.h"
#include "core/bench/frontier_plot.h"
#include "core/io/atomic_file.h"
#include "core/base/input_error.h"

namespace {

void usage(std::ostream& o) {
  o << "usage: pmsim-bench [--quick] [--json FILE] [--out-dir DIR] [--size N] [--threads N]\n"
       "                   [--cache-dir DIR] [--no-throughput] [--scene SUBSTR] [--strategy SUBSTR]\n"
       "                   [--images DIR] [--from-json FILE (redraw table/plot/markdown, no run)]\n";
}

// <build>/bench-cache next to the app folder of this executable.
std::string default_cache_dir() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return "bench-cache";
  return (exe.parent_path().parent_path() / "bench-cache").string();
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
  std::string json_path, out_dir, from_json;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> const char* {
        if (i + 1 >= argc) throw pmsim::InputError("", a, "", "missing value");
        return argv[++i];
      };
      if (a == "--quick") opt.quick = true;
      else if (a == "--json") json_path = value();
      else if (a == "--out-dir") out_dir = value();
      else if (a == "--cache-dir") opt.cache_dir = value();
      else if (a == "--scene") opt.scene_filter = value();
      else if (a == "--strategy") opt.strategy_filter = value();
      else if (a == "--images") opt.images_dir = value();
      else if (a == "--from-json") from_json = value();
      else if (a == "--size") {
        opt.size = parse_int(a, value());
        if (opt.size < 8 || opt.size > 4096) throw pmsim::InputError("", a, std::to_string(opt.size), "must be in 8…4096");
      } else if (a == "--threads") {
        opt.threads = parse_int(a, value());
        if (opt.threads < 0) throw pmsim::InputError("", a, std::to_string(opt.threads), "must be ≥ 0");
      } else if (a == "--no-throughput") opt.throughput_rays = -1;
      else if (a == "-h" || a == "--help") {
        usage(std::cout);
        return 0;
      } else {
        throw pmsim::InputError("", "argument", a, "unknown option");
      }
    }
  } catch (const pmsim::InputError& e) {
    std::cerr << "pmsim-bench: " << e.what() << "\n";
    usage(std::cerr);
    return 2;
  }
  try {
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
    if (!json_path.empty()) pmsim::write_text_atomically(json_path, pmsim::bench_report_json(rep).dump(1) + "\n");
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
