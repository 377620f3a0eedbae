#include "core/bench/bench_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/bench/bench_scenes.h"
#include "core/bench/bench_strategy.h"
#include "core/bench/grain_mount_bench.h"
#include "core/bench/response_bench.h"
#include "core/bench/image_error.h"
#include "core/bench/reference_image.h"
#include "core/io/image_file.h"
#include "core/base/input_error.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"

namespace pmsim {

namespace {

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

const BenchRow* find_row(const BenchReport& r, const std::string& scene, const std::string& strategy) {
  for (const BenchRow& row : r.rows)
    if (row.scene == scene && row.strategy == strategy) return &row;
  return nullptr;
}

void save_png(const std::string& dir, const std::string& name, int w, int h, const std::vector<float>& xyz) {
  std::filesystem::create_directories(dir);
  std::vector<float> rgb(xyz.size());
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) {
    const glm::dvec3 c = xyz_to_linear_srgb({xyz[i], xyz[i + 1], xyz[i + 2]});
    for (int k = 0; k < 3; ++k) rgb[i + k] = static_cast<float>(c[k]);
  }
  write_image((std::filesystem::path(dir) / (name + ".png")).string(), w, h, rgb, nlohmann::json::object());
}

}  // namespace

BenchReport run_bench(const BenchOptions& opt_in, std::ostream& log) {
  const auto t_start = std::chrono::steady_clock::now();
  BenchReport rep;
  rep.options = opt_in;
  BenchOptions& opt = rep.options;
  if (opt.size <= 0) opt.size = opt.quick ? 96 : 512;
  if (opt.throughput_rays == 0) opt.throughput_rays = opt.quick ? 200000 : 2000000;

  const auto scenes = bench_scenes(opt.size, &rep.notes);
  for (const BenchScene& bs : scenes) {
    if (!opt.scene_filter.empty() && bs.name.find(opt.scene_filter) == std::string::npos) continue;
    log << "scene " << bs.name << ": reference… " << std::flush;
    const ReferenceImage ref = bs.physical_lenses ? converged_physical_reference(bs.scene, opt.cache_dir)
                                                  : converged_reference(bs.scene, opt.cache_dir);
    const glm::dvec3 white = illuminant_white_xyz(bs.scene.illuminant);
    SceneReferenceInfo info;
    info.scene = bs.name;
    info.description = bs.description;
    info.cache_file = ref.cache_file;
    info.time_ms = ref.time_ms;
    info.from_cache = ref.from_cache;
    info.half_vs_full_mean_de2000 = image_error_de2000(ref.xyz_half, ref.xyz, ref.lit, white).mean_de2000;
    rep.references.push_back(info);
    if (!opt.images_dir.empty())
      save_png(opt.images_dir, bs.name + "__reference", ref.width, ref.height, ref.xyz);
    log << (ref.from_cache ? "cached" : fmt("%.0f ms", ref.time_ms)) << ", half-vs-full ΔE "
        << fmt("%.3f", info.half_vs_full_mean_de2000) << "\n";
    {
      BenchRow row;
      row.scene = bs.name;
      row.strategy = bs.physical_lenses ? "reference-half (64 bands)" : "reference-half (2 nm)";
      row.width = ref.width;
      row.height = ref.height;
      row.time_ms = ref.time_ms;
      const ImageError e = image_error_de2000(ref.xyz_half, ref.xyz, ref.lit, white);
      row.mean_de2000 = e.mean_de2000;
      row.p95_de2000 = e.p95_de2000;
      row.max_de2000 = e.max_de2000;
      row.wavelengths = bs.physical_lenses ? 64 : kReferenceBands / 2;
      row.code = "bench-side";
      row.model_report = "the reference with half its spectral samples (convergence check)";
      rep.rows.push_back(row);
    }
    for (const BenchStrategy& st : bench_strategies(bs, opt.quick)) {
      if (!opt.strategy_filter.empty() && st.name.find(opt.strategy_filter) == std::string::npos) continue;
      const double cpu0 = process_cpu_ms();
      const StrategyResult r = run_strategy(bs.scene, st, opt.threads);
      const double cpu = process_cpu_ms() - cpu0;
      const ImageError e = image_error_de2000(r.xyz, ref.xyz, ref.lit, white);
      BenchRow row;
      row.scene = bs.name;
      row.strategy = st.name;
      row.width = ref.width;
      row.height = ref.height;
      row.time_ms = r.time_ms;
      row.mean_de2000 = e.mean_de2000;
      row.p95_de2000 = e.p95_de2000;
      row.max_de2000 = e.max_de2000;
      row.wavelengths = r.wavelengths;
      row.cpu_ms = r.cpu_ms >= 0.0 ? r.cpu_ms : cpu;
      row.code = st.product() ? "product" : "bench-side";
      row.renderer_estimate = r.error_estimate;
      row.model_report = r.model_report;
      log << "  " << st.name << ": " << fmt("%.1f ms", r.time_ms) << ", mean ΔE00 "
          << fmt("%.3f", e.mean_de2000) << "\n";
      rep.rows.push_back(row);
      if (!opt.images_dir.empty())
        save_png(opt.images_dir, bs.name + "__" + st.name, ref.width, ref.height, r.xyz);
    }
  }
  // The refracting specimen's rows (issue 12), under the same filters as the scenes above.
  const auto specimen_selected = [&](const std::string& scene, const std::string& polars) {
    if (scene.find(opt.scene_filter) == std::string::npos) return false;
    for (const std::string& suffix : specimen_bench_strategy_suffixes())
      if ((polars + "-" + suffix).find(opt.strategy_filter) != std::string::npos) return true;
    return false;
  };
  const auto add_rows = [&](std::vector<BenchRow> rows) {
    for (BenchRow& row : rows) rep.rows.push_back(std::move(row));
  };
  if (specimen_selected("grain-mount-garnet-1.54", "plane-light")) add_rows(grain_mount_bench_rows(opt.size, log));
  if (specimen_selected("grain-mount-calcite-crossed", "crossed-polars"))
    add_rows(crossed_polar_grain_bench_rows(opt.size, log));
  if (specimen_selected("section-granite-plane-light", "plane-light")) add_rows(section_relief_bench_rows(opt.size, log));
  // --quick (what tests/bench_json_test.cpp runs): 48², where a 1024-path reference of a crossed-
  // polar slab takes ~10 s instead of ~40 s at the quick size.
  if (specimen_selected("section-granite-crossed", "crossed-polars"))
    add_rows(section_crossed_bench_rows(opt.quick ? std::min(opt.size, 48) : opt.size, log));
  // The response/instrument split (issue 21): the default scene's Disc response composed at other
  // settings; --quick at 16², few traces and no 512² apply-settings timing (its rows' shape only:
  // at 32² with the full trace counts it took 590 s of the ASan suite).
  if (specimen_selected("response-granite-crossed", "crossed-polars"))
    add_rows(response_bench_rows(opt.quick ? std::min(opt.size, 16) : opt.size, opt.quick ? 0 : 512, opt.quick,
                                 rep.notes, log));
  if (opt.throughput_rays > 0) {
    log << "lens throughput (" << opt.throughput_rays << " rays per measurement, 1 core)…\n";
    rep.throughput = measure_lens_throughput(opt.throughput_rays);
  }
  if (opt.process_start_runs == 0) opt.process_start_runs = opt.quick ? 5 : 21;
  if (opt.process_start_runs > 0) {
    std::string binary = opt.render_binary;
    if (binary.empty()) {
      std::error_code ec;
      binary = (std::filesystem::read_symlink("/proc/self/exe", ec).parent_path() / "pmsim-render").string();
    }
    log << "process start (" << opt.process_start_runs << " runs of an 8×8 PNG render)…\n";
    rep.process_start = measure_process_start(binary, opt.process_start_runs);
  }
  if (opt.ebsd_points == 0) opt.ebsd_points = opt.quick ? 100000 : 1000000;
  if (opt.ebsd_points > 0) {
    log << "EBSD map load (" << opt.ebsd_points << " points, .ctf and .ang)…\n";
    rep.ebsd_load = measure_ebsd_load(static_cast<std::size_t>(opt.ebsd_points));
    log << "EBSD map as a section (" << opt.ebsd_points << " points: load, first image, converged 1024²)…\n";
    rep.ebsd_render = measure_ebsd_render(static_cast<std::size_t>(opt.ebsd_points), opt.threads);
  }
  rep.total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  std::ifstream la("/proc/loadavg");
  la >> rep.load_average;
  rep.cores = static_cast<int>(std::thread::hardware_concurrency());
  return rep;
}

nlohmann::json bench_report_json(const BenchReport& rep) {
  nlohmann::json j;
  j["rows"] = nlohmann::json::array();
  for (const BenchRow& r : rep.rows)
    j["rows"].push_back({{"scene", r.scene},
                         {"strategy", r.strategy},
                         {"width", r.width},
                         {"height", r.height},
                         {"time_ms", r.time_ms},
                         {"mean_de2000", r.mean_de2000},
                         {"p95_de2000", r.p95_de2000},
                         {"max_de2000", r.max_de2000},
                         {"wavelengths", r.wavelengths},
                         {"cpu_ms", r.cpu_ms},
                         {"code", r.code},
                         {"renderer_error_estimate", r.renderer_estimate},
                         {"model_report", r.model_report}});
  j["references"] = nlohmann::json::array();
  for (const SceneReferenceInfo& i : rep.references)
    j["references"].push_back({{"scene", i.scene},
                               {"description", i.description},
                               {"time_ms", i.time_ms},
                               {"from_cache", i.from_cache},
                               {"half_vs_full_mean_de2000", i.half_vs_full_mean_de2000}});
  if (rep.process_start)
    j["process_start"] = {{"runs", rep.process_start->runs},
                          {"median_ms", rep.process_start->median_ms},
                          {"min_ms", rep.process_start->min_ms},
                          {"max_ms", rep.process_start->max_ms},
                          {"max_rss_kb", rep.process_start->max_rss_kb}};
  j["ebsd_load"] = nlohmann::json::array();
  for (const EbsdLoadResult& e : rep.ebsd_load)
    j["ebsd_load"].push_back({{"format", e.format},
                              {"points", e.points},
                              {"file_mb", e.file_mb},
                              {"load_s", e.load_s},
                              {"points_per_s", e.points_per_s},
                              {"map_mb", e.map_mb},
                              {"peak_rss_kb", e.peak_rss_kb},
                              {"rss_before_kb", e.rss_before_kb}});
  if (rep.ebsd_render) {
    const EbsdRenderResult& e = *rep.ebsd_render;
    j["ebsd_render"] = {{"points", e.points},
                        {"grains", e.grains},
                        {"clusters", e.clusters},
                        {"load_s", e.load_s},
                        {"first_ms", e.first_ms},
                        {"first_cpu_ms", e.first_cpu_ms},
                        {"first_vs_converged_mean_de2000", e.first_vs_converged_mean_de2000},
                        {"converged_ms", e.converged_ms},
                        {"converged_cpu_ms", e.converged_cpu_ms},
                        {"converged_error_estimate", e.converged_error_estimate},
                        {"width", e.width},
                        {"height", e.height}};
  }
  j["lens_throughput"] = nlohmann::json::array();
  for (const ThroughputResult& t : rep.throughput)
    j["lens_throughput"].push_back({{"name", t.name},
                                    {"rays_per_s_per_core", t.rays_per_s_per_core},
                                    {"rays", t.rays},
                                    {"note", t.note}});
  j["targets"] = bench_targets(rep);
  j["notes"] = rep.notes;
  j["quick"] = rep.options.quick;
  j["size"] = rep.options.size;
  j["total_s"] = rep.total_s;
  j["load_average"] = rep.load_average;
  j["cores"] = rep.cores;
  return j;
}

BenchReport bench_report_from_json(const nlohmann::json& j, const std::string& file) {
  BenchReport rep;
  const auto need = [&](const nlohmann::json& o, const char* key) -> const nlohmann::json& {
    if (!o.is_object() || !o.contains(key)) throw InputError(file, key, "", "missing");
    return o.at(key);
  };
  try {
    for (const auto& r : need(j, "rows")) {
      BenchRow row;
      row.scene = need(r, "scene").get<std::string>();
      row.strategy = need(r, "strategy").get<std::string>();
      row.width = need(r, "width").get<int>();
      row.height = need(r, "height").get<int>();
      row.time_ms = need(r, "time_ms").get<double>();
      row.mean_de2000 = need(r, "mean_de2000").get<double>();
      row.p95_de2000 = need(r, "p95_de2000").get<double>();
      row.max_de2000 = need(r, "max_de2000").get<double>();
      row.wavelengths = r.value("wavelengths", 0);
      row.cpu_ms = r.value("cpu_ms", 0.0);
      row.code = r.value("code", std::string("product"));
      row.renderer_estimate = r.value("renderer_error_estimate", -1.0);
      row.model_report = r.value("model_report", std::string());
      rep.rows.push_back(row);
    }
    for (const auto& i : j.value("references", nlohmann::json::array()))
      rep.references.push_back({i.value("scene", ""), i.value("description", ""), "", i.value("time_ms", 0.0),
                                i.value("from_cache", false), i.value("half_vs_full_mean_de2000", 0.0)});
    if (j.contains("process_start")) {
      const auto& p = j.at("process_start");
      rep.process_start = ProcessStartResult{p.at("runs").get<int>(), p.at("median_ms").get<double>(),
                                             p.at("min_ms").get<double>(), p.at("max_ms").get<double>(),
                                             p.at("max_rss_kb").get<long>()};
    }
    for (const auto& e : j.value("ebsd_load", nlohmann::json::array()))
      rep.ebsd_load.push_back({e.value("format", ""), e.value("points", std::size_t{0}), e.value("file_mb", 0.0),
                               e.value("load_s", 0.0), e.value("points_per_s", 0.0), e.value("map_mb", 0.0),
                               e.value("peak_rss_kb", -1L), e.value("rss_before_kb", -1L)});
    if (j.contains("ebsd_render")) {
      const auto& e = j.at("ebsd_render");
      rep.ebsd_render = EbsdRenderResult{e.value("points", std::size_t{0}),
                                         e.value("grains", std::size_t{0}),
                                         e.value("clusters", std::size_t{0}),
                                         e.value("load_s", 0.0),
                                         e.value("first_ms", 0.0),
                                         e.value("first_cpu_ms", 0.0),
                                         e.value("first_vs_converged_mean_de2000", 0.0),
                                         e.value("converged_ms", 0.0),
                                         e.value("converged_cpu_ms", 0.0),
                                         e.value("converged_error_estimate", -1.0),
                                         e.value("width", 0),
                                         e.value("height", 0)};
    }
    for (const auto& t : j.value("lens_throughput", nlohmann::json::array()))
      rep.throughput.push_back({t.value("name", ""), t.value("rays_per_s_per_core", 0.0),
                                t.value("rays", 0.0), 0.0, t.value("note", "")});
    rep.notes = j.value("notes", std::vector<std::string>{});
    rep.options.quick = j.value("quick", false);
    rep.options.size = j.value("size", 0);
    rep.total_s = j.value("total_s", 0.0);
    rep.load_average = j.value("load_average", 0.0);
    rep.cores = j.value("cores", 0);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "rows", "", std::string("malformed bench report: ") + e.what());
  }
  return rep;
}

std::string bench_table(const BenchReport& rep) {
  std::ostringstream o;
  char line[256];
  std::snprintf(line, sizeof line, "%-26s %-26s %9s %9s %8s %8s %8s %5s  %s\n", "scene", "strategy",
                "time_ms", "cpu_ms", "mean_dE", "p95_dE", "max_dE", "nλ", "code");
  o << line;
  for (const BenchRow& r : rep.rows) {
    std::snprintf(line, sizeof line, "%-26s %-26s %9.1f %9.1f %8.3f %8.3f %8.3f %5d  %s\n", r.scene.c_str(),
                  r.strategy.c_str(), r.time_ms, r.cpu_ms, r.mean_de2000, r.p95_de2000, r.max_de2000,
                  r.wavelengths, r.code.c_str());
    o << line;
  }
  if (!rep.throughput.empty()) {
    o << "\nlens tracing, one core:\n";
    for (const ThroughputResult& t : rep.throughput) {
      std::snprintf(line, sizeof line, "  %-52s %12.0f rays/s  (%s)\n", t.name.c_str(), t.rays_per_s_per_core,
                    t.note.c_str());
      o << line;
    }
  }
  if (rep.process_start) {
    const ProcessStartResult& p = *rep.process_start;
    std::snprintf(
        line, sizeof line,
        "\nprocess start, 8×8 PNG render: median %.1f ms (min %.1f, max %.1f, %d runs), peak RSS %ld KB\n",
        p.median_ms, p.min_ms, p.max_ms, p.runs, p.max_rss_kb);
    o << line;
  }
  if (!rep.ebsd_load.empty()) {
    o << "\nEBSD map load:\n";
    for (const EbsdLoadResult& e : rep.ebsd_load) {
      std::snprintf(line, sizeof line,
                    "  %-22s %9zu points, %6.1f MB text: %6.3f s (%.2e points/s), map %.1f MB, peak RSS %ld KB "
                    "(before %ld KB)\n",
                    e.format.c_str(), e.points, e.file_mb, e.load_s, e.points_per_s, e.map_mb, e.peak_rss_kb,
                    e.rss_before_kb);
      o << line;
    }
  }
  if (rep.ebsd_render) {
    const EbsdRenderResult& e = *rep.ebsd_render;
    std::snprintf(line, sizeof line,
                  "\nEBSD map as a section (%zu points, %zu grains, %zu orientation clusters), %d×%d crossed "
                  "polars:\n  load %.3f s, first image %.1f ms (cpu %.1f ms; mean ΔE00 %.2f against converged), "
                  "converged %.1f ms (cpu %.1f ms; estimate ΔE00 %.3f)\n",
                  e.points, e.grains, e.clusters, e.width, e.height, e.load_s, e.first_ms, e.first_cpu_ms,
                  e.first_vs_converged_mean_de2000, e.converged_ms, e.converged_cpu_ms, e.converged_error_estimate);
    o << line;
  }
  o << "\ntargets:\n";
  for (const std::string& s : bench_targets(rep)) o << "  " << s << "\n";
  for (const std::string& n : rep.notes) o << "note: " << n << "\n";
  o << "machine: " << rep.cores << " cores, load average " << fmt("%.1f", rep.load_average)
    << " at the end (other processes share the cores: wall times are inflated by about load/cores; "
       "cpu_ms/cores estimates the unloaded wall time)\n";
  return o.str();
}

std::vector<std::string> bench_targets(const BenchReport& rep) {
  std::vector<std::string> out;
  // Idle-machine estimate from CPU time: a lower bound (perfect scaling over the cores).
  const auto idle = [&](const BenchRow& r) {
    return " (CPU " + fmt("%.1f ms", r.cpu_ms) + " → ≥ " + fmt("%.1f ms", r.cpu_ms / std::max(1, rep.cores)) +
           " idle)";
  };
  const std::string size = std::to_string(rep.options.size) + "²";
  // Converged calcite figure ≤ 50 ms at mean ΔE ≤ 1, ≥ 10× faster than uniform-81 at that error.
  {
    const std::string sc = "calcite-1mm-cono";
    const BenchRow* best = nullptr;
    for (const BenchRow& r : rep.rows)
      // A composed frame costs milliseconds only once the figure's response exists: not a render.
      if (r.scene == sc && r.mean_de2000 <= 1.0 && r.code == "product" && r.strategy != "stage-drag-composed" &&
          (!best || r.time_ms < best->time_ms))
        best = &r;
    const BenchRow* u81 = find_row(rep, sc, "uniform-81");
    if (best) {
      std::string s = "calcite conoscopic converged (ΔE ≤ 1) at " + size + ": fastest '" + best->strategy +
                      "' " + "wall " + fmt("%.1f ms", best->time_ms) + idle(*best) +
                      " (target ≤ 50 ms: " + (best->time_ms <= 50 ? "MET" : "not met") + ")";
      if (u81)
        s += u81->mean_de2000 <= 1.0
                 ? "; uniform-81 reaches ΔE " + fmt("%.2f", u81->mean_de2000) + " in " +
                       fmt("%.1f ms", u81->time_ms) + " → " + fmt("%.1f×", u81->time_ms / best->time_ms)
                 : "; uniform-81 never reaches ΔE ≤ 1 here (ΔE " + fmt("%.2f", u81->mean_de2000) +
                       ", aliasing of the 10⁵-nm retardation): the speed-up at equal error is unbounded";
      out.push_back(s);
    } else {
      out.push_back("calcite conoscopic: no strategy reached mean ΔE ≤ 1");
    }
  }
  // Interactive preview: first pass ≤ 33 ms, ΔE ≤ 5 on every scene.
  for (const BenchRow& r : rep.rows)
    if (r.strategy == "first-pass")
      out.push_back("first pass " + r.scene + ": wall " + fmt("%.1f ms", r.time_ms) + idle(r) + ", ΔE " +
                    fmt("%.2f", r.mean_de2000) +
                    " (≤ 33 ms & ≤ 5: " + (r.time_ms <= 33 && r.mean_de2000 <= 5 ? "MET" : "not met") + ")");
  // Moonshot: ≤ 16 ms at ΔE ≤ 1 for the ideal-lens scenes: best renderer strategy per scene (a
  // bench-side Monte Carlo row can be lucky on a one-unit plate; it is not something the product does).
  std::map<std::string, const BenchRow*> best;
  for (const BenchRow& r : rep.rows) {
    if (r.mean_de2000 > 1.0 || r.code != "product" || r.scene.find("physical") != std::string::npos) continue;
    const BenchRow*& b = best[r.scene];
    if (!b || r.time_ms < b->time_ms) b = &r;
  }
  for (const auto& [scene, r] : best)
    out.push_back("60 Hz moonshot " + scene + ": best ΔE ≤ 1 is '" + r->strategy + "' at wall " +
                  fmt("%.1f ms", r->time_ms) + idle(*r) +
                  (r->time_ms <= 16 ? " (MET)" : " (" + fmt("%.1f×", r->time_ms / 16.0) + " away)"));
  // Stage drag (issue 14): a converged figure on every frame at 60 Hz.
  for (const BenchRow& r : rep.rows)
    if (r.strategy == "stage-drag" || r.strategy == "stage-drag-composed")
      out.push_back((r.strategy == "stage-drag" ? "stage drag " : "stage drag composed from the view's response ") +
                    r.scene + ": mean frame to converged " + fmt("%.1f ms", r.time_ms) +
                    idle(r) + ", last frame ΔE " + fmt("%.2f", r.mean_de2000) +
                    (r.time_ms <= 16 && r.mean_de2000 <= 1 ? " (≤ 16 ms: MET)"
                                                            : " (" + fmt("%.1f×", r.time_ms / 16.0) + " of 16 ms)"));
  // Process start: an 8×8 render ≤ 50 ms wall (issue 14).
  if (rep.process_start)
    out.push_back("process start (8×8 PNG render as a new process): median " +
                  fmt("%.1f ms", rep.process_start->median_ms) + " over " +
                  std::to_string(rep.process_start->runs) +
                  " runs (target ≤ 50 ms: " + (rep.process_start->median_ms <= 50 ? "MET" : "not met") + ")");
  // EBSD map load: a 10⁶-point map in ≤ 3 s (issue 13).
  for (const EbsdLoadResult& e : rep.ebsd_load)
    out.push_back("EBSD map load, " + e.format + ", " + std::to_string(e.points) + " points: " +
                  fmt("%.3f s", e.load_s) +
                  (e.points >= 1000000 ? std::string(" (target ≤ 3 s: ") + (e.load_s <= 3.0 ? "MET)" : "not met)")
                                       : std::string(" (the ≤ 3 s target is for 10^6 points)")));
  // EBSD map as a section (issue 13): load ≤ 3 s, first image ≤ 100 ms, converged 1024² ≤ 1 s.
  if (rep.ebsd_render) {
    const EbsdRenderResult& e = *rep.ebsd_render;
    const bool full = e.points >= 1000000;
    auto verdict = [&](bool met) { return full ? (met ? std::string("MET") : std::string("not met")) : std::string("for 10^6 points"); };
    out.push_back("EBSD map section, " + std::to_string(e.points) + " points: load " + fmt("%.3f s", e.load_s) +
                  " (target ≤ 3 s: " + verdict(e.load_s <= 3.0) + "), first image " + fmt("%.1f ms", e.first_ms) +
                  " (≤ 100 ms: " + verdict(e.first_ms <= 100.0) + "), converged 1024² " +
                  fmt("%.1f ms", e.converged_ms) + " (≤ 1 s: " + verdict(e.converged_ms <= 1000.0) + ")");
  }
  // Lens throughput: SML ≥ 30 % of Embree rtcIntersect1 "on the same geometry" (issue 5): the lens
  // itself, as user geometry and triangulated; the 262k-triangle sphere for scale.
  double sml = 0;
  for (const ThroughputResult& t : rep.throughput)
    if (t.name.rfind("SML", 0) == 0) sml = t.rays_per_s_per_core;
  for (const char* ref :
       {"Embree rtcIntersect1, lens as user geometry", "Embree rtcIntersect1, lens triangulated (33k tris)",
        "Embree rtcIntersect1, sphere 262k tris"}) {
    double embree = 0;
    for (const ThroughputResult& t : rep.throughput)
      if (t.name == ref) embree = t.rays_per_s_per_core;
    if (sml > 0 && embree > 0)
      out.push_back("SML dT=3 " + fmt("%.2f", sml / 1e6) + " M rays/s/core vs " + ref + " " +
                    fmt("%.2f", embree / 1e6) + " M: " + fmt("%.0f %%", 100 * sml / embree) +
                    " (target ≥ 30 %: " + (sml >= 0.3 * embree ? "MET" : "not met") + ")");
  }
  return out;
}

std::string frontier_markdown(const BenchReport& rep, const std::string& plot_file) {
  std::ostringstream o;
  o << "# Speed against error: the pmsim-bench frontier\n\n";
  o << "Produced by `pmsim-bench" << (rep.options.quick ? " --quick" : "") << "` (" << rep.options.size << "×"
    << rep.options.size << " pixels, "
    << (rep.options.threads > 0 ? std::to_string(rep.options.threads) : "all") << " threads, total "
    << fmt("%.0f", rep.total_s) << " s). Error: per-pixel CIEDE2000 against a converged "
    << "reference (1 nm bands, exact plate eigenmodes, band-averaged interference; see "
    << "core/bench/reference_image.h), over the lit pixels. `code`: *product* rows time the renderer "
    << "itself; *bench-side* rows are sampling schemes or models the renderer does not offer, evaluated on "
       "its set-up.\n\n";
  o << "![time vs mean CIEDE2000](" << plot_file << ")\n\n";
  o << "Machine: " << rep.cores << " cores shared with other processes, 1-minute load average "
    << fmt("%.1f", rep.load_average)
    << " at the end of the run: wall times are inflated by roughly load/cores; "
    << "`cpu ms` is the process CPU time of the strategy (all threads), so cpu ms / " << rep.cores
    << " estimates the wall time on an idle machine.\n\n";
  o << "| scene | strategy | time (ms) | cpu (ms) | mean ΔE00 | p95 ΔE00 | max ΔE00 | λ samples | code |\n";
  o << "|---|---|---:|---:|---:|---:|---:|---:|---|\n";
  for (const BenchRow& r : rep.rows)
    o << "| " << r.scene << " | " << r.strategy << " | " << fmt("%.1f", r.time_ms) << " | "
      << fmt("%.1f", r.cpu_ms) << " | " << fmt("%.3f", r.mean_de2000) << " | " << fmt("%.3f", r.p95_de2000)
      << " | " << fmt("%.3f", r.max_de2000) << " | " << r.wavelengths << " | " << r.code << " |\n";
  o << "\n## References\n\n| scene | reference time (ms) | half-samples vs full (mean ΔE00) "
       "|\n|---|---:|---:|\n";
  for (const SceneReferenceInfo& i : rep.references)
    o << "| " << i.scene << " | " << (i.from_cache ? std::string("cached") : fmt("%.0f", i.time_ms)) << " | "
      << fmt("%.4f", i.half_vs_full_mean_de2000) << " |\n";
  if (!rep.throughput.empty()) {
    o << "\n## Lens tracing throughput (one core, same run)\n\n| what | rays/s/core | note "
         "|\n|---|---:|---|\n";
    for (const ThroughputResult& t : rep.throughput)
      o << "| " << t.name << " | " << fmt("%.3g", t.rays_per_s_per_core) << " | " << t.note << " |\n";
  }
  o << "\n## Recommended defaults (what the numbers justify)\n\n";
  {
    // Cheapest strategy per scene reaching mean ΔE ≤ 1 (just noticeable) and ≤ 0.5.
    std::map<std::string, std::pair<const BenchRow*, const BenchRow*>> best;
    for (const BenchRow& r : rep.rows) {
      if (r.code != "product") continue;  // what the renderer offers
      auto& b = best[r.scene];
      if (r.mean_de2000 <= 1.0 && (!b.first || r.cpu_ms < b.first->cpu_ms)) b.first = &r;
      if (r.mean_de2000 <= 0.5 && (!b.second || r.cpu_ms < b.second->cpu_ms)) b.second = &r;
    }
    o << "Cheapest renderer strategy (by CPU time) per scene:\n\n";
    o << "| scene | cheapest with mean ΔE00 ≤ 1 (cpu ms) | cheapest with mean ΔE00 ≤ 0.5 (cpu ms) "
         "|\n|---|---|---|\n";
    for (const auto& [scene, b] : best)
      o << "| " << scene << " | "
        << (b.first ? b.first->strategy + " (" + fmt("%.0f", b.first->cpu_ms) + ")" : "none") << " | "
        << (b.second ? b.second->strategy + " (" + fmt("%.0f", b.second->cpu_ms) + ")" : "none") << " |\n";
    const BenchRow* d1 = find_row(rep, "calcite-1mm-cono-physical", "sml-dT1");
    const BenchRow* d3 = find_row(rep, "calcite-1mm-cono-physical", "sml-dT3");
    const BenchRow* sch = find_row(rep, "calcite-1mm-cono-physical", "sml-dT3-schlick");
    const BenchRow* ideal = find_row(rep, "calcite-1mm-cono-physical", "ideal-lenses");
    o << "\n- **Spectral integration: `render.strategy=auto`** (the modal fit: three exact mode solutions "
         "per "
         "pixel, the interference term averaged over each band in closed form). It is the only family that "
         "converges on the 1 mm calcite figure; per-wavelength point sampling — uniform 81 (the paper's), "
         "RGB, "
         "stratified or hero wavelengths per pixel — aliases the 10⁵-nm retardations into false colours and "
         "noise however many samples it takes.\n";
    o << "- **Band count:** 8 bands are enough for a first progressive pass (mean ΔE00 ≈ 1 on the conoscopic "
         "figures), 16–32 bands converge below 0.5; more only costs time.\n";
    o << "- **Thin plates and sections:** the cost is per-pixel bookkeeping, not optics (see profile.md).";
    const BenchRow* sm = find_row(rep, "section-ortho", "modal-32");
    const BenchRow* sa = find_row(rep, "section-ortho", "auto");
    const BenchRow* su = find_row(rep, "section-ortho", "uniform-32");
    if (sm && sa && su)
      o << " On the granite the pure modal fit stays at mean ΔE00 " << fmt("%.2f", sm->mean_de2000)
        << " (p95 " << fmt("%.1f", sm->p95_de2000) << ") where exact Jones matrices at 32 bands reach "
        << fmt("%.2f", su->mean_de2000)
        << " for the same time: the difference sits in the brown (absorbing, pleochroic biotite) grains, "
           "whose "
           "transmission the fit interpolates from three anchor wavelengths. So `auto` evaluates absorbing "
           "crystals "
           "in parallel light exactly (one evaluation per grain): "
        << fmt("%.2f", sa->mean_de2000) << ".";
    o << "\n";
    const BenchRow* rp = find_row(rep, "calcite-1mm-cono-physical", "renderer-physical");
    if (d1 && d3 && ideal)
      o << "- **Lens depth:** against the dT = 5 SML reference (same 128 bands), dT = 1 differs by mean ΔE00 "
        << fmt("%.2f", d1->mean_de2000) << " (p95 " << fmt("%.2f", d1->p95_de2000) << ") and dT = 3 by "
        << fmt("%.2f", d3->mean_de2000) << ": ghost light from internal reflections is "
        << (d1->mean_de2000 < 1.0
                ? "below the visible threshold, so `optics.lens_depth=1` is the right default"
                : "visible, so keep dT ≥ 2")
        << ". The lens model matters more: ideal (aplanatic) lenses are ΔE00 "
        << fmt("%.1f", ideal->mean_de2000) << " from the SML model at NA 0.85"
        << (rp ? ", the renderer's own physical model (the SML's s/p transmission profile on the aplanatic "
                 "frame, direct path) ΔE00 " +
                     fmt("%.1f", rp->mean_de2000)
               : std::string())
        << ".\n";
    if (sch && d3)
      o << "- **Fresnel vs Schlick:** with Schlick the SML figure is ΔE00 " << fmt("%.2f", sch->mean_de2000)
        << " from the Fresnel reference instead of " << fmt("%.2f", d3->mean_de2000)
        << " (Schlick has no s/p difference, which is what turns the polarization in a real lens) at no "
           "saving in "
           "time: keep exact Fresnel.\n";
  }
  o << "\n## Targets (issue 5)\n\n";
  for (const std::string& s : bench_targets(rep)) o << "- " << s << "\n";
  for (const std::string& n : rep.notes) o << "- note: " << n << "\n";
  return o.str();
}

}  // namespace pmsim
