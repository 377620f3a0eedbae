// pmsim-render [SCENE.json] [--set key=value]... --out FILE.png|.exr|.tif [--stats FILE.json]
//              [--labels FILE.png] [--grains FILE.json] [--scale-bar]
// Renders a microscope scene to convergence (or to render.spp / render.wavelengths), or a 3-D
// scene ("type": "scene3d", core/scene3d), and writes the image atomically. A thin section's
// ground truth goes with it: --labels the grain under every pixel centre (16-bit grey PNG,
// core/microscope/grain_labels.h), --grains the grains in the image (core/io/grain_report_file.h).
// Bad input: a message naming file, key and value on stderr, exit code 2, no output file.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <new>
#include <optional>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli_policy.h"

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
#include "core/scene3d/scene3d_render.h"
#include "core/specimen/traced_specimen.h"

namespace {

constexpr const char* kProgram = "pmsim-render";

struct Args {
  std::string scene_path, out, stats, labels, grains;
  std::vector<std::string> sets;
  bool scale_bar = false;
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
                 "thin sections: write the grain under every pixel centre as a 16-bit grey PNG "
                 "(0 = mounting medium or slide, k = grain k)")
      ->type_name("FILE.png");
  app.add_option("--grains", a.grains,
                 "thin sections: write the grains in the image (mineral, orientation, area, cleavage "
                 "traces, extinction, retardation, twin) as JSON")
      ->type_name("FILE.json");
  app.add_flag("--scale-bar", a.scale_bar,
               "orthoscopic microscope views: burn a scale bar (section millimetres) into the image, "
               "bottom left, as the app's exports do");
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

void progress_bar(const pmsim::RenderImage& img) {
  std::fprintf(stderr, "\r%-10s pass %2d  %5d bands  ΔE≈%7.3f  %8.1f ms",
               img.converged ? "done" : "rendering", img.passes, img.wavelengths,
               img.error_estimate.value_or(std::nan("")), img.time_ms);
  std::fflush(stderr);
}

bool ends_with_ci(std::string s, const std::string& suf) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s.size() >= suf.size() && s.compare(s.size() - suf.size(), suf.size(), suf) == 0;
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
  int width = 0, height = 0;
  std::vector<float> rgb;
  std::vector<std::uint16_t> labels;
  std::shared_ptr<const pmsim::SectionMap> section;
  std::optional<pmsim::Scene> microscope_scene;
  nlohmann::json meta, stats;
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
      for (const std::string& s : args.sets) apply_scene3d_setting(j, s);
      const pmsim::Scene3dDescription desc = pmsim::parse_scene3d(j, path);
      pmsim::Scene3dImage img = pmsim::render_scene3d(desc);
      img.settings["scene"] = j;
      width = img.width;
      height = img.height;
      rgb = std::move(img.rgb_linear);
      meta = std::move(img.settings);
      stats = {{"time_ms", img.time_ms},
               {"samples_per_pixel", desc.camera.samples_per_pixel * desc.camera.samples_per_pixel},
               {"wavelengths", meta.contains("channels") ? meta["channels"] : nlohmann::json(3)},
               {"error_estimate", 0.0},
               {"converged", true},
               {"passes", 1},
               {"model_report", "scene3d: Whitted ray tracer with SML lenses"}};
    } else {
      if (j.is_object() && j.contains("type") && j["type"] != "microscope")
        throw pmsim::InputError(path, "type", j["type"].dump(),
                                "pmsim-render renders \"microscope\" and \"scene3d\" scenes");
      pmsim::Scene scene = pmsim::scene_from_json(j, path, &warnings);
      for (const std::string& w : warnings) std::cerr << "pmsim-render: warning: " << w << "\n";
      pmsim::apply_settings(scene, args.sets);
      // render.native=on on an EBSD map: one pixel per point (checked like any --set size).
      scene = pmsim::native_resolution_scene(scene);
      if (scene.render.native) pmsim::validate_scene(scene, path);
      if (ground_truth && !(scene.sample_in && scene.sample.type == pmsim::SampleType::Section)) {
        const nlohmann::json saved = pmsim::scene_to_json(scene);
        throw pmsim::InputError(path, scene.sample_in ? "sample.type" : "sample.present",
                                scene.sample_in ? saved["sample"]["type"].get<std::string>() : "false",
                                std::string(ground_truth_flag) +
                                    " needs a thin section on the stage (sample.type=section)");
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
      const bool tty = ::isatty(STDERR_FILENO);
      const auto bar = tty ? std::function<void(const pmsim::RenderImage&)>(progress_bar) : nullptr;
      // A grain mount, and a thin section with optics.relief on (orthoscopic), are refracting
      // 3-D specimens (core/specimen), traced with their polarization.
      pmsim::RenderImage img = pmsim::is_traced_specimen(scene) ? pmsim::render_traced_specimen(scene, bar)
                                                                : pmsim::ProgressiveRenderer::render(scene, 0, bar);
      if (tty) std::fprintf(stderr, "\n");
      width = img.width;
      height = img.height;
      rgb = std::move(img.rgb);
      // render.exposure_ev scales the 8-bit PNG only (before the scale bar, which stays white);
      // EXR and TIFF are linear floats and carry the key in their scene metadata.
      if (ends_with_ci(args.out, ".png")) rgb = pmsim::exposed(rgb, scene.render.exposure_ev);
      meta = pmsim::scene_to_json(scene);
      if (args.scale_bar)
        pmsim::burn_scale_bar(rgb, width, height,
                              pmsim::choose_scale_bar(pmsim::mm_per_pixel(scene, width, height), width));
      if (ground_truth) {
        section = pmsim::load_scene_section(scene);
        labels = pmsim::grain_label_image(scene, *section);
        microscope_scene = scene;
      }
      stats = {
          {"time_ms", img.time_ms},
          {"samples_per_pixel", img.samples_per_pixel},
          {"wavelengths", img.wavelengths},
          {"error_estimate", img.error_estimate ? nlohmann::json(*img.error_estimate) : nlohmann::json()},
          {"converged", img.converged},
          {"passes", img.passes},
          {"model_report", img.model_report}};
    }
  } catch (const pmsim::InputError& e) {
    std::cerr << kProgram << ": " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "pmsim-render: not enough memory to render this scene (try a smaller "
                 "render.width × render.height)\n";
    return 1;
  } catch (const std::exception& e) {  // no future throw may abort: a message and exit 1
    std::cerr << kProgram << ": " << e.what() << "\n";
    return 1;
  }
  try {
    // The ground truth first, each file atomic, after checking that every output's folder takes
    // files: a failure leaves no image without its labels (and none of the files half-written).
    for (const std::string& p : {args.labels, args.grains, args.out}) {
      if (p.empty()) continue;
      const std::filesystem::path dir = std::filesystem::absolute(p).parent_path();
      if (::access(dir.c_str(), W_OK | X_OK) != 0)
        throw std::runtime_error("cannot write " + p + ": folder " + dir.string() + " is not writable");
    }
    if (!args.labels.empty()) pmsim::write_gray16_png(args.labels, width, height, labels, meta);
    if (!args.grains.empty())
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
