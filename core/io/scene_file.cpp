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
#include "core/io/input_error.h"
#include "core/microscope/scene_check.h"

namespace pmsim {

using nlohmann::json;

namespace {

// Thrown inside a key's reader with only the reason; the caller adds file, key and value.
struct BadValue {
  std::string why;
};

double as_number(const json& v) {
  if (!v.is_number()) throw BadValue{"expected a number"};
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw BadValue{"not a finite number"};
  return d;
}
int as_int(const json& v) {
  const double d = as_number(v);
  if (d != std::floor(d) || std::fabs(d) > 1e9) throw BadValue{"expected an integer"};
  return static_cast<int>(d);
}
bool as_bool(const json& v) {
  if (!v.is_boolean()) throw BadValue{"expected true or false"};
  return v.get<bool>();
}
// Well-formed UTF-8 (RFC 3629: no overlongs, no surrogates, ≤ U+10FFFF): anything else cannot be
// saved back as JSON (nlohmann's dump throws on it).
bool valid_utf8(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    int n;
    unsigned cp;
    if (c < 0x80) {
      ++i;
      continue;
    } else if ((c & 0xE0) == 0xC0) {
      n = 1, cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      n = 2, cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      n = 3, cp = c & 0x07;
    } else {
      return false;
    }
    if (i + n >= s.size()) return false;  // truncated sequence
    for (int k = 1; k <= n; ++k) {
      const unsigned char d = static_cast<unsigned char>(s[i + k]);
      if ((d & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (d & 0x3F);
    }
    static constexpr unsigned kMin[4] = {0, 0x80, 0x800, 0x10000};
    if (cp < kMin[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += n + 1;
  }
  return true;
}

std::string as_string(const json& v) {
  if (!v.is_string()) throw BadValue{"expected a string"};
  std::string s = v.get<std::string>();
  if (!valid_utf8(s)) throw BadValue{"not valid UTF-8 text"};
  return s;
}
std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}
bool as_in_out(const json& v) {  // "in"|"out" (booleans accepted too)
  if (v.is_boolean()) return v.get<bool>();
  const std::string s = lower(as_string(v));
  if (s == "in") return true;
  if (s == "out") return false;
  throw BadValue{"expected \"in\" or \"out\""};
}
std::array<double, 3> as_vec3(const json& v) {
  if (!v.is_array() || v.size() != 3) throw BadValue{"expected a vector [x, y, z]"};
  std::array<double, 3> a{};
  for (int i = 0; i < 3; ++i) a[i] = as_number(v[i]);
  const double len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  if (!(len > 1e-12)) throw BadValue{"a direction cannot be the zero vector"};
  // Vectors are normalised (issue convention). One that is already unit to rounding is kept as
  // written: dividing by a length of 1 ± 1 ulp would change its last bit on every save → load.
  if (std::abs(len - 1.0) > 4.0 * std::numeric_limits<double>::epsilon())
    for (double& c : a) c /= len;
  return a;
}
template <class E>
E as_enum(const json& v, std::initializer_list<std::pair<const char*, E>> names) {
  const std::string s = lower(as_string(v));
  std::string all;
  for (const auto& [n, e] : names) {
    if (s == n) return e;
    all += (all.empty() ? "" : "|") + std::string(n);
  }
  throw BadValue{"expected one of " + all};
}
template <class E>
std::string enum_name(E e, std::initializer_list<std::pair<const char*, E>> names) {
  for (const auto& [n, x] : names)
    if (x == e) return n;
  return "?";
}

const std::initializer_list<std::pair<const char*, ViewMode>> kModes = {{"ortho", ViewMode::Ortho},
                                                                        {"cono", ViewMode::Cono}};
const std::initializer_list<std::pair<const char*, SampleType>> kSampleTypes = {
    {"plate", SampleType::Plate}, {"wedge", SampleType::Wedge}, {"section", SampleType::Section}};
const std::initializer_list<std::pair<const char*, Compensator>> kCompensators = {
    {"none", Compensator::None},
    {"gypsum", Compensator::Gypsum},
    {"mica", Compensator::Mica},
    {"quartz_wedge", Compensator::QuartzWedge}};
const std::initializer_list<std::pair<const char*, LensModel>> kLensModels = {
    {"auto", LensModel::Auto}, {"ideal", LensModel::Ideal}, {"physical", LensModel::Physical}};
const std::initializer_list<std::pair<const char*, RenderStrategy>> kRenderStrategies = {
    {"auto", RenderStrategy::Auto}, {"modal", RenderStrategy::Modal}, {"exact", RenderStrategy::Exact}};

CrystalIndices as_crystal(const json& v) {
  if (!v.is_object()) throw BadValue{"expected {\"no\":..,\"ne\":..} or {\"nalpha\":..,\"nbeta\":..,\"ngamma\":..}"};
  CrystalIndices c;
  auto index = [&](const char* k) {
    const double n = as_number(v.at(k));
    if (!(n > 1.0)) throw BadValue{std::string(k) + " must be > 1"};
    if (n > 5.0) throw BadValue{std::string(k) + " must be ≤ 5"};
    return n;
  };
  if (v.contains("no") && v.contains("ne") && v.size() == 2) {
    c.uniaxial = true;
    c.no = index("no");
    c.ne = index("ne");
  } else if (v.contains("nalpha") && v.contains("nbeta") && v.contains("ngamma") && v.size() == 3) {
    c.uniaxial = false;
    c.nalpha = index("nalpha");
    c.nbeta = index("nbeta");
    c.ngamma = index("ngamma");
    if (!(c.nalpha <= c.nbeta && c.nbeta <= c.ngamma))
      throw BadValue{"biaxial indices must satisfy nalpha ≤ nbeta ≤ ngamma"};
  } else {
    throw BadValue{"expected exactly {\"no\",\"ne\"} or {\"nalpha\",\"nbeta\",\"ngamma\"}"};
  }
  return c;
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

const std::vector<Key>& keys() {
  static const std::vector<Key> k = {
      {"mode",
       [](Scene& s, const json& v) { s.mode = as_enum(v, kModes); },
       [](const Scene& s) -> json { return enum_name(s.mode, kModes); }},
      {"polarizer_deg", [](Scene& s, const json& v) { s.polarizer_deg = as_number(v); },
       [](const Scene& s) -> json { return s.polarizer_deg; }},
      {"analyzer_deg", [](Scene& s, const json& v) { s.analyzer_deg = as_number(v); },
       [](const Scene& s) -> json { return s.analyzer_deg; }},
      {"analyzer", [](Scene& s, const json& v) { s.analyzer_in = as_in_out(v); },
       [](const Scene& s) -> json { return s.analyzer_in ? "in" : "out"; }},
      {"stage_deg", [](Scene& s, const json& v) { s.stage_deg = as_number(v); },
       [](const Scene& s) -> json { return s.stage_deg; }},
      {"bertrand", [](Scene& s, const json& v) { s.bertrand_in = as_in_out(v); },
       [](const Scene& s) -> json { return s.bertrand_in ? "in" : "out"; }},
      {"illuminant",
       [](Scene& s, const json& v) {
         if (!parse_illuminant(as_string(v), s.illuminant)) throw BadValue{"expected D65 or A"};
       },
       [](const Scene& s) -> json { return std::string(illuminant_name(s.illuminant)); }},
      {"objective.magnification",
       [](Scene& s, const json& v) { s.objective.magnification = as_number(v); },
       [](const Scene& s) -> json { return s.objective.magnification; }},
      {"objective.na", [](Scene& s, const json& v) { s.objective.na = as_number(v); },
       [](const Scene& s) -> json { return s.objective.na; }},
      {"condenser.na", [](Scene& s, const json& v) { s.condenser.na = as_number(v); },
       [](const Scene& s) -> json { return s.condenser.na; }},
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
         if (v.is_null() || (v.is_string() && lower(v.get<std::string>()) == "none"))
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
      {"sample.section", [](Scene& s, const json& v) { s.sample.section = as_string(v); },
       [](const Scene& s) -> json { return s.sample.section; }},
      {"sample.medium", [](Scene& s, const json& v) { s.sample.medium = as_string(v); },
       [](const Scene& s) -> json { return s.sample.medium; }},
      {"compensator", [](Scene& s, const json& v) { s.compensator = as_enum(v, kCompensators); },
       [](const Scene& s) -> json { return enum_name(s.compensator, kCompensators); }},
      {"compensator_position",
       [](Scene& s, const json& v) { s.compensator_position = as_number(v); },
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
      {"render.tolerance",
       [](Scene& s, const json& v) { s.render.tolerance_de2000 = as_number(v); },
       [](const Scene& s) -> json { return s.render.tolerance_de2000; }},
      {"render.strategy", [](Scene& s, const json& v) { s.render.strategy = as_enum(v, kRenderStrategies); },
       [](const Scene& s) -> json { return enum_name(s.render.strategy, kRenderStrategies); }},
      {"optics.lens_model",
       [](Scene& s, const json& v) { s.optics.lens_model = as_enum(v, kLensModels); },
       [](const Scene& s) -> json { return enum_name(s.optics.lens_model, kLensModels); }},
      {"optics.lens_depth", [](Scene& s, const json& v) { s.optics.lens_depth = as_int(v); },
       [](const Scene& s) -> json { return s.optics.lens_depth; }},
      {"optics.schlick", [](Scene& s, const json& v) { s.optics.schlick = as_bool(v); },
       [](const Scene& s) -> json { return s.optics.schlick; }},
  };
  return k;
}

const Key* find_key(std::string_view path) {
  for (const Key& k : keys())
    if (path == k.path) return &k;
  return nullptr;
}

// Keys that document a file rather than set anything.
bool is_annotation(std::string_view key) {
  return key == "source" || key == "description" || key == "comment" || key == "type" ||
         key == "name";
}

std::string shown(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

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
      } else if (!(prefix.empty() && is_annotation(path))) {
        if (warnings) warnings->push_back((file.empty() ? "" : file + ": ") + "unknown key '" + path + "' ignored");
      }
    }
  };
  walk(j, "");
  // mode = cono alone implies the Bertrand lens in (the usual way to look at a figure).
  if (!bertrand_given) s.bertrand_in = s.mode == ViewMode::Cono;
  // sample.crystal replaces sample.mineral whatever their order in the file.
  if (j.contains("sample") && j["sample"].is_object() && j["sample"].contains("crystal") &&
      !j["sample"]["crystal"].is_null())
    read_key(s, *find_key("sample.crystal"), j["sample"]["crystal"], file,
             shown(j["sample"]["crystal"]));
  try {
    validate_scene(s, file);
  } catch (const InputError& e) {
    const auto it = raw.find(e.key);
    if (it == raw.end()) throw;
    throw e.with_value(it->second);  // the value as the file wrote it
  }
  return s;
}

std::string read_scene_text(const std::string& path) {
  // A folder opens as an ifstream on Linux and fails only while being read, from inside the
  // parser (std::ios_base::failure thrown through nlohmann's lexer left its heap corrupt): refuse
  // it here and parse from memory.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path, "", "", "cannot read: is a folder, not a scene file");
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path, "", "", "cannot open the scene file");
  std::ostringstream text;
  text << f.rdbuf();
  if (f.bad()) throw InputError(path, "", "", "cannot read the scene file");
  return text.str();
}

Scene load_scene_file(const std::string& path, std::vector<std::string>* warnings) {
  const std::string text = read_scene_text(path);
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // syntax errors, and numbers beyond double (1e400)
    throw InputError(path, "", "", std::string("not valid JSON: ") + e.what());
  }
  return scene_from_json(j, path, warnings);
}

json scene_to_json(const Scene& scene) {
  json j = json::object();
  j["type"] = "microscope";
  for (const Key& k : keys()) {
    const json v = k.write(scene);
    if (v.is_null()) continue;
    j[json::json_pointer("/" + [&] {
        std::string p = k.path;
        std::replace(p.begin(), p.end(), '.', '/');
        return p;
      }())] = v;
  }
  return j;
}

void save_scene_file(const Scene& scene, const std::string& path) {
  write_text_atomically(path, scene_to_json(scene).dump(2) + "\n");
}

void apply_setting(Scene& scene, std::string_view key, std::string_view value) {
  const Key* k = find_key(key);
  if (!k) throw InputError("", std::string(key), std::string(value), "unknown scene key");
  json v = json::parse(value.begin(), value.end(), nullptr, false);
  if (v.is_discarded()) v = std::string(value);
  Scene s = scene;
  read_key(s, *k, v, "", std::string(value));
  // Switching the view mode moves condenser top lens and Bertrand lens together, as the UI's
  // one-click switch does; bertrand can then be flipped on its own.
  if (key == "mode") s.bertrand_in = s.mode == ViewMode::Cono;
  try {
    // Too many pixels is the fault of the side just set, not necessarily of render.height.
    if (key == "render.width" || key == "render.height")
      check_pixel_count(s, "", key == "render.width" ? "render.width" : "render.height");
    validate_scene(s, "");
  } catch (const InputError& e) {
    if (e.key != key) throw;
    throw e.with_value(std::string(value));  // as typed: 1000000, not 1e+06
  }
  scene = s;
}

void apply_setting(Scene& scene, std::string_view assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw InputError("", std::string(assignment), "", "expected key=value");
  apply_setting(scene, assignment.substr(0, eq), assignment.substr(eq + 1));
}

void validate_scene(const Scene& s, const std::string& file) { check_scene(s, file); }

}  // namespace pmsim
