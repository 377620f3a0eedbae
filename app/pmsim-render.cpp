// pmsim-render [SCENE.json] [--set key=value]... --out FILE.png|.exr|.tif [--stats FILE.json]
// Renders a microscope scene to convergence (or to render.spp / render.wavelengths) and writes
// the image atomically. Bad input: a message naming file, key and value on stderr, exit code 2,
// no output file.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/io/atomic_file.h"
#include "core/io/image_file.h"
#include "core/io/input_error.h"
#include "core/io/scene_file.h"
#include "core/microscope/sample_source.h"
#include "core/render/progressive_renderer.h"

namespace {

constexpr const char* kUsage =
    "usage: pmsim-render [SCENE.json] [--set key=value]... --out FILE.png|.exr|.tif "
    "[--stats FILE.json]\n"
    "  Without SCENE, renders the default scene (assets/scenes/quartz_section_ortho.json).\n"
    "  Keys are the scene's dot paths, e.g. --set stage_deg=45 --set sample.mineral=calcite.\n";

struct Args {
  std::string scene_path, out, stats;
  std::vector<std::string> sets;
};

[[noreturn]] void usage_error(const std::string& msg) {
  std::cerr << "pmsim-render: " << msg << "\n" << kUsage;
  std::exit(2);
}

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto value = [&](const char* opt) {
      if (i + 1 >= argc) usage_error(std::string(opt) + " needs a value");
      return std::string(argv[++i]);
    };
    if (s == "--help" || s == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (s == "--set") {
      a.sets.push_back(value("--set"));
    } else if (s.rfind("--set=", 0) == 0) {
      a.sets.push_back(s.substr(6));
    } else if (s == "--out" || s == "-o") {
      a.out = value("--out");
    } else if (s.rfind("--out=", 0) == 0) {
      a.out = s.substr(6);
    } else if (s == "--stats") {
      a.stats = value("--stats");
    } else if (s.rfind("--stats=", 0) == 0) {
      a.stats = s.substr(8);
    } else if (!s.empty() && s[0] == '-') {
      usage_error("unknown option '" + s + "'");
    } else if (a.scene_path.empty()) {
      a.scene_path = s;
    } else {
      usage_error("more than one scene file given ('" + a.scene_path + "', '" + s + "')");
    }
  }
  if (a.out.empty()) usage_error("--out FILE is required");
  return a;
}

// The single place where scene types dispatch: microscope scenes (the default) render here; a
// "scene3d" scene is for the lead's 3-D renderer to add.
pmsim::Scene load_microscope_scene(const std::string& path, std::vector<std::string>& warnings) {
  std::ifstream f(path);
  if (!f) throw pmsim::InputError(path, "", "", "cannot open the scene file");
  nlohmann::json j = nlohmann::json::parse(f, nullptr, false);
  if (j.is_discarded()) throw pmsim::InputError(path, "", "", "not valid JSON");
  if (j.is_object() && j.contains("type") && j["type"] != "microscope")
    throw pmsim::InputError(path, "type", j["type"].dump(),
                            "pmsim-render renders \"microscope\" scenes");
  return pmsim::scene_from_json(j, path, &warnings);
}

void progress_bar(const pmsim::RenderImage& img) {
  std::fprintf(stderr, "\r%-10s pass %2d  %5d bands  ΔE≈%7.3f  %8.1f ms", img.converged ? "done" : "rendering",
               img.passes, img.wavelengths, img.error_estimate, img.time_ms);
  std::fflush(stderr);
}

bool ends_with_ci(std::string s, const std::string& suf) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s.size() >= suf.size() && s.compare(s.size() - suf.size(), suf.size(), suf) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = parse_args(argc, argv);
  if (!(ends_with_ci(args.out, ".png") || ends_with_ci(args.out, ".exr") ||
        ends_with_ci(args.out, ".tif") || ends_with_ci(args.out, ".tiff")))
    usage_error("--out must end in .png, .exr or .tif: '" + args.out + "'");
  pmsim::Scene scene;
  pmsim::RenderImage img;
  try {
    std::vector<std::string> warnings;
    const std::string path = args.scene_path.empty()
                                 ? pmsim::asset_dir() + "/scenes/quartz_section_ortho.json"
                                 : args.scene_path;
    scene = load_microscope_scene(path, warnings);
    for (const std::string& w : warnings) std::cerr << "pmsim-render: warning: " << w << "\n";
    for (const std::string& s : args.sets) pmsim::apply_setting(scene, s);
    const bool tty = ::isatty(STDERR_FILENO);
    img = pmsim::ProgressiveRenderer::render(
        scene, 0, tty ? std::function<void(const pmsim::RenderImage&)>(progress_bar) : nullptr);
    if (tty) std::fprintf(stderr, "\n");
  } catch (const pmsim::InputError& e) {
    std::cerr << "pmsim-render: " << e.what() << "\n";
    return 2;
  }
  try {
    nlohmann::json meta = pmsim::scene_to_json(scene);
    pmsim::write_image(args.out, img.width, img.height, img.rgb, meta);
    if (!args.stats.empty()) {
      const nlohmann::json stats = {{"time_ms", img.time_ms},
                                    {"samples_per_pixel", img.samples_per_pixel},
                                    {"wavelengths", img.wavelengths},
                                    {"error_estimate", img.error_estimate},
                                    {"converged", img.converged},
                                    {"passes", img.passes},
                                    {"model_report", img.model_report}};
      pmsim::write_text_atomically(args.stats, stats.dump(2) + "\n");
    }
  } catch (const std::exception& e) {
    std::cerr << "pmsim-render: " << e.what() << "\n";
    std::error_code ec;
    return 1;
  }
  return 0;
}
