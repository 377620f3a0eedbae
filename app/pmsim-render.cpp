// pmsim-render [SCENE.json] [--set key=value]... --out FILE.png|.exr|.tif [--stats FILE.json]
//              [--labels FILE.png] [--grains FILE.json] [--scale-bar] [--progress]
//              [--sweep KEY=START:STOP:STEP]
// Renders a microscope scene to convergence (or to render.spp / render.wavelengths), or a 3-D
// scene ("type": "scene3d", core/scene3d), and writes the image atomically. A thin section's
// ground truth goes with it: --labels the grain under every pixel centre (16-bit grey PNG,
// core/microscope/grain_labels.h), --grains the grains in the image (core/io/grain_report_file.h);
// a grain mount's likewise, its fragments (core/specimen/grain_mount_truth.h).
// --sweep renders one frame per value of an instrument key (stage_deg, polarizer_deg,
// analyzer_deg, compensator_position) into the numbered files of --out (one printf integer
// field); a traced specimen's response is traced once and composed at every value
// (core/specimen/specimen_response.h), and a conoscopic figure or a section's flat view is rendered
// once with its nine probes (and its plan, for frames with an accessory) and composed at every
// value (core/specimen/figure_response.h). --progress (or a terminal on stderr): a progress line.
// Bad input: a message naming file, key and value on stderr, exit code 2, no output file.
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <memory>
#include <new>
#include <optional>
#include <cstdio>
#include <filesystem>
#include <deque>
#include <fstream>
#include <future>
#include <thread>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/io/cli_policy.h"

#include "core/io/atomic_file.h"
#include "core/io/grain_report_file.h"
#include "core/io/image_file.h"
#include "core/base/input_error.h"
#include "core/io/scene_file.h"
#include "core/microscope/grain_labels.h"
#include "core/microscope/view_geometry.h"
#include "core/render/scale_bar.h"
#include "core/microscope/grain_report.h"
#include "core/microscope/sample_source.h"
#include "core/ebsd/read_orientation_map.h"
#include "core/microscope/map_section.h"
#include "core/microscope/native_resolution.h"
#include "core/microscope/section_map.h"
#include "core/render/exposure.h"
#include "core/render/progressive_renderer.h"
#include "core/specimen/instrument_response.h"
#include "core/scene3d/scene3d_render.h"
#include "core/specimen/becke_probe.h"
#include "core/specimen/forward_response.h"
#include "core/specimen/grain_mount_render.h"
#include "core/specimen/grain_mount_truth.h"
#include "core/specimen/specimen_response.h"
#include "core/specimen/traced_specimen.h"

namespace {

constexpr const char* kProgram = "pmsim-render";

struct Args {
  std::string scene_path, out, stats, labels, grains, sweep;
  std::vector<std::string> sets;
  bool scale_bar = false, progress = false;
};

[[noreturn]] void usage_error(const std::string& msg) { pmsim::cli::usage_error(kProgram, msg); }

Args parse_args(int argc, char** argv) {
  Args a;
  CLI::App app{"Renders a microscope or 3-D scene to convergence and writes the image.", kProgram};
  app.footer(
      "Without SCENE, renders the default scene (assets/scenes/quartz_section_ortho.json).\n"
      "Keys are the scene's dot paths, e.g. --set stage_deg=45 --set sample.mineral=calcite.");
  pmsim::cli::last_value_wins(app);
  app.add_option("SCENE", a.scene_path, "scene file (JSON)")->type_name("FILE.json");
  pmsim::cli::add_repeatable(app, "--set", a.sets, "change a scene key (repeatable, applied in order)")
      ->type_name("key=value");
  app.add_option("-o,--out", a.out, "output image (.png, .exr or .tif)")->type_name("FILE")->required();
  app.add_option("--stats", a.stats, "write the render statistics as JSON")->type_name("FILE.json");
  app.add_option("--labels", a.labels,
                 "thin sections and grain mounts: write the grain (fragment) under every pixel centre "
                 "as a 16-bit grey PNG (0 = mounting medium, liquid or slide, k = grain k)")
      ->type_name("FILE.png");
  app.add_option("--grains", a.grains,
                 "thin sections: write the grains in the image (mineral, orientation, area, cleavage "
                 "traces, extinction, retardation, twin) as JSON; grain mounts: the fragments (mineral, "
                 "optic axes, area, n' along the polarizer, n fast and slow, relief against the liquid)")
      ->type_name("FILE.json");
  app.add_flag("--scale-bar", a.scale_bar,
               "orthoscopic microscope views: burn a scale bar (section millimetres) into the image, "
               "bottom left, as the app's exports do");
  app.add_option("--sweep", a.sweep,
                 "render one frame per value START, START+STEP, ... <= STOP of an instrument key (stage_deg, "
                 "polarizer_deg, analyzer_deg, compensator_position) into --out's numbered files (one "
                 "field %d, %Nd or %0Nd, e.g. frames/stage_%03d.png; frames from 0); each frame is the "
                 "image of --set KEY=value")
      ->type_name("KEY=START:STOP:STEP");
  app.add_flag("--progress", a.progress,
               "print a progress line on stderr (passes, error estimate, elapsed and estimated time "
               "left); always on when stderr is a terminal");
  pmsim::cli::parse_or_exit(app, argc, argv);
  return a;
}

nlohmann::json read_scene_json(const std::string& path) {
  const std::string text = pmsim::read_scene_text(path);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // syntax errors, numbers beyond double (1e400)
    throw pmsim::InputError(path, "", "", std::string("not valid JSON: ") + e.what());
  }
}

// The single place where scene types dispatch: "scene3d" scenes go to the 3-D renderer, anything
// else (no "type", or "microscope") is a microscope scene.
bool is_scene3d(const nlohmann::json& j) {
  return j.is_object() && j.contains("type") && j["type"].is_string() && j["type"] == "scene3d";
}

// --set key=value on a 3-D scene: the value (JSON when it parses, else a string) replaces the one
// at the dot path, creating objects on the way; the 3-D scene parser then checks keys and values.
void apply_scene3d_setting(nlohmann::json& j, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) throw pmsim::InputError("", assignment, "", "expected key=value");
  const std::string key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  nlohmann::json v = nlohmann::json::parse(text, nullptr, false);
  if (v.is_discarded()) v = text;
  nlohmann::json* node = &j;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    const std::string part = key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (part.empty()) throw pmsim::InputError("", key, text, "empty part in the dot path");
    if (!node->is_object())
      throw pmsim::InputError("", key, text,
                              "'" + key.substr(0, start ? start - 1 : 0) + "' is not an object");
    if (dot == std::string::npos) {
      (*node)[part] = v;
      return;
    }
    node = &(*node)[part];
    if (node->is_null()) *node = nlohmann::json::object();
    start = dot + 1;
  }
}

// The progress line (--progress, or whenever stderr is a terminal): passes, the error estimate
// against render.tolerance, the elapsed time and an estimate of the time left. On a terminal the
// line is redrawn in place; otherwise (--progress into a file or pipe) every update is a line.
//
// Time left, the sooner of two guesses, "?" when neither is known:
//   - the estimate's trend: a least-squares line through log(estimate) against log(elapsed) over
//     the last few updates (Monte Carlo noise falls as t^−½, a spectral level's error faster), run
//     on to render.tolerance; unknown until two estimates fall;
//   - the passes toward the cap: `measure` (traces a pixel, or bands) grows toward `cap` at the
//     rate so far — elapsed × (cap − measure) / measure (for the flat renderer's doubling bands the
//     levels done cost ~2·measure and the levels left ~2·(cap − measure), the same ratio).
class ProgressLine {
 public:
  ProgressLine(bool enabled, bool tty) : enabled_(enabled), tty_(tty) {}
  bool enabled() const { return enabled_; }

  // A new render: its label (the sweep's frame, "" for a single image), tolerance and cap (0: none).
  void begin(std::string label, double tolerance, double cap) {
    label_ = std::move(label);
    tolerance_ = tolerance;
    cap_ = cap;
    history_.clear();
  }

  void update(int passes, double measure, std::optional<double> estimate, double elapsed_ms,
              const std::string& stopped, bool preview = false) {
    if (!enabled_) return;
    const double t = elapsed_ms * 1e-3;
    if (!preview) history_.push_back({t, measure, estimate});
    char est[64], line[512];
    if (estimate)
      std::snprintf(est, sizeof est, "ΔE≈%.3f (tolerance %.3g)", *estimate, tolerance_);
    else
      std::snprintf(est, sizeof est, "ΔE≈? (tolerance %.3g)", tolerance_);
    std::string left;
    if (!stopped.empty()) {
      left = "stopped: " + stopped;
    } else if (const std::optional<double> s = time_left_s()) {
      char b[48];
      std::snprintf(b, sizeof b, "~%.1f s left", *s);
      left = b;
    } else {
      left = "? left";
    }
    std::snprintf(line, sizeof line, "%s%s%s  pass %d  %s  %.1f s  %s", label_.c_str(), label_.empty() ? "" : ": ",
                  preview ? "preview" : stopped.empty() ? "rendering" : "done", passes, est, t, left.c_str());
    emit(line);
  }

  // A line of its own (a sweep's composed frame).
  void note(const std::string& text) {
    if (enabled_) emit(text);
  }

  // Ends the line in place on a terminal.
  void end() {
    if (enabled_ && tty_ && drawn_) std::fputc('\n', stderr);
    drawn_ = false;
    std::fflush(stderr);
  }

 private:
  struct Point {
    double t_s, measure;
    std::optional<double> estimate;
  };

  void emit(const char* line) { emit(std::string(line)); }
  void emit(const std::string& line) {
    if (tty_)
      std::fprintf(stderr, "\r%s\033[K", line.c_str());
    else
      std::fprintf(stderr, "%s\n", line.c_str());
    drawn_ = true;
    std::fflush(stderr);
  }

  std::optional<double> time_left_s() const {
    std::optional<double> best;
    auto take = [&](double s) {
      if (std::isfinite(s) && s >= 0 && (!best || s < *best)) best = s;
    };
    if (history_.empty()) return best;
    const Point& now = history_.back();
    // The estimate's trend toward the tolerance.
    std::vector<std::pair<double, double>> xy;  // (log t, log estimate), the last four
    for (auto it = history_.rbegin(); it != history_.rend() && xy.size() < 4; ++it)
      if (it->estimate && *it->estimate > 0 && it->t_s > 0) xy.emplace_back(std::log(it->t_s), std::log(*it->estimate));
    if (now.estimate && *now.estimate <= tolerance_) {
      take(0.0);
    } else if (xy.size() >= 2 && now.estimate) {
      double mx = 0, my = 0;
      for (const auto& [x, y] : xy) mx += x, my += y;
      mx /= xy.size();
      my /= xy.size();
      double sxx = 0, sxy = 0;
      for (const auto& [x, y] : xy) sxx += (x - mx) * (x - mx), sxy += (x - mx) * (y - my);
      const double slope = sxx > 0 ? sxy / sxx : 0.0;
      if (slope < -1e-3) {
        // log e = my + slope·(log t − mx) reaches log(tolerance) at:
        const double t_tol = std::exp(mx + (std::log(tolerance_) - my) / slope);
        take(t_tol - now.t_s);
      }
    }
    // The passes toward the cap.
    if (cap_ > 0 && now.measure > 0 && now.t_s > 0) take(now.t_s * std::max(0.0, cap_ - now.measure) / now.measure);
    return best;
  }

  bool enabled_, tty_;
  bool drawn_ = false;
  std::string label_;
  double tolerance_ = 0.5, cap_ = 0.0;
  std::vector<Point> history_;
};

// What a render's progress counts toward its cap: a traced specimen's traces a pixel toward the
// cap its renderer uses (render.spp, or the specimen's default: 64 between the polars, 256 in
// plane light), the flat renderer's bands toward render.wavelengths or its last level. Without
// the cap the time left rested on the estimate's trend alone, which swung from hours to minutes
// on the default render (38 056 s, then 3 655 s, then 324 s one pass before it stopped).
double progress_cap(const pmsim::Scene& scene) {
  if (pmsim::is_traced_specimen(scene)) return pmsim::plane_light_options(scene).spp;
  if (scene.render.single_wavelength_nm > 0) return 0.0;
  return scene.render.wavelengths > 0 ? scene.render.wavelengths : pmsim::kProgressiveMaxBands;
}
double progress_measure(const pmsim::Scene& scene, const pmsim::RenderImage& img) {
  return pmsim::is_traced_specimen(scene) ? img.samples_per_pixel : img.wavelengths;
}

// The render's callback for the progress line; none when the line is off (a traced specimen
// composes an image for every pass it reports).
std::function<void(const pmsim::RenderImage&)> progress_callback(ProgressLine& progress, const pmsim::Scene& scene) {
  if (!progress.enabled()) return nullptr;
  return [&progress, &scene](const pmsim::RenderImage& im) {
    progress.update(im.passes, progress_measure(scene, im), im.error_estimate, im.time_ms, im.stopped);
  };
}

bool ends_with_ci(std::string s, const std::string& suf) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s.size() >= suf.size() && s.compare(s.size() - suf.size(), suf.size(), suf) == 0;
}

// --sweep KEY=START:STOP:STEP: the instrument keys a traced response can be composed at, and the
// values START, START + STEP, … up to STOP (within 1e-9·STEP, so that 0:1:0.1 ends at 1).
constexpr const char* kSweepKeys[] = {"stage_deg", "polarizer_deg", "analyzer_deg", "compensator_position"};
constexpr int kMaxSweepFrames = 3600;

struct Sweep {
  std::string key;
  double start = 0, stop = 0, step = 0;
  std::vector<std::string> values;  // each as --set would take it (%.15g: 0.30000000000000004 is 0.3)
};

Sweep parse_sweep(const std::string& arg) {
  const auto bad = [&](const std::string& why) { usage_error("--sweep " + arg + ": " + why); };
  const auto eq = arg.find('=');
  if (eq == std::string::npos) bad("expected KEY=START:STOP:STEP");
  Sweep sw;
  sw.key = arg.substr(0, eq);
  bool known = false;
  std::string keys;
  for (const char* k : kSweepKeys) {
    known = known || sw.key == k;
    keys += std::string(keys.empty() ? "" : ", ") + k;
  }
  if (!known) bad("key '" + sw.key + "' cannot be swept (one of " + keys + ")");
  std::vector<std::string> parts;
  const std::string range = arg.substr(eq + 1);
  for (std::size_t p = 0;;) {
    const std::size_t c = range.find(':', p);
    parts.push_back(range.substr(p, c == std::string::npos ? std::string::npos : c - p));
    if (c == std::string::npos) break;
    p = c + 1;
  }
  if (parts.size() != 3) bad("expected KEY=START:STOP:STEP (three numbers), got '" + range + "'");
  double v[3];
  const char* names[] = {"START", "STOP", "STEP"};
  for (int i = 0; i < 3; ++i) {
    const std::string& t = parts[i];
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v[i]);
    if (t.empty() || ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(v[i]))
      bad(std::string(names[i]) + " '" + t + "' is not a number");
  }
  sw.start = v[0];
  sw.stop = v[1];
  sw.step = v[2];
  if (!(sw.step > 0)) bad("STEP " + parts[2] + " must be > 0");
  if (sw.start > sw.stop) bad("START " + parts[0] + " is above STOP " + parts[1]);
  const double q = (sw.stop - sw.start) / sw.step + 1e-9;  // value i ≤ STOP + 1e-9·STEP ⇔ i ≤ q
  if (!(q < kMaxSweepFrames))
    bad((q < 1e15 ? std::to_string(static_cast<long long>(std::floor(q)) + 1) + " frames" : std::string("too many frames")) +
        " (" + parts[0] + " to " + parts[1] + " by " + parts[2] + "): more than " + std::to_string(kMaxSweepFrames) +
        " frames");
  const int n = static_cast<int>(std::floor(q)) + 1;
  for (int i = 0; i < n; ++i) {
    char b[64];
    std::snprintf(b, sizeof b, "%.15g", sw.start + i * sw.step);
    sw.values.push_back(b);
  }
  return sw;
}

// --out with a sweep: exactly one printf integer field, %d, %Nd or %0Nd ("%%" is a literal %).
struct OutPattern {
  std::string prefix, suffix;
  int width = 0;
  bool zero = false;
  std::string file(int i) const {
    std::string n = std::to_string(i);
    if (static_cast<int>(n.size()) < width) n.insert(0, width - n.size(), zero ? '0' : ' ');
    return prefix + n + suffix;
  }
};

OutPattern parse_out_pattern(const std::string& out) {
  const auto bad = [&](const std::string& why) {
    usage_error("--out " + out + " with --sweep: " + why +
                " (one integer field: %d, %Nd or %0Nd, e.g. frames/stage_%03d.png)");
  };
  OutPattern p;
  int fields = 0;
  std::string* side = &p.prefix;
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (out[i] != '%') {
      *side += out[i];
      continue;
    }
    if (i + 1 < out.size() && out[i + 1] == '%') {
      *side += '%';
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    const bool zero = j < out.size() && out[j] == '0';
    if (zero) ++j;
    std::size_t d = j;
    while (d < out.size() && std::isdigit(static_cast<unsigned char>(out[d]))) ++d;
    if (d >= out.size() || out[d] != 'd') bad("'" + out.substr(i, d + 1 - i) + "' is not an integer field");
    if (d - j > 2) bad("field width '" + out.substr(j, d - j) + "' is too wide");
    if (++fields > 1) bad("more than one field");
    p.zero = zero;
    p.width = d > j ? std::stoi(out.substr(j, d - j)) : 0;
    side = &p.suffix;
    i = d;
  }
  if (fields == 0) bad("no frame-number field");
  return p;
}

// Writable folders for every file about to be written, before anything is rendered: a failure
// leaves no image without its labels (and none of the files half-written).
void check_writable(const std::vector<std::string>& paths) {
  std::vector<std::filesystem::path> seen;
  for (const std::string& p : paths) {
    if (p.empty()) continue;
    const std::filesystem::path dir = std::filesystem::absolute(p).parent_path();
    if (std::find(seen.begin(), seen.end(), dir) != seen.end()) continue;
    seen.push_back(dir);
    if (::access(dir.c_str(), W_OK | X_OK) != 0)
      throw std::runtime_error("cannot write " + p + ": folder " + dir.string() + " is not writable");
  }
}

nlohmann::json image_stats(const pmsim::RenderImage& img) {
  return {{"time_ms", img.time_ms},
          {"samples_per_pixel", img.samples_per_pixel},
          {"wavelengths", img.wavelengths},
          {"error_estimate", img.error_estimate ? nlohmann::json(*img.error_estimate) : nlohmann::json()},
          {"converged", img.converged},
          {"stopped", img.stopped},
          {"passes", img.passes},
          {"model_report", img.model_report}};
}

// One image's pixels as written: exposure and colour vision for 8-bit PNG, then the scale bar.
std::vector<float> output_pixels(const pmsim::Scene& scene, std::vector<float> rgb, int width, int height,
                                 const std::string& out, bool scale_bar) {
  // render.exposure_ev and render.vision change the 8-bit PNG only (before the scale bar, which
  // stays white); EXR and TIFF are linear floats and carry the keys in their scene metadata.
  if (ends_with_ci(out, ".png")) rgb = pmsim::displayed(rgb, scene.render.exposure_ev, scene.render.vision);
  if (scale_bar)
    pmsim::burn_scale_bar(rgb, width, height,
                          pmsim::choose_scale_bar(pmsim::mm_per_pixel(scene, width, height), width));
  return rgb;
}

// --sweep: every frame's scene (the key set through apply_settings, as --set does: the same
// validation), checked before anything renders; then the frames, each written as it is made.
int run_sweep(const Args& args, const Sweep& sw, const OutPattern& pattern, const pmsim::Scene& scene,
              ProgressLine& progress) {
  std::vector<pmsim::Scene> frames;
  for (const std::string& v : sw.values) {
    pmsim::Scene f = scene;
    try {
      pmsim::apply_settings(f, {sw.key + "=" + v});
    } catch (const pmsim::InputError& e) {
      std::cerr << kProgram << ": --sweep " << args.sweep << ": " << e.what() << "\n";
      return 2;
    }
    frames.push_back(std::move(f));
  }
  const int n = static_cast<int>(frames.size());
  std::vector<std::string> files;
  for (int i = 0; i < n; ++i) files.push_back(pattern.file(i));
  std::vector<std::string> outputs = files;
  outputs.push_back(args.stats);
  check_writable(outputs);

  const auto t0 = std::chrono::steady_clock::now();
  // One response serves every frame when the swept key only moves the instrument on a view that
  // has one (core/specimen/instrument_response.h): a traced specimen's, traced once (over the disc
  // the field sweeps when the stage turns), or a conoscopic figure's nine probes.
  bool one_response = true;
  for (const pmsim::Scene& f : frames) one_response = one_response && pmsim::response_serves(frames[0], f);
  const bool disc = sw.key == "stage_deg";
  nlohmann::json frame_stats = nlohmann::json::array(), response_stats;
  std::optional<pmsim::InstrumentResponse> response;
  if (one_response) {
    const pmsim::ResponseKind kind = pmsim::response_kind(frames[0]);
    const bool probed = kind == pmsim::ResponseKind::Figure || kind == pmsim::ResponseKind::Flat;
    progress.begin(kind == pmsim::ResponseKind::Figure ? "figure response"
                   : kind == pmsim::ResponseKind::Flat ? "flat response"
                                                       : std::string("response (") + (disc ? "disc" : "field") + ")",
                   frames[0].render.tolerance_de2000, progress_cap(frames[0]));
    const pmsim::Scene& first = frames[0];
    response = pmsim::render_instrument_response(
        first, disc ? pmsim::ResponseCoverage::Disc : pmsim::ResponseCoverage::Field,
        progress.enabled() ? [&](const pmsim::InstrumentResponse& r) {
          const pmsim::RenderImage st = r.status();
          progress.update(st.passes, progress_measure(first, st), st.error_estimate, st.time_ms, st.stopped,
                          r.preview());
        } : std::function<void(const pmsim::InstrumentResponse&)>());
    progress.end();
    if (!response) throw std::runtime_error("the specimen's response was not rendered");
    const pmsim::RenderImage st = response->status();
    response_stats = {{"coverage", response->coverage_name()},
                      {"time_ms", st.time_ms},
                      {"passes", st.passes},
                      {"error_estimate", st.error_estimate ? nlohmann::json(*st.error_estimate) : nlohmann::json()},
                      {"converged", st.converged},
                      {"stopped", st.stopped},
                      {"model_report", st.model_report}};
    if (probed)
      response_stats["wavelengths"] = st.wavelengths;
    else
      response_stats["samples_per_pixel"] = st.samples_per_pixel;
  }
  bool all_converged = true, all_tolerance = true, any_unknown = false;
  double worst = 0.0;
  std::deque<std::future<void>> writing;
  const std::size_t in_flight = std::max(1u, std::thread::hardware_concurrency());
  for (int i = 0; i < n; ++i) {
    const pmsim::Scene& f = frames[i];
    const std::string label = "frame " + std::to_string(i + 1) + "/" + std::to_string(n) + " " + sw.key + "=" +
                              sw.values[i];
    pmsim::RenderImage img;
    if (response) {
      img = response->compose(pmsim::instrument_settings(f));
      progress.note(label + ": composed");
    } else {
      progress.begin(label, f.render.tolerance_de2000, progress_cap(f));
      img = pmsim::render_microscope_scene(f, progress_callback(progress, f));
      progress.end();
    }
    // Developed, encoded and written on threads of their own while the next frames are composed:
    // a 512² PNG's sRGB encoding and zlib pass (~60 ms on one core) cost ten times composing it.
    // As many frames in flight as cores; an error surfaces when its frame is collected.
    while (writing.size() >= in_flight) {
      writing.front().get();
      writing.pop_front();
    }
    writing.push_back(std::async(std::launch::async, [&args, &f, file = files[i], w = img.width, h = img.height,
                                              rgb = std::move(img.rgb)]() mutable {
      pmsim::write_image(file, w, h, output_pixels(f, std::move(rgb), w, h, file, args.scale_bar),
                         pmsim::scene_to_json(f));
    }));
    nlohmann::json st = image_stats(img);
    st["index"] = i;
    st["value"] = std::stod(sw.values[i]);
    st["file"] = files[i];
    frame_stats.push_back(std::move(st));
    all_converged = all_converged && img.converged;
    all_tolerance = all_tolerance && img.stopped == "tolerance";
    if (img.error_estimate)
      worst = std::max(worst, *img.error_estimate);
    else
      any_unknown = true;
  }
  for (std::future<void>& w : writing) w.get();
  progress.end();
  if (!args.stats.empty()) {
    nlohmann::json stats;
    stats["sweep"] = {{"key", sw.key}, {"start", sw.start}, {"stop", sw.stop}, {"step", sw.step}, {"frames", n}};
    stats["time_ms"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (response) {
      // Every frame carries the response's estimate and stop.
      stats["error_estimate"] = response_stats["error_estimate"];
      stats["converged"] = response_stats["converged"];
      stats["stopped"] = response_stats["stopped"];
    } else {
      stats["error_estimate"] = any_unknown ? nlohmann::json() : nlohmann::json(worst);  // the worst frame's
      stats["converged"] = all_converged;
      stats["stopped"] = all_tolerance ? "tolerance" : "cap";
    }
    stats["response"] = response_stats;  // null: each frame rendered on its own
    stats["frames"] = std::move(frame_stats);
    pmsim::write_text_atomically(args.stats, stats.dump(2) + "\n");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = parse_args(argc, argv);
  if (!(ends_with_ci(args.out, ".png") || ends_with_ci(args.out, ".exr") || ends_with_ci(args.out, ".tif") ||
        ends_with_ci(args.out, ".tiff")))
    usage_error("--out must end in .png, .exr or .tif: '" + args.out + "'");
  if (!args.labels.empty() && !ends_with_ci(args.labels, ".png"))
    usage_error("--labels must end in .png: '" + args.labels + "'");
  const bool ground_truth = !args.labels.empty() || !args.grains.empty();
  const char* ground_truth_flag = !args.labels.empty() ? "--labels" : "--grains";
  std::optional<Sweep> sweep;
  std::optional<OutPattern> pattern;
  if (!args.sweep.empty()) {
    sweep = parse_sweep(args.sweep);
    pattern = parse_out_pattern(args.out);
    if (ground_truth) usage_error(std::string(ground_truth_flag) + " cannot be used with --sweep");
  }
  ProgressLine progress(args.progress || ::isatty(STDERR_FILENO), ::isatty(STDERR_FILENO));
  int width = 0, height = 0;
  std::vector<float> rgb;
  std::vector<std::uint16_t> labels;
  std::shared_ptr<const pmsim::SectionMap> section;
  std::optional<pmsim::Scene> microscope_scene;
  nlohmann::json meta, stats, mount_report;
  try {
    std::vector<std::string> warnings;
    const std::string path =
        args.scene_path.empty() ? pmsim::asset_dir() + "/scenes/quartz_section_ortho.json" : args.scene_path;
    nlohmann::json j = read_scene_json(path);
    if (is_scene3d(j)) {
      if (args.scale_bar)
        throw pmsim::InputError(path, "type", "scene3d", "--scale-bar needs an orthoscopic microscope scene");
      if (ground_truth)
        throw pmsim::InputError(path, "type", "scene3d",
                                std::string(ground_truth_flag) +
                                    " needs a microscope scene with sample.type=section");
      if (sweep) throw pmsim::InputError(path, "type", "scene3d", "--sweep needs a microscope scene");
      for (const std::string& s : args.sets) apply_scene3d_setting(j, s);
      const pmsim::Scene3dDescription desc = pmsim::parse_scene3d(j, path);
      check_writable({args.out, args.stats});
      pmsim::Scene3dImage img = pmsim::render_scene3d(desc);
      img.settings["scene"] = j;
      width = img.width;
      height = img.height;
      rgb = std::move(img.rgb_linear);
      meta = std::move(img.settings);
      // The 3-D renderer runs its fixed samples a pixel once: stopped by that count, with no
      // error estimate to compare with a tolerance, so not claimed converged.
      stats = {{"time_ms", img.time_ms},
               {"samples_per_pixel", desc.camera.samples_per_pixel * desc.camera.samples_per_pixel},
               {"wavelengths", meta.contains("channels") ? meta["channels"] : nlohmann::json(3)},
               {"error_estimate", nullptr},
               {"converged", false},
               {"stopped", "cap"},
               {"passes", 1},
               {"model_report", "scene3d: Whitted ray tracer with SML lenses"}};
    } else {
      if (j.is_object() && j.contains("type") && j["type"] != "microscope" && j["type"] != "pmexercise")
        throw pmsim::InputError(path, "type", j["type"].dump(),
                                "pmsim-render renders \"microscope\" and \"scene3d\" scenes (and an exercise's specimen)");
      pmsim::Scene scene = pmsim::scene_from_json(j, path, &warnings);
      for (const std::string& w : warnings) std::cerr << "pmsim-render: warning: " << w << "\n";
      pmsim::apply_settings(scene, args.sets);
      // render.native=on on an EBSD map: one pixel per point (checked like any --set size).
      scene = pmsim::native_resolution_scene(scene);
      if (scene.render.native) pmsim::validate_scene(scene, path);
      const bool grain_mount = scene.sample_in && scene.sample.type == pmsim::SampleType::Grains;
      if (ground_truth && !(scene.sample_in && (scene.sample.type == pmsim::SampleType::Section || grain_mount))) {
        const nlohmann::json saved = pmsim::scene_to_json(scene);
        throw pmsim::InputError(path, scene.sample_in ? "sample.type" : "sample.present",
                                scene.sample_in ? saved["sample"]["type"].get<std::string>() : "false",
                                std::string(ground_truth_flag) +
                                    " needs a thin section or a grain mount on the stage "
                                    "(sample.type=section or grains)");
      }
      // The bar measures the specimen plane: only the orthoscopic image (without the Bertrand
      // lens) is one; a conoscopic image shows directions, not lengths.
      if (args.scale_bar && scene.mode != pmsim::ViewMode::Ortho)
        throw pmsim::InputError(path, "mode", "cono", "--scale-bar needs the orthoscopic view (mode=ortho)");
      if (args.scale_bar && scene.bertrand_in)
        throw pmsim::InputError(path, "bertrand", "in", "--scale-bar needs the Bertrand lens out (bertrand=out)");
      // An EBSD map's reader warnings (a truncated file: both point counts).
      if (scene.sample_in && scene.sample.type == pmsim::SampleType::Section &&
          pmsim::is_orientation_map_path(scene.sample.section))
        if (const pmsim::MapSectionFacts* f = pmsim::map_section_facts(*pmsim::load_scene_section(scene)))
          for (const std::string& w : f->warnings) std::cerr << "pmsim-render: warning: " << w << "\n";
      if (sweep) return run_sweep(args, *sweep, *pattern, scene, progress);
      check_writable({args.labels, args.grains, args.out, args.stats});
      progress.begin("", scene.render.tolerance_de2000, progress_cap(scene));
      // One image from whichever source the scene needs (a traced specimen's response composed
      // at its settings, or the progressive renderer's flat image): core/specimen/traced_specimen.h.
      pmsim::RenderImage img = pmsim::render_microscope_scene(scene, progress_callback(progress, scene));
      progress.end();
      width = img.width;
      height = img.height;
      rgb = output_pixels(scene, std::move(img.rgb), width, height, args.out, args.scale_bar);
      meta = pmsim::scene_to_json(scene);
      if (ground_truth && grain_mount) {
        const std::shared_ptr<const pmsim::SpecimenScene> mount = pmsim::grain_mount_specimen_cached(scene);
        labels = pmsim::fragment_label_image(*mount, scene);
        mount_report = pmsim::grain_mount_report_json(scene, pmsim::fragment_truths(*mount, scene, labels),
                                                      mount->liquid().n(pmsim::kBeckeWavelengthNm));
      } else if (ground_truth) {
        section = pmsim::load_scene_section(scene);
        labels = pmsim::grain_label_image(scene, *section);
        microscope_scene = scene;
      }
      stats = image_stats(img);
    }
  } catch (const pmsim::InputError& e) {
    progress.end();
    std::cerr << kProgram << ": " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    progress.end();
    std::cerr << "pmsim-render: not enough memory to render this scene (try a smaller "
                 "render.width × render.height)\n";
    return 1;
  } catch (const std::exception& e) {  // no future throw may abort: a message and exit 1
    progress.end();
    std::cerr << kProgram << ": " << e.what() << "\n";
    return 1;
  }
  try {
    // The ground truth first, each file atomic (every folder was checked before rendering).
    if (!args.labels.empty()) pmsim::write_gray16_png(args.labels, width, height, labels, meta);
    if (!args.grains.empty() && !mount_report.is_null())
      pmsim::write_text_atomically(args.grains, mount_report.dump(2) + "\n");
    else if (!args.grains.empty())
      pmsim::write_grain_report_file(args.grains, *microscope_scene, *section,
                                     pmsim::report_grains(*microscope_scene, *section, labels));
    pmsim::write_image(args.out, width, height, rgb, meta);
    if (!args.stats.empty()) pmsim::write_text_atomically(args.stats, stats.dump(2) + "\n");
  } catch (const std::bad_alloc&) {
    std::cerr << "pmsim-render: not enough memory to write " << args.out << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}
