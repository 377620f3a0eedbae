// Fuzz entries for the scene input paths: scene files (load_scene_file: open, parse, read every
// key, validate) and `--set key=value` lines (apply_setting, the path the CLI and the UI share).
// Oracles: only InputError may escape; a scene that was accepted is valid and survives
// scene_to_json → text → scene_from_json unchanged and without warnings.
#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/crystal/crystal.h"
#include "core/base/input_error.h"
#include "core/io/scene_file.h"
#include "tests/fuzz/fuzz_support.h"
#include "tests/fuzz/fuzz_targets.h"

namespace pmsim::fuzz {

namespace {

// What the renderer builds from an accepted scene must not throw: the crystal orientation
// (either kind, as the mineral can be switched without touching the axes).
void check_orientation(const Scene& s, const char* who) {
  const auto v = [](const std::array<double, 3>& a) { return glm::dvec3(a[0], a[1], a[2]); };
  try {
    uniaxial_orientation(v(s.sample.optic_axis));
    biaxial_orientation(v(s.sample.x_axis), v(s.sample.z_axis));
  } catch (const std::exception& e) {
    fail(std::string(who) + ": an accepted scene has axes the renderer rejects: " + e.what());
  }
}

void check_round_trip(const Scene& s, const char* who) {
  check_orientation(s, who);
  const nlohmann::json j = scene_to_json(s);
  std::vector<std::string> warnings;
  Scene back;
  try {
    validate_scene(s, "");
    back = scene_from_json(nlohmann::json::parse(j.dump()), "round-trip", &warnings);
  } catch (const std::exception& e) {
    fail(std::string(who) + ": an accepted scene does not load back: " + e.what() + "\n" +
         j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  }
  if (!warnings.empty()) fail(std::string(who) + ": saving then loading warns: " + warnings.front());
  const nlohmann::json j2 = scene_to_json(back);
  check(j2 == j, std::string(who) + ": save → load changes the scene:\n" + j.dump() + "\n" +
                     j2.dump());  // both dumped fine above
}

std::vector<std::filesystem::path> json_files(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().extension() == ".json") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

std::string read_text(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

}  // namespace

int scene_parser(const std::uint8_t* data, std::size_t size) {
  const std::string path = write_scratch("scene", data, size);
  Scene s;
  std::vector<std::string> warnings;
  try {
    s = load_scene_file(path, &warnings);
  } catch (const InputError&) {
    return 0;  // the expected answer to bad input
  } catch (const std::exception& e) {
    fail(std::string("scene_parser: an exception other than InputError escaped: ") + e.what());
  }
  for (const std::string& w : warnings)
    check(w.find('\'') != std::string::npos, "scene_parser: a warning that names no key: " + w);
  check_round_trip(s, "scene_parser");
  return 0;
}

int scene_setting(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  Scene s;
  std::istringstream in(text);
  std::string line;
  for (int n = 0; n < 64 && std::getline(in, line); ++n) {
    try {
      apply_setting(s, line);
    } catch (const InputError&) {
      continue;  // the scene must stay the last good one
    } catch (const std::exception& e) {
      fail("scene_setting: an exception other than InputError escaped for '" + line + "': " + e.what());
    }
  }
  check_round_trip(s, "scene_setting");
  return 0;
}

void scene_parser_seeds(const std::string& asset_dir, const std::string& out_dir) {
  int i = 0;
  for (const auto& p : json_files(std::filesystem::path(asset_dir) / "scenes"))
    write_file(out_dir + "/asset_" + p.filename().string(), read_text(p));
  for (const char* extra :
       {"{}", "{\"type\":\"microscope\"}", "{\"sample\":{\"crystal\":{\"no\":1.5,\"ne\":1.6}}}",
        "{\"render\":{\"width\":1e9}}", "{\"sample\":{\"optic_axis\":[0,0,0]}}"})
    write_file(out_dir + "/edge_" + std::to_string(i++) + ".json", std::string(extra));
}

void scene_setting_seeds(const std::string& asset_dir, const std::string& out_dir) {
  for (const auto& p : json_files(std::filesystem::path(asset_dir) / "scenes")) {
    const nlohmann::json j = nlohmann::json::parse(read_text(p), nullptr, false);
    if (j.is_discarded() || !j.is_object()) continue;
    std::string lines;
    const nlohmann::json flat = j.flatten();
    for (const auto& [ptr, v] : flat.items()) {
      std::string key = ptr.substr(1);
      std::replace(key.begin(), key.end(), '/', '.');
      if (key.rfind("source", 0) == 0 || key.rfind("description", 0) == 0) continue;
      lines += key + "=" + (v.is_string() ? v.get<std::string>() : v.dump()) + "\n";
    }
    write_file(out_dir + "/asset_" + p.stem().string() + ".txt", lines);
  }
  write_file(out_dir + "/edges.txt",
             std::string("sample.crystal={\"nalpha\":1.5,\"nbeta\":1.6,\"ngamma\":1.7}\n"
                         "mode=cono\nrender.width=100000\nstage_deg=nan\n"
                         "sample.optic_axis=[0,0,0]\nrender.single_wavelength_nm=300\n"));
}

}  // namespace pmsim::fuzz
