#include "core/ebsd/phase_names.h"

#include <algorithm>
#include <optional>
#include <string_view>
#include <vector>

#include "core/base/asset_locator.h"
#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/base/text.h"
#include "core/crystal/crystal.h"

namespace pmsim {

namespace {

struct NameTable {
  std::map<std::string, std::string> mineral_of;  // lower-case alias → mineral
};

const NameTable& name_table() {
  static const NameTable table = [] {
    const std::string path = asset_dir() + "/ebsd/phase_names.json";
    const nlohmann::json j = read_json_file(path, "EBSD phase-name table");
    NameTable t;
    if (!j.is_object() || !j.contains("names") || !j["names"].is_object())
      throw InputError(path, "names", "", "expected an object of phase names");
    for (const auto& [name, entry] : j["names"].items()) {
      if (!entry.is_object() || !entry.contains("mineral") || !entry["mineral"].is_string() ||
          !entry.contains("why") || !entry["why"].is_string())
        throw InputError(path, "names." + name, shown(entry), "expected {\"mineral\": …, \"why\": …}");
      t.mineral_of[lower_case(name)] = entry["mineral"].get<std::string>();
    }
    return t;
  }();
  return table;
}

// Lower case, surrounding blanks removed, '_' read as ' ', runs of spaces as one.
std::string normalized(std::string_view s) {
  std::string out;
  for (char c : lower_case(s)) {
    if (c == '_' || c == '\t') c = ' ';
    if (c == ' ' && (out.empty() || out.back() == ' ')) continue;
    out += c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string without_qualifiers(std::string s) {
  static const char* const kSuffixes[] = {"-new",  " new",  "-low",   " low",
                                          "-high", " high", " alpha", "-alpha"};
  static const char* const kPrefixes[] = {"low ", "high ", "alpha-", "alpha "};
  for (bool changed = true; changed;) {
    changed = false;
    for (const char* suf : kSuffixes) {
      const std::string_view x(suf);
      if (s.size() > x.size() && s.compare(s.size() - x.size(), x.size(), x) == 0) {
        s.erase(s.size() - x.size());
        changed = true;
      }
    }
    for (const char* pre : kPrefixes) {
      const std::string_view x(pre);
      if (s.size() > x.size() && s.compare(0, x.size(), x) == 0) {
        s.erase(0, x.size());
        changed = true;
      }
    }
  }
  return s;
}

bool is_library_mineral(const std::string& lower_name) {
  static const std::vector<std::string> names = mineral_names();
  return std::binary_search(names.begin(), names.end(), lower_name);
}

// The mineral part of "olivine:Fo90" (lower case).
std::string base_name(const std::string& target) { return normalized(target.substr(0, target.find(':'))); }

// Steps 2 and 3 for `name`; nullopt when nothing matches. A table entry whose mineral the library
// lacks is reported (it names a mineral that should exist).
std::optional<std::string> resolve_automatically(std::string_view name, const std::string& file,
                                                 const std::string& shown_name) {
  const std::string n = normalized(name);
  for (const std::string& candidate : {n, without_qualifiers(n)}) {
    if (candidate == "isotropic" || candidate == "none") return candidate;
    const auto& table = name_table().mineral_of;
    if (const auto it = table.find(candidate); it != table.end()) {
      if (!is_library_mineral(base_name(it->second)))
        throw InputError(file, "sample.phases", shown_name,
                         "the phase-name table (assets/ebsd/phase_names.json) maps '" + candidate + "' to '" +
                             it->second +
                             "', which the mineral library lacks; map the phase explicitly with "
                             "sample.phases");
      return it->second;
    }
    if (is_library_mineral(candidate)) return candidate;
  }
  return std::nullopt;
}

std::string how_to_map(const std::string& name) {
  return "map it in the scene with \"sample\": {\"phases\": {\"" + name +
         "\": \"<mineral>\"}} (on the command line: --set 'sample.phases={\"" + name +
         "\": \"<mineral>\"}'), the mineral a library name (quartz, olivine, …), a composition "
         "(olivine:Fo90), \"isotropic\" or \"none\"";
}

}  // namespace

std::string map_phase_name(const std::string& name_in_file,
                           const std::map<std::string, std::string>& explicit_map, const std::string& file) {
  auto it = explicit_map.find(name_in_file);
  if (it == explicit_map.end()) {
    const std::string want = normalized(name_in_file);
    it = std::find_if(explicit_map.begin(), explicit_map.end(),
                      [&](const auto& kv) { return normalized(kv.first) == want; });
  }
  if (it != explicit_map.end()) {
    const std::string value(it->second);
    const std::string key = "sample.phases." + it->first;
    if (value.find(':') != std::string::npos) {
      if (!is_library_mineral(base_name(value)))
        throw InputError(file, key, value, "'" + base_name(value) + "' is not a library mineral");
      return value;
    }
    if (auto r = resolve_automatically(value, file, value)) return *r;
    throw InputError(file, key, value,
                     "maps the map's phase '" + name_in_file +
                         "' to no library mineral; use a library name (quartz, olivine, …), a composition "
                         "(olivine:Fo90), \"isotropic\" or \"none\"");
  }
  if (auto r = resolve_automatically(name_in_file, file, name_in_file)) return *r;
  throw InputError(
      file, "sample.phases", name_in_file,
      "the map's phase '" + name_in_file + "' matches no library mineral; " + how_to_map(name_in_file));
}

}  // namespace pmsim
