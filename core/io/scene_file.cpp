#include "core/io/scene_file.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "core/io/atomic_file.h"
#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/base/text.h"
#include "core/crystal/lattice.h"
#include "core/microscope/scene_check.h"

namespace pmsim {

using nlohmann::json;

namespace {

double as_number(const json& v) { return number_value(v); }
int as_int(const json& v) { return integer_value(v); }
bool as_bool(const json& v) { return bool_value(v); }
std::string as_string(const json& v) { return string_value(v); }
bool as_in_out(const json& v) {  // "in"|"out" (booleans accepted too)
  if (v.is_boolean()) return v.get<bool>();
  const std::string s = lower_string_value(v);
  if (s == "in") return true;
  if (s == "out") return false;
  throw BadValue{"expected \"in\" or \"out\""};
}
std::array<double, 3> as_vec3(const json& v) { return unit_vector_value(v); }
template <class E>
E as_enum(const json& v, const NameTable<E>& names) {
  return enum_value(v, names);
}
template <class E>
std::string enum_name(E e, const NameTable<E>& names) {
  return names.name(e);
}

const NameTable<ViewMode> kModes = {{"ortho", ViewMode::Ortho}, {"cono", ViewMode::Cono}};
const NameTable<SampleType> kSampleTypes = {
    {"plate", SampleType::Plate}, {"wedge", SampleType::Wedge}, {"section", SampleType::Section},
    {"grains", SampleType::Grains}};
const NameTable<NonIndexed> kNonIndexed = {{"medium", NonIndexed::Medium}, {"black", NonIndexed::Black}};
const NameTable<Compensator> kCompensators = {{"none", Compensator::None},
                                              {"gypsum", Compensator::Gypsum},
                                              {"mica", Compensator::Mica},
                                              {"quartz_wedge", Compensator::QuartzWedge}};
// render.strategy: auto (the cheapest accurate plate model per scene), modal (eigenmodes fitted
// across the spectrum, band-averaged interference terms), exact (plate Jones matrix at every
// wavelength sample, plain midpoint quadrature: the paper's uniform sampling).
const NameTable<RenderStrategy> kStrategies = {
    {"auto", RenderStrategy::Auto}, {"modal", RenderStrategy::Modal}, {"exact", RenderStrategy::Exact}};
const NameTable<LensModel> kLensModels = {
    {"auto", LensModel::Auto}, {"ideal", LensModel::Ideal}, {"physical", LensModel::Physical}};

CrystalIndices as_crystal(const json& v) {
  if (!v.is_object())
    throw BadValue{"expected {\"no\":..,\"ne\":..} or {\"nalpha\":..,\"nbeta\":..,\"ngamma\":..}"};
  CrystalIndices c;
  if (v.contains("no") && v.contains("ne") && v.size() == 2) {
    c.uniaxial = true;
    c.no = as_number(v.at("no"));
    c.ne = as_number(v.at("ne"));
  } else if (v.contains("nalpha") && v.contains("nbeta") && v.contains("ngamma") && v.size() == 3) {
    c.uniaxial = false;
    c.nalpha = as_number(v.at("nalpha"));
    c.nbeta = as_number(v.at("nbeta"));
    c.ngamma = as_number(v.at("ngamma"));
  } else {
    throw BadValue{"expected exactly {\"no\",\"ne\"} or {\"nalpha\",\"nbeta\",\"ngamma\"}"};
  }
  check_crystal_indices(c);
  return c;
}
// sample.cut: {"plane": "(hkl)", "north": "[uvw]"}, the text kept as written (save → load gives
// it back unchanged); its syntax is checked here, its fit to the mineral by check_scene.
SampleCut as_cut(const json& v) {
  if (!v.is_object() || v.size() != 2 || !v.contains("plane") || !v.contains("north"))
    throw BadValue{"expected {\"plane\": \"(hkl)\", \"north\": \"[uvw]\"}"};
  SampleCut c{string_value(v.at("plane")), string_value(v.at("north"))};
  try {
    parse_miller_plane(c.plane);
  } catch (const BadValue& b) {
    throw BadValue{"plane " + c.plane + ": " + b.why};
  }
  try {
    parse_lattice_direction(c.north);
  } catch (const BadValue& b) {
    throw BadValue{"north " + c.north + ": " + b.why};
  }
  return c;
}

// sample.phases: {"<phase name in the map file>": "<mineral>", …}, every value a string (which
// minerals they name is checked when the map is read: core/ebsd/phase_names.h).
std::map<std::string, std::string> as_phases(const json& v) {
  if (!v.is_object()) throw BadValue{"expected {\"<phase name in the file>\": \"<mineral>\", ...}"};
  std::map<std::string, std::string> m;
  for (auto it = v.begin(); it != v.end(); ++it) {
    if (!it.value().is_string()) throw BadValue{"phase '" + it.key() + "': expected a mineral name (a string)"};
    m[it.key()] = it.value().get<std::string>();
  }
  return m;
}

// render.native, optics.relief: on|off (booleans accepted too).
bool as_on_off(const json& v) {
  if (v.is_boolean()) return v.get<bool>();
  const std::string s = lower_string_value(v);
  if (s == "on") return true;
  if (s == "off") return false;
  throw BadValue{"expected \"on\" or \"off\""};
}

json crystal_json(const CrystalIndices& c) {
  if (c.uniaxial) return {{"no", c.no}, {"ne", c.ne}};
  return {{"nalpha", c.nalpha}, {"nbeta", c.nbeta}, {"ngamma", c.ngamma}};
}

// One scene key: how to read it into a Scene and how to write it back.
struct Key {
  const char* path;
  std::function<void(Scene&, const json&)> read;
  std::function<json(const Scene&)> write;
};

// The microscope: view, polars, stage, lenses, illuminant, focus.
std::vector<Key> microscope_keys() {
  return {
    {"mode", [](Scene& s, const json& v) { s.mode = as_enum(v, kModes); },
     [](const Scene& s) -> json { return enum_name(s.mode, kModes); }},
    {"polarizer_deg", [](Scene& s, const json& v) { s.polarizer_deg = as_number(v); },
     [](const Scene& s) -> json { return s.polarizer_deg; }},
    {"analyzer_deg", [](Scene& s, const json& v) { s.analyzer_deg = as_number(v); },
     [](const Scene& s) -> json { return s.analyzer_deg; }},
    {"analyzer", [](Scene& s, const json& v) { s.analyzer_in = as_in_out(v); },
     [](const Scene& s) -> json { return s.analyzer_in ? "in" : "out"; }},
    {"stage_deg", [](Scene& s, const json& v) { s.stage_deg = as_number(v); },
     [](const Scene& s) -> json { return s.stage_deg; }},
    {"stage.x_mm", [](Scene& s, const json& v) { s.stage.x_mm = as_number(v); },
     [](const Scene& s) -> json { return s.stage.x_mm; }},
    {"stage.y_mm", [](Scene& s, const json& v) { s.stage.y_mm = as_number(v); },
     [](const Scene& s) -> json { return s.stage.y_mm; }},
    {"bertrand", [](Scene& s, const json& v) { s.bertrand_in = as_in_out(v); },
     [](const Scene& s) -> json { return s.bertrand_in ? "in" : "out"; }},
    {"illuminant",
     [](Scene& s, const json& v) {
       if (!parse_illuminant(as_string(v), s.illuminant)) throw BadValue{"expected D65 or A"};
     },
     [](const Scene& s) -> json { return std::string(illuminant_name(s.illuminant)); }},
    {"objective.magnification", [](Scene& s, const json& v) { s.objective.magnification = as_number(v); },
     [](const Scene& s) -> json { return s.objective.magnification; }},
    {"objective.na", [](Scene& s, const json& v) { s.objective.na = as_number(v); },
     [](const Scene& s) -> json { return s.objective.na; }},
    {"eyepiece.field_number_mm", [](Scene& s, const json& v) { s.eyepiece.field_number_mm = as_number(v); },
     [](const Scene& s) -> json { return s.eyepiece.field_number_mm; }},
    {"condenser.na", [](Scene& s, const json& v) { s.condenser.na = as_number(v); },
     [](const Scene& s) -> json { return s.condenser.na; }},
    {"condenser.aperture_na", [](Scene& s, const json& v) { s.condenser.aperture_na = as_number(v); },
     [](const Scene& s) -> json { return s.condenser.aperture_na; }},
    {"focus_um", [](Scene& s, const json& v) { s.focus_um = as_number(v); },
     [](const Scene& s) -> json { return s.focus_um; }},
  };
}

// The sample on the stage.
std::vector<Key> sample_keys() {
  return {
    {"sample.present", [](Scene& s, const json& v) { s.sample_in = as_bool(v); },
     [](const Scene& s) -> json { return s.sample_in; }},
    {"sample.type", [](Scene& s, const json& v) { s.sample.type = as_enum(v, kSampleTypes); },
     [](const Scene& s) -> json { return enum_name(s.sample.type, kSampleTypes); }},
    {"sample.mineral",
     [](Scene& s, const json& v) {
       s.sample.mineral = as_string(v);
       s.sample.crystal.reset();  // the latest choice of sample wins
     },
     [](const Scene& s) -> json { return s.sample.mineral; }},
    {"sample.crystal",
     [](Scene& s, const json& v) {
       if (v.is_null() || (v.is_string() && lower_case(v.get<std::string>()) == "none"))
         s.sample.crystal.reset();
       else
         s.sample.crystal = as_crystal(v);
     },
     [](const Scene& s) -> json {
       return s.sample.crystal ? crystal_json(*s.sample.crystal) : json(nullptr);
     }},
    {"sample.thickness_um", [](Scene& s, const json& v) { s.sample.thickness_um = as_number(v); },
     [](const Scene& s) -> json { return s.sample.thickness_um; }},
    {"sample.optic_axis", [](Scene& s, const json& v) { s.sample.optic_axis = as_vec3(v); },
     [](const Scene& s) -> json { return s.sample.optic_axis; }},
    {"sample.x_axis", [](Scene& s, const json& v) { s.sample.x_axis = as_vec3(v); },
     [](const Scene& s) -> json { return s.sample.x_axis; }},
    {"sample.z_axis", [](Scene& s, const json& v) { s.sample.z_axis = as_vec3(v); },
     [](const Scene& s) -> json { return s.sample.z_axis; }},
    {"sample.cut",
     [](Scene& s, const json& v) {
       if (v.is_null() || (v.is_string() && lower_case(v.get<std::string>()) == "none"))
         s.sample.cut.reset();
       else
         s.sample.cut = as_cut(v);
     },
     [](const Scene& s) -> json {
       return s.sample.cut ? json{{"plane", s.sample.cut->plane}, {"north", s.sample.cut->north}}
                           : json(nullptr);
     }},
    {"sample.section", [](Scene& s, const json& v) { s.sample.section = as_string(v); },
     [](const Scene& s) -> json { return s.sample.section; }},
    {"sample.medium", [](Scene& s, const json& v) { s.sample.medium = as_string(v); },
     [](const Scene& s) -> json { return s.sample.medium; }},
    // The EBSD map keys are written only when they differ from the default, so that the saved
    // form (and image metadata) of every other scene stays as it was.
    {"sample.phases", [](Scene& s, const json& v) { s.sample.phases = as_phases(v); },
     [](const Scene& s) -> json { return s.sample.phases.empty() ? json(nullptr) : json(s.sample.phases); }},
    {"sample.nonindexed", [](Scene& s, const json& v) { s.sample.nonindexed = as_enum(v, kNonIndexed); },
     [](const Scene& s) -> json {
       return s.sample.nonindexed == NonIndexed::Medium ? json(nullptr) : json(enum_name(s.sample.nonindexed, kNonIndexed));
     }},
    {"sample.medium_index",
     [](Scene& s, const json& v) {
       if (v.is_null() || (v.is_string() && lower_case(v.get<std::string>()) == "none"))
         s.sample.medium_index.reset();
       else
         s.sample.medium_index = as_number(v);
     },
     [](const Scene& s) -> json { return s.sample.medium_index ? json(*s.sample.medium_index) : json(nullptr); }},
    {"sample.orientation_seed",
     [](Scene& s, const json& v) {
       if (v.is_null() || (v.is_string() && lower_case(v.get<std::string>()) == "none"))
         s.sample.orientation_seed.reset();
       else
         s.sample.orientation_seed = as_int(v);
     },
     [](const Scene& s) -> json { return s.sample.orientation_seed ? json(*s.sample.orientation_seed) : json(nullptr); }},
    {"sample.seed",
     [](Scene& s, const json& v) {
       if (v.is_null() || (v.is_string() && lower_case(v.get<std::string>()) == "none"))
         s.sample.seed.reset();
       else
         s.sample.seed = as_int(v);
     },
     [](const Scene& s) -> json { return s.sample.seed ? json(*s.sample.seed) : json(nullptr); }},
  };
}

// The accessory slot, the render and the optics models.
std::vector<Key> slot_render_optics_keys() {
  return {
    {"compensator", [](Scene& s, const json& v) { s.compensator = as_enum(v, kCompensators); },
     [](const Scene& s) -> json { return enum_name(s.compensator, kCompensators); }},
    {"compensator_position", [](Scene& s, const json& v) { s.compensator_position = as_number(v); },
     [](const Scene& s) -> json { return s.compensator_position; }},
    {"render.width", [](Scene& s, const json& v) { s.render.width = as_int(v); },
     [](const Scene& s) -> json { return s.render.width; }},
    {"render.height", [](Scene& s, const json& v) { s.render.height = as_int(v); },
     [](const Scene& s) -> json { return s.render.height; }},
    {"render.spp", [](Scene& s, const json& v) { s.render.spp = as_int(v); },
     [](const Scene& s) -> json { return s.render.spp; }},
    {"render.wavelengths", [](Scene& s, const json& v) { s.render.wavelengths = as_int(v); },
     [](const Scene& s) -> json { return s.render.wavelengths; }},
    {"render.single_wavelength_nm",
     [](Scene& s, const json& v) { s.render.single_wavelength_nm = as_number(v); },
     [](const Scene& s) -> json { return s.render.single_wavelength_nm; }},
    {"render.tolerance", [](Scene& s, const json& v) { s.render.tolerance_de2000 = as_number(v); },
     [](const Scene& s) -> json { return s.render.tolerance_de2000; }},
    {"render.strategy", [](Scene& s, const json& v) { s.render.strategy = as_enum(v, kStrategies); },
     [](const Scene& s) -> json { return enum_name(s.render.strategy, kStrategies); }},
    {"render.native", [](Scene& s, const json& v) { s.render.native = as_on_off(v); },
     [](const Scene& s) -> json { return s.render.native ? json("on") : json(nullptr); }},
    {"render.exposure_ev", [](Scene& s, const json& v) { s.render.exposure_ev = as_number(v); },
     [](const Scene& s) -> json { return s.render.exposure_ev != 0.0 ? json(s.render.exposure_ev) : json(nullptr); }},
    {"render.vision",
     [](Scene& s, const json& v) {
       if (!parse_colour_vision(as_string(v), s.render.vision))
         throw BadValue{"expected normal, protanopia, deuteranopia or tritanopia"};
     },
     [](const Scene& s) -> json {
       return s.render.vision != ColourVision::Normal ? json(std::string(colour_vision_name(s.render.vision)))
                                                       : json(nullptr);
     }},
    {"optics.lens_model", [](Scene& s, const json& v) { s.optics.lens_model = as_enum(v, kLensModels); },
     [](const Scene& s) -> json { return enum_name(s.optics.lens_model, kLensModels); }},
    {"optics.lens_depth", [](Scene& s, const json& v) { s.optics.lens_depth = as_int(v); },
     [](const Scene& s) -> json { return s.optics.lens_depth; }},
    {"optics.relief", [](Scene& s, const json& v) { s.optics.relief = as_on_off(v); },
     [](const Scene& s) -> json { return s.optics.relief ? json(nullptr) : json("off"); }},
    {"optics.schlick",  // a bool in files and --set: true is the Schlick approximation
     [](Scene& s, const json& v) {
       s.optics.fresnel = as_bool(v) ? FresnelModel::Schlick : FresnelModel::Exact;
     },
     [](const Scene& s) -> json { return s.optics.fresnel == FresnelModel::Schlick; }},
  };
}

// Every key, in the order files are written.
const std::vector<Key>& keys() {
  static const std::vector<Key> k = [] {
    std::vector<Key> all;
    for (auto group : {microscope_keys, sample_keys, slot_render_optics_keys})
      for (Key& key : group()) all.push_back(std::move(key));
    return all;
  }();
  return k;
}

const Key* find_key(std::string_view path) {
  for (const Key& k : keys())
    if (path == k.path) return &k;
  return nullptr;
}

// The groups of dot paths: a value that is not an object there is a wrong type, not an unknown key.
bool is_group(std::string_view key) {
  return key == "objective" || key == "eyepiece" || key == "stage" || key == "condenser" || key == "sample" ||
         key == "render" || key == "optics";
}

// Keys that document a file rather than set anything.
bool is_annotation(std::string_view key) {
  return key == "source" || key == "description" || key == "comment" || key == "type" || key == "name";
}

void read_key(Scene& s, const Key& k, const json& v, const std::string& file, const std::string& raw) {
  try {
    k.read(s, v);
  } catch (const BadValue& b) {
    throw InputError(file, k.path, raw, b.why);
  } catch (const json::exception& e) {
    throw InputError(file, k.path, raw, e.what());
  }
}

}  // namespace

Scene scene_from_json(const json& j, const std::string& file, std::vector<std::string>* warnings) {
  if (!j.is_object()) throw InputError(file, "", "", "a scene file must hold a JSON object");
  // A student's exercise file (core/exercise/exercise_files.h) opens as its specimen.
  if (j.contains("type") && j["type"] == "pmexercise") {
    if (!j.contains("scene") || !j["scene"].is_object())
      throw InputError(file, "scene", "", "an exercise file holds its specimen's scene as an object");
    try {
      return scene_from_json(j["scene"], file, warnings);
    } catch (const InputError& e) {
      throw e.under("scene");
    }
  }
  if (j.contains("type") && !(j["type"].is_string() && j["type"] == "microscope"))
    throw InputError(file, "type", shown(j["type"]), "this reader takes microscope scenes");
  Scene s;
  bool bertrand_given = false;
  std::map<std::string, std::string> raw;  // key → its value as written, for messages
  // Flatten nested objects into dot paths; sample.crystal is a value, not a group.
  std::function<void(const json&, const std::string&)> walk = [&](const json& obj,
                                                                  const std::string& prefix) {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      const std::string path = prefix.empty() ? it.key() : prefix + "." + it.key();
      if (const Key* k = find_key(path)) {
        if (path == "bertrand") bertrand_given = true;
        raw[path] = shown(it.value());
        read_key(s, *k, it.value(), file, raw[path]);
      } else if (it.value().is_object()) {
        walk(it.value(), path);
      } else if (is_group(path)) {
        throw InputError(file, path, shown(it.value()), "expected an object");
      } else if (!(prefix.empty() && is_annotation(path))) {
        JsonReader(j, file, "", warnings).warn("unknown key '" + path + "' ignored");
      }
    }
  };
  walk(j, "");
  // mode = cono alone implies the Bertrand lens in (the usual way to look at a figure).
  if (!bertrand_given) s.bertrand_in = s.mode == ViewMode::Cono;
  // sample.crystal replaces sample.mineral whatever their order in the file.
  if (j.contains("sample") && j["sample"].is_object() && j["sample"].contains("crystal") &&
      !j["sample"]["crystal"].is_null())
    read_key(s, *find_key("sample.crystal"), j["sample"]["crystal"], file, shown(j["sample"]["crystal"]));
  try {
    validate_scene(s, file);
  } catch (const InputError& e) {
    const auto it = raw.find(e.key);
    if (it == raw.end()) throw;
    throw e.with_value(it->second);  // the value as the file wrote it
  }
  return s;
}

std::string read_scene_text(const std::string& path) { return read_text_file(path, "scene file"); }

Scene load_scene_file(const std::string& path, std::vector<std::string>* warnings) {
  return scene_from_json(read_json_file(path, "scene file"), path, warnings);
}

json scene_to_json(const Scene& scene) {
  json j = json::object();
  j["type"] = "microscope";
  for (const Key& k : keys()) {
    const json v = k.write(scene);
    if (v.is_null()) continue;
    // Appended rather than "/" + path: GCC 12 warns (-Wrestrict, a known false positive) on the
    // inlined operator+ of a literal and a string.
    std::string pointer = "/";
    pointer += k.path;
    std::replace(pointer.begin(), pointer.end(), '.', '/');
    j[json::json_pointer(pointer)] = v;
  }
  return j;
}

void save_scene_file(const Scene& scene, const std::string& path) {
  write_text_atomically(path, scene_to_json(scene).dump(2) + "\n");
}

namespace {

// Reads one --set into `s` (type and value checks of that key only); the scene as a whole is
// checked once all settings apply, since some are valid only together (x_axis and z_axis).
void read_setting(Scene& s, std::string_view key, std::string_view value) {
  const Key* k = find_key(key);
  if (!k) throw InputError("", std::string(key), std::string(value), "unknown scene key");
  json v = json::parse(value.begin(), value.end(), nullptr, false);
  if (v.is_discarded()) v = std::string(value);
  read_key(s, *k, v, "", std::string(value));
  // Switching the view mode moves condenser top lens and Bertrand lens together, as the UI's
  // one-click switch does; bertrand can then be flipped on its own.
  if (key == "mode") s.bertrand_in = s.mode == ViewMode::Cono;
}

std::pair<std::string_view, std::string_view> split_assignment(std::string_view assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw InputError("", std::string(assignment), "", "expected key=value");
  return {assignment.substr(0, eq), assignment.substr(eq + 1)};
}

// Applies (key, value) pairs in order to a copy, validates it once, and only then replaces
// `scene`: a refused setting leaves the scene as it was.
void apply_pairs(Scene& scene, const std::vector<std::pair<std::string_view, std::string_view>>& kv) {
  Scene s = scene;
  std::map<std::string, std::string, std::less<>> typed;  // key → its value as typed
  const char* pixel_key = nullptr;
  for (const auto& [key, value] : kv) {
    read_setting(s, key, value);
    typed[std::string(key)] = std::string(value);
    if (key == "render.width") pixel_key = "render.width";
    if (key == "render.height") pixel_key = "render.height";
  }
  try {
    // Too many pixels is the fault of the side set last, not necessarily of render.height.
    if (pixel_key) check_pixel_count(s, "", pixel_key);
    validate_scene(s, "");
  } catch (const InputError& e) {
    const auto it = typed.find(e.key);
    if (it == typed.end()) throw;
    throw e.with_value(it->second);  // as typed: 1000000, not 1e+06
  }
  scene = s;
}

}  // namespace

void apply_setting(Scene& scene, std::string_view key, std::string_view value) {
  apply_pairs(scene, {{key, value}});
}

void apply_setting(Scene& scene, std::string_view assignment) {
  apply_pairs(scene, {split_assignment(assignment)});
}

void apply_settings(Scene& scene, const std::vector<std::string>& assignments) {
  std::vector<std::pair<std::string_view, std::string_view>> kv;
  for (const std::string& a : assignments) kv.push_back(split_assignment(a));
  apply_pairs(scene, kv);
}

void validate_scene(const Scene& s, const std::string& file) { check_scene(s, file); }

}  // namespace pmsim
