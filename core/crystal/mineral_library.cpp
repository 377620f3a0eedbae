// The mineral library: assets/minerals/*.json parsed into Crystals, loaded once, looked up by
// case-insensitive name, alias (assets/minerals/aliases.json) or composition ("plagioclase:An35",
// the series of the file interpolated; the plain name keeps the file's own "indices").
//
// File format (every number's origin is named by the "source" keys):
//   {"name": "quartz", "symmetry": "uniaxial" | "biaxial" | "isotropic", "source": "...",
//    "indices": {"no": N, "ne": N} | {"nalpha": N, "nbeta": N, "ngamma": N} | {"n": N},
//        where N is a number (constant) or {"model": "ghosh1999", "A","B","C","D","E"}
//        or {"model": "cauchy", "A","B","C"} (λ in µm),
//    "absorption": {"source": "...", "reference_thickness_um": 30, "wavelength_nm": [...],
//        "transmittance": {"o": [...], "e": [...]} or {"alpha": [...], "beta": [...], "gamma": [...]}}
//        or {"source": "...", "wavelength_nm": [...], "extinction_coefficient_k": {axes as above}}
//        (the imaginary part of the complex index, μ = 4πk/λ: opaque minerals),
//    "rotatory_power": {"source": "...", "A_deg_um2_per_mm": A, "lambda0_um": l0,
//        "handedness": "right" | "left"},
//    "optic_angle_2vz_deg": literature 2Vz (biaxial; checked by the tests, not used),
//    "amorphous": true — a glass, not a crystal: isotropic, with no crystallography keys,
//    "series": a solid solution's indices against composition (core/crystal/mineral_series.h),
//    crystallography keys: see core/crystal/mineral_crystallography.h}
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>

#include <nlohmann/json.hpp>

#include "core/base/units.h"
#include "core/crystal/crystal.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/crystal/mineral_series.h"
#include "core/base/json_reader.h"
#include "core/base/asset_locator.h"
#include "core/base/asset_names.h"
#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/base/text.h"

namespace pmsim {
namespace {

using nlohmann::json;

struct Reader {
  const std::string& file;
  [[noreturn]] void fail(const std::string& key, const json& v, const std::string& why) const {
    throw InputError(file, key, v.is_null() ? std::string() : shown(v), why);
  }
  const json& need(const json& obj, const std::string& key, const std::string& path) const {
    if (!obj.is_object() || !obj.contains(key)) fail(path, json(), "missing key");
    return obj.at(key);
  }
  double number(const json& v, const std::string& path) const {
    try {
      return number_value(v);
    } catch (const BadValue& b) {
      fail(path, v, b.why);
    }
  }
  // Every nm of the visible range: a pole of a dispersion formula (C or E near λ²) is a narrow
  // feature that three probe wavelengths miss, and the renderer samples any λ in 380–780 nm.
  double index_at(const IndexDispersion& d, const std::string& path, const json& v) const {
    for (double wl = 380.0; wl <= 780.0; wl += 1.0) {
      const double n = d.n(wl);
      try {
        check_refractive_index(n);
      } catch (const BadValue& b) {
        fail(path, v, b.why + " (n = " + number_text(n) + " at " + number_text(wl) + " nm)");
      }
    }
    return d.n(589.3);
  }
  // Typos must not pass silently: a misspelt optional key would drop its data.
  void only_keys(const json& obj, const std::string& prefix, std::initializer_list<const char*> known) const {
    if (!obj.is_object()) return;
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      bool ok = false;
      for (const char* k : known) ok |= it.key() == k;
      if (!ok) fail(prefix + it.key(), it.value(), "unknown key");
    }
  }
  IndexDispersion dispersion(const json& v, const std::string& path) const {
    IndexDispersion d;
    if (v.is_number()) {
      d.A = number(v, path);
    } else if (v.is_object()) {
      only_keys(v, path + ".", {"model", "A", "B", "C", "D", "E", "n", "source"});
      const json& m = need(v, "model", path + ".model");
      if (!m.is_string()) fail(path + ".model", m, "expected a string");
      const std::string model = m.get<std::string>();
      if (model == "ghosh1999") {
        d.model = IndexDispersion::Model::Ghosh1999;
        d.A = number(need(v, "A", path + ".A"), path + ".A");
        d.B = number(need(v, "B", path + ".B"), path + ".B");
        d.C = number(need(v, "C", path + ".C"), path + ".C");
        d.D = number(need(v, "D", path + ".D"), path + ".D");
        d.E = number(need(v, "E", path + ".E"), path + ".E");
      } else if (model == "cauchy") {
        d.model = IndexDispersion::Model::Cauchy;
        d.A = number(need(v, "A", path + ".A"), path + ".A");
        d.B = v.contains("B") ? number(v["B"], path + ".B") : 0.0;
        d.C = v.contains("C") ? number(v["C"], path + ".C") : 0.0;
      } else if (model == "constant") {
        d.A = number(need(v, "n", path + ".n"), path + ".n");
      } else {
        fail(path + ".model", m, "unknown dispersion model (constant, ghosh1999, cauchy)");
      }
    } else {
      fail(path, v, "expected a number or a dispersion object");
    }
    index_at(d, path, v);
    return d;
  }
  std::vector<double> numbers(const json& v, const std::string& path) const {
    if (!v.is_array() || v.empty()) fail(path, v, "expected a non-empty array of numbers");
    std::vector<double> r;
    for (size_t i = 0; i < v.size(); ++i) r.push_back(number(v[i], path + "[" + std::to_string(i) + "]"));
    return r;
  }
};

}  // namespace

namespace {
Crystal load_mineral(const std::string& path, std::optional<MineralCrystallography>* crystallography,
                     std::optional<MineralSeries>* series);
}  // namespace

Crystal load_mineral_file(const std::string& path) { return load_mineral(path, nullptr, nullptr); }

Crystal load_mineral_file(const std::string& path, std::optional<MineralCrystallography>* crystallography) {
  return load_mineral(path, crystallography, nullptr);
}

namespace {

// The "absorption" block as μ(λ) per µm along X, Y, Z. Two forms, each with "wavelength_nm":
// "transmittance" of a "reference_thickness_um" slab (T = e^(−μd), the form of the coloured
// silicates), or "extinction_coefficient_k", the imaginary part of the complex index n + ik as
// optical-constant tables give it (opaque oxides: Querry 1985), with μ = 4πk/λ (the intensity
// absorption coefficient; Born & Wolf §14.1, Bohren & Huffman 1983 §2.8).
std::array<AbsorptionTable, 3> read_absorption(const Reader& r, const json& ab, const std::string& sym,
                                               const std::vector<std::string>& axis_keys) {
  if (!ab.is_object()) r.fail("absorption", ab, "expected an object");
  r.only_keys(ab, "absorption.",
              {"source", "reference_thickness_um", "wavelength_nm", "transmittance", "extinction_coefficient_k"});
  const bool by_k = ab.contains("extinction_coefficient_k");
  if (by_k == ab.contains("transmittance"))
    r.fail("absorption", json(), "give either transmittance (with reference_thickness_um) or extinction_coefficient_k");
  double d_um = 0.0;
  if (!by_k) {
    d_um = r.number(r.need(ab, "reference_thickness_um", "absorption.reference_thickness_um"),
                    "absorption.reference_thickness_um");
    if (!(d_um > 0.0)) r.fail("absorption.reference_thickness_um", ab["reference_thickness_um"], "must be > 0");
  } else if (ab.contains("reference_thickness_um")) {
    r.fail("absorption.reference_thickness_um", ab["reference_thickness_um"],
           "not used with extinction_coefficient_k (k is a property of the material, not of a slab)");
  }
  const auto wl = r.numbers(r.need(ab, "wavelength_nm", "absorption.wavelength_nm"), "absorption.wavelength_nm");
  for (size_t i = 1; i < wl.size(); ++i)
    if (!(wl[i] > wl[i - 1])) r.fail("absorption.wavelength_nm", ab["wavelength_nm"], "must increase");
  for (double w : wl)
    if (!(w > 0.0)) r.fail("absorption.wavelength_nm", ab["wavelength_nm"], "wavelengths must be > 0");
  const std::string block = by_k ? "absorption.extinction_coefficient_k" : "absorption.transmittance";
  const json& tr = r.need(ab, by_k ? "extinction_coefficient_k" : "transmittance", block);
  if (sym == "uniaxial")
    r.only_keys(tr, block + ".", {"o", "e"});
  else if (sym == "biaxial")
    r.only_keys(tr, block + ".", {"alpha", "beta", "gamma"});
  else
    r.only_keys(tr, block + ".", {"n"});
  std::array<AbsorptionTable, 3> t;
  for (int k = 0; k < 3; ++k) {
    const std::string key = block + "." + axis_keys[k];
    const auto v = r.numbers(r.need(tr, axis_keys[k], key), key);
    if (v.size() != wl.size()) r.fail(key, tr[axis_keys[k]], "needs one value per wavelength");
    t[k].wavelength_nm = wl;
    for (size_t i = 0; i < v.size(); ++i) {
      if (by_k) {
        if (!(v[i] >= 0.0 && v[i] <= 10.0)) r.fail(key, tr[axis_keys[k]], "k must be in [0, 10]");
        t[k].mu_per_um.push_back(4.0 * kPi * v[i] / (wl[i] * 1e-3));  // μ = 4πk/λ, λ in µm
      } else {
        if (!(v[i] > 0.0 && v[i] <= 1.0)) r.fail(key, tr[axis_keys[k]], "transmittance must be in (0, 1]");
        t[k].mu_per_um.push_back(-std::log(v[i]) / d_um);  // Beer–Lambert: T = e^(−μd)
      }
    }
  }
  return t;
}

Crystal load_mineral(const std::string& path, std::optional<MineralCrystallography>* crystallography,
                     std::optional<MineralSeries>* series) {
  const json j = read_json_file(path, "mineral file");
  const Reader r{path};
  if (!j.is_object()) r.fail("", j, "expected a JSON object");
  r.only_keys(j, "",
              {"name", "symmetry", "source", "indices", "absorption", "rotatory_power", "optic_angle_2vz_deg",
               "amorphous", "pleochroism", "note", "description", "crystal_system", "unit_cell", "optical_orientation",
               "cleavage", "habit", "twins", "series"});
  const json& name_v = r.need(j, "name", "name");
  if (!name_v.is_string() || name_v.get<std::string>().empty()) r.fail("name", name_v, "expected a name");
  const json& src_v = r.need(j, "source", "source");
  if (!src_v.is_string() || src_v.get<std::string>().empty())
    r.fail("source", src_v, "every mineral file must cite the source of its numbers");
  const json& sym_v = r.need(j, "symmetry", "symmetry");
  const std::string sym = sym_v.is_string() ? sym_v.get<std::string>() : std::string();
  const json& idx = r.need(j, "indices", "indices");
  if (j.contains("amorphous")) {
    if (!j["amorphous"].is_boolean()) r.fail("amorphous", j["amorphous"], "expected true or false");
    if (j["amorphous"].get<bool>() && sym != "isotropic")
      r.fail("amorphous", j["amorphous"], "a glass is isotropic (\"symmetry\": \"isotropic\")");
    if (j["amorphous"].get<bool>() && (j.contains("crystal_system") || j.contains("unit_cell")))
      r.fail("amorphous", j["amorphous"], "a glass has no crystal system or unit cell");
  }

  Crystal c;
  std::vector<std::string> axis_keys;
  if (sym == "uniaxial") {
    r.only_keys(idx, "indices.", {"no", "ne"});
    const auto no = r.dispersion(r.need(idx, "no", "indices.no"), "indices.no");
    const auto ne = r.dispersion(r.need(idx, "ne", "indices.ne"), "indices.ne");
    c = Crystal::make(name_v.get<std::string>(), CrystalSymmetry::Uniaxial, no, no, ne,
                      src_v.get<std::string>());
    axis_keys = {"o", "o", "e"};
  } else if (sym == "biaxial") {
    r.only_keys(idx, "indices.", {"nalpha", "nbeta", "ngamma"});
    const auto a = r.dispersion(r.need(idx, "nalpha", "indices.nalpha"), "indices.nalpha");
    const auto b = r.dispersion(r.need(idx, "nbeta", "indices.nbeta"), "indices.nbeta");
    const auto g = r.dispersion(r.need(idx, "ngamma", "indices.ngamma"), "indices.ngamma");
    for (double wl = 380.0; wl <= 780.0; wl += 1.0) {
      try {
        check_biaxial_order(a.n(wl), b.n(wl), g.n(wl));
      } catch (const BadValue& e) {
        r.fail("indices", idx, e.why + " (at " + number_text(wl) + " nm)");
      }
    }
    c = Crystal::make(name_v.get<std::string>(), CrystalSymmetry::Biaxial, a, b, g, src_v.get<std::string>());
    axis_keys = {"alpha", "beta", "gamma"};
  } else if (sym == "isotropic") {
    r.only_keys(idx, "indices.", {"n"});
    const auto n = r.dispersion(r.need(idx, "n", "indices.n"), "indices.n");
    c = Crystal::make(name_v.get<std::string>(), CrystalSymmetry::Isotropic, n, n, n,
                      src_v.get<std::string>());
    axis_keys = {"n", "n", "n"};
  } else {
    r.fail("symmetry", sym_v, "expected uniaxial, biaxial or isotropic");
  }

  if (j.contains("absorption")) {
    const auto t = read_absorption(r, j["absorption"], sym, axis_keys);
    c.set_absorption(t[0], t[1], t[2]);
  }

  if (j.contains("rotatory_power")) {
    const json& rp = j["rotatory_power"];
    if (!rp.is_object()) r.fail("rotatory_power", rp, "expected an object");
    r.only_keys(rp, "rotatory_power.", {"source", "A_deg_um2_per_mm", "lambda0_um", "handedness"});
    const double a_deg = r.number(r.need(rp, "A_deg_um2_per_mm", "rotatory_power.A_deg_um2_per_mm"),
                                  "rotatory_power.A_deg_um2_per_mm");
    const double l0 =
        r.number(r.need(rp, "lambda0_um", "rotatory_power.lambda0_um"), "rotatory_power.lambda0_um");
    if (!(l0 >= 0.0 && l0 < 0.35))
      r.fail("rotatory_power.lambda0_um", rp["lambda0_um"], "must be in [0, 0.35)");
    const json& hand = r.need(rp, "handedness", "rotatory_power.handedness");
    double sign = 0.0;
    if (hand == "right")
      sign = 1.0;
    else if (hand == "left")
      sign = -1.0;
    else
      r.fail("rotatory_power.handedness", hand, "expected right or left");
    RotatoryDispersion rd;
    rd.A_rad_um = sign * a_deg * (kPi / 180.0) * 1e-3;  // °·µm²/mm → rad·µm²/µm
    rd.lambda0_um = l0;
    c.set_rotatory_power(rd);
  }
  // Read (and so checked) whether or not the caller keeps it: a bad block fails the load.
  const JsonReader root(j, path);
  auto cr = read_mineral_crystallography(root, c.symmetry());
  if (crystallography) *crystallography = std::move(cr);
  if (const auto se = root.optional_object("series")) {
    if (c.symmetry() != CrystalSymmetry::Biaxial) se->fail("", "a series tabulates nalpha, nbeta, ngamma: biaxial only");
    MineralSeries s = read_mineral_series(*se);
    if (series) *series = std::move(s);
  }
  return c;
}

std::filesystem::path mineral_dir() { return std::filesystem::path(asset_dir()) / "minerals"; }

// The alias table is data, not a mineral: it lives beside the mineral files under this name.
constexpr const char* kAliasFile = "aliases.json";

struct Library {
  std::map<std::string, Crystal> by_name;  // lower-case name → crystal (node-stable references)
  std::map<std::string, MineralCrystallography> crystallography;  // minerals whose file has it
  std::map<std::string, MineralSeries> series;                    // solid solutions
  std::map<std::string, std::string> aliases;                     // lower-case alias → target
};

// Reads assets/minerals/aliases.json: {"source": "...", "groups": [{"target": "enstatite",
// "aliases": ["opx", ...], "source": "why these names mean this mineral"}, ...]}. Targets are
// checked once the whole library is loaded (they may be compositions such as "olivine:Fo100").
void read_aliases(const std::string& path, Library& l) {
  const nlohmann::json j = read_json_file(path, "mineral alias file");
  const JsonReader r(j, path);
  r.refuse_unknown_keys({"source", "groups", "note"});
  if (r.require<std::string>("source").empty()) r.fail("source", "the alias file cites its sources");
  for (const JsonReader& g : r.objects("groups", 1)) {
    g.refuse_unknown_keys({"target", "aliases", "source"});
    const std::string target = lower_case(g.require<std::string>("target"));
    if (g.require<std::string>("source").empty()) g.fail("source", "every alias group says why");
    const nlohmann::json& names = *g.find("aliases");
    if (!names.is_array() || names.empty()) g.fail("aliases", "expected a non-empty array of names");
    for (size_t i = 0; i < names.size(); ++i) {
      const std::string key = "aliases[" + std::to_string(i) + "]";
      const std::string a = lower_case(g.checked(key, names[i], [](const nlohmann::json& v) {
        return string_value(v);
      }));
      if (a.empty() || a.find(':') != std::string::npos) g.fail(key, names[i], "an alias is a plain name");
      if (l.by_name.count(a)) g.fail(key, names[i], "is the name of a mineral file, not an alias");
      if (!l.aliases.emplace(a, target).second) g.fail(key, names[i], "is an alias twice");
    }
  }
}

std::string canonical_in(const Library& l, std::string_view name);

const Library& library() {
  static const Library lib = [] {
    Library l;
    const auto dir = mineral_dir();
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec))
      throw InputError(dir.string(), "", "", "mineral directory not found (set PMSIM_ASSETS)");
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".json" && e.path().filename() != kAliasFile) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    AssetNames defined("mineral");
    for (const auto& f : files) {
      std::optional<MineralCrystallography> cr;
      std::optional<MineralSeries> se;
      Crystal c = load_mineral(f.string(), &cr, &se);
      defined.add(c.name(), f.string());
      const std::string key = lower_case(c.name());
      if (key.find(':') != std::string::npos)
        throw InputError(f.string(), "name", c.name(), "':' separates a mineral from its composition");
      l.by_name.emplace(key, std::move(c));
      if (cr) l.crystallography.emplace(key, std::move(*cr));
      if (se) l.series.emplace(key, std::move(*se));
    }
    const auto alias_file = dir / kAliasFile;
    if (std::filesystem::is_regular_file(alias_file, ec)) {
      read_aliases(alias_file.string(), l);
      for (auto& [a, target] : l.aliases) {
        try {
          target = canonical_in(l, target);  // stored in its one spelling ("olivine:Fo100")
        } catch (const InputError& e) {
          throw InputError(alias_file.string(), "groups", target, "alias '" + a + "': " + e.reason);
        }
      }
    }
    return l;
  }();
  return lib;
}

// "actinolite, aegirine, …; aliases: cpx = augite, garnet = almandine, …": every name taken.
std::string known_text(const Library& l) {
  std::string known;
  for (const auto& [k, v] : l.by_name) known += (known.empty() ? "" : ", ") + k;
  std::string aliases;
  for (const auto& [a, target] : l.aliases) aliases += (aliases.empty() ? "" : ", ") + a + " = " + target;
  return aliases.empty() ? known : known + "; aliases: " + aliases;
}

[[noreturn]] void unknown_mineral(const Library& l, std::string_view name) {
  throw InputError("", "", std::string(name), "unknown mineral (known: " + known_text(l) + ")");
}

std::string trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

// "An35", "an 35.5", "Fa10" → the component's mol % (Fa10 → Fo90), or InputError naming `name`.
double composition_of(const MineralSeries& s, const std::string& base, std::string_view text,
                      std::string_view name) {
  const std::string t = lower_case(trimmed(text));
  size_t i = 0;
  while (i < t.size() && std::isalpha(static_cast<unsigned char>(t[i]))) ++i;
  const std::string comp = t.substr(0, i);
  const std::string number = trimmed(std::string_view(t).substr(i));
  const bool complement = !s.complement.empty() && comp == lower_case(s.complement);
  const std::string example = base + ":" + s.component + "35";
  if (comp != lower_case(s.component) && !complement)
    throw InputError("", "", std::string(name),
                     std::string(std::string_view("aeiou").find(base.front()) != std::string_view::npos ? "an " : "a ") +
                         base + " composition is written " + example + " (mol % " + s.component +
                         (s.complement.empty() ? "" : ", or " + s.complement) + ")");
  // Plain decimal digits only: strtod would also take "1e1", "inf" and hexadecimal.
  bool ok = !number.empty() && number.front() != '.' && number.back() != '.';
  int dots = 0;
  for (char c : number) {
    dots += c == '.';
    ok &= (std::isdigit(static_cast<unsigned char>(c)) || c == '.');
  }
  if (!ok || dots > 1)
    throw InputError("", "", std::string(name), "the composition needs a number of mol %, e.g. " + example);
  const double x = std::strtod(number.c_str(), nullptr);
  if (!(x >= 0.0 && x <= 100.0))
    throw InputError("", "", std::string(name),
                     "composition " + (complement ? s.complement : s.component) + number +
                         " is outside 0..100 mol %");
  // Rounded to 1e-6 mol % so that Fa12.3 names the same crystal as Fo87.7 (100 − 12.3 is not
  // exact in binary).
  return std::round((complement ? 100.0 - x : x) * 1e6) / 1e6;
}

std::string canonical_in(const Library& l, std::string_view name) {
  const std::string n = lower_case(trimmed(name));
  const size_t colon = n.find(':');
  std::string base = trimmed(std::string_view(n).substr(0, colon));
  std::string composition_text;
  if (const auto a = l.aliases.find(base); a != l.aliases.end()) {
    const std::string& target = a->second;
    const size_t tc = target.find(':');
    if (tc != std::string::npos) {
      // An alias that is itself a composition ("forsterite" → olivine:Fo100) takes none.
      if (colon != std::string::npos)
        throw InputError("", "", std::string(name),
                         "'" + base + "' already names a composition (" + target + ")");
      base = target.substr(0, tc);
      composition_text = target.substr(tc + 1);
    } else {
      base = target;
    }
  }
  if (colon != std::string::npos) composition_text = n.substr(colon + 1);
  if (!l.by_name.count(base)) unknown_mineral(l, name);
  if (colon == std::string::npos && composition_text.empty()) return base;
  const auto s = l.series.find(base);
  if (s == l.series.end())
    throw InputError("", "", std::string(name), "'" + base + "' is not a solid-solution series (" +
                                                     [&] {
                                                       std::string all;
                                                       for (const auto& [k, v] : l.series)
                                                         all += (all.empty() ? "" : ", ") + k;
                                                       return all;
                                                     }() +
                                                     " are)");
  const double x = composition_of(s->second, base, composition_text, name);
  return base + ":" + s->second.component + number_text(x);
}

// Crystals of compositions, made on first use and kept for the process (references stay valid:
// std::map nodes do not move). Guarded: renders look minerals up from several threads.
struct CompositionCache {
  std::mutex mutex;
  std::map<std::string, Crystal> crystals;
};
CompositionCache& composition_cache() {
  static CompositionCache c;
  return c;
}

}  // namespace

std::string canonical_mineral_name(std::string_view name) { return canonical_in(library(), name); }

const Crystal& find_mineral(std::string_view name) {
  const Library& lib = library();
  const std::string key = canonical_in(lib, name);
  if (const auto it = lib.by_name.find(key); it != lib.by_name.end()) return it->second;
  CompositionCache& cache = composition_cache();
  const std::lock_guard<std::mutex> lock(cache.mutex);
  if (const auto it = cache.crystals.find(key); it != cache.crystals.end()) return it->second;
  const size_t colon = key.find(':');
  const std::string base = key.substr(0, colon);
  const MineralSeries& s = lib.series.at(base);
  const double x = std::strtod(key.c_str() + colon + 1 + s.component.size(), nullptr);
  const glm::dvec3 n = s.indices_at(x);
  IndexDispersion d[3];
  for (int k = 0; k < 3; ++k) d[k].A = n[k];
  Crystal c = Crystal::make(key, CrystalSymmetry::Biaxial, d[0], d[1], d[2],
                            s.source + " Indices interpolated linearly in composition at " + key + ".");
  return cache.crystals.emplace(key, std::move(c)).first->second;
}

const MineralCrystallography* find_mineral_crystallography(std::string_view name) {
  const Library& lib = library();
  const std::string key = canonical_in(lib, name);  // an unknown name throws as find_mineral does
  // A composition shares its series' lattice and orientation data (the file's blocks).
  const auto it = lib.crystallography.find(key.substr(0, key.find(':')));
  return it == lib.crystallography.end() ? nullptr : &it->second;
}

const MineralSeries* find_mineral_series(std::string_view name) {
  const Library& lib = library();
  const std::string key = canonical_in(lib, name);
  const auto it = lib.series.find(key.substr(0, key.find(':')));
  return it == lib.series.end() ? nullptr : &it->second;
}

std::vector<std::string> mineral_names() {
  std::vector<std::string> names;
  for (const auto& [k, v] : library().by_name) names.push_back(k);
  return names;
}

std::vector<std::pair<std::string, std::string>> mineral_aliases() {
  const auto& a = library().aliases;
  return {a.begin(), a.end()};
}

std::string known_minerals_text() { return known_text(library()); }

}  // namespace pmsim
