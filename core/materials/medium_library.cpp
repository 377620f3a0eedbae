// The material library: JSON material files (assets/materials/*.json) → Medium.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "core/base/asset_locator.h"
#include "core/base/asset_names.h"
#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/base/text.h"
#include "core/materials/medium.h"

namespace pmsim {

namespace {

using nlohmann::json;

// Reads a material file's keys with the file and key named in every error; values convert with
// the shared rules of core/base/json_reader.h (the same messages as every other file type).
class Reader {
 public:
  Reader(const std::string& file, const json& root) : file_(file), root_(root) {}

  [[noreturn]] void fail(const std::string& key, const json& value, const std::string& why) const {
    throw InputError(file_, key, value.is_null() ? std::string() : shown(value), why);
  }

  const json& require(const std::string& key) const {
    if (!root_.contains(key)) fail(key, json(), "missing required key");
    return root_.at(key);
  }

  std::string string(const std::string& key) const {
    const json& v = require(key);
    if (!v.is_string() || v.get<std::string>().empty()) fail(key, v, "expected a non-empty string");
    return v.get<std::string>();
  }

  double number(const json& v, const std::string& key) const {
    try {
      return number_value(v);
    } catch (const BadValue& b) {
      fail(key, v, b.why);
    }
  }
  double number(const std::string& key) const { return number(require(key), key); }

  std::vector<double> numbers(const json& v, const std::string& key, std::size_t min_size,
                              std::size_t exact_size = 0) const {
    if (!v.is_array()) fail(key, v, "expected an array of numbers");
    if (exact_size != 0 && v.size() != exact_size) {
      fail(key, v, "expected exactly " + std::to_string(exact_size) + " numbers");
    }
    if (v.size() < min_size) fail(key, v, "expected at least " + std::to_string(min_size) + " numbers");
    std::vector<double> out;
    for (std::size_t i = 0; i < v.size(); ++i) {
      out.push_back(number(v[i], key + "[" + std::to_string(i) + "]"));
    }
    return out;
  }
  std::vector<double> numbers(const std::string& key, std::size_t min_size,
                              std::size_t exact_size = 0) const {
    return numbers(require(key), key, min_size, exact_size);
  }

 private:
  const std::string& file_;
  const json& root_;
};

// No transparent medium of the visible range has an index above 5 (diamond 2.42, rutile 2.9);
// larger values are typos (the same bound as the crystal files').
constexpr double kMaxIndex = 5.0;

// Keys a material file may hold; anything else is a typo and reported as such.
const std::set<std::string> kKnownKeys = {"name",
                                          "source",
                                          "model",
                                          "n",
                                          "B",
                                          "C_um2",
                                          "A",
                                          "B_nm2",
                                          "wavelength_range_nm",
                                          "attenuation_per_mm",
                                          "internal_transmittance",
                                          "catalogue",
                                          "note"};

}  // namespace

Medium load_medium_file(const std::string& path) {
  const json root = read_json_file(path, "material file");
  if (!root.is_object()) throw InputError(path, "", "", "expected a JSON object");
  const Reader r(path, root);
  for (const auto& [key, value] : root.items()) {
    if (!kKnownKeys.count(key)) r.fail(key, value, "unknown key");
  }

  const std::string name = r.string("name");
  r.string("source");  // every data file names where its numbers come from
  const std::string model = r.string("model");
  const bool gas = lower_case(name) == "air" || lower_case(name) == "vacuum";

  Medium m;
  std::vector<double> sellmeier_b, sellmeier_c;
  if (model == "constant") {
    const double n = r.number("n");
    if (gas ? n < 1.0 : n <= 1.0) r.fail("n", root["n"], gas ? "must be >= 1" : "must be > 1");
    if (n > kMaxIndex) r.fail("n", root["n"], "must be <= 5 (no transparent medium has more)");
    m = Medium::constant(name, n);
  } else if (model == "sellmeier3") {
    const std::vector<double> B = r.numbers("B", 3, 3);
    const std::vector<double> C = r.numbers("C_um2", 3, 3);
    for (int i = 0; i < 3; ++i) {
      if (C[i] < 0.0) r.fail("C_um2[" + std::to_string(i) + "]", root["C_um2"][i], "must be >= 0");
    }
    m = Medium::sellmeier(name, B.data(), C.data());
    sellmeier_c = C;
    sellmeier_b = B;
  } else if (model == "cauchy") {
    m = Medium::cauchy(name, r.number("A"), r.number("B_nm2"));
  } else {
    r.fail("model", root["model"], "expected \"constant\", \"sellmeier3\" or \"cauchy\"");
  }

  if (root.contains("wavelength_range_nm")) {
    const std::vector<double> range = r.numbers("wavelength_range_nm", 2, 2);
    if (!(range[0] > 0.0 && range[1] > range[0])) {
      r.fail("wavelength_range_nm", root["wavelength_range_nm"], "expected [min, max] with 0 < min < max");
    }
    // pmsim traces 380–780 nm (and quotes n_d at 587.56 nm): a medium must be defined there.
    if (!(range[0] <= 380.0 && range[1] >= 780.0)) {
      r.fail("wavelength_range_nm", root["wavelength_range_nm"], "must cover the visible range 380-780 nm");
    }
    m.set_wavelength_range(range[0], range[1]);
  } else if (model != "constant") {
    r.fail("wavelength_range_nm", json(), "missing required key (the formula's validity range)");
  }

  // A Sellmeier term B·λ²/(λ² − C) has a pole at λ = √C: inside the claimed range the index is
  // infinite there and imaginary just beyond, a feature too narrow for sampling to find.
  // Checked after the visible probes, which name the model for a pole where it matters most.
  auto check_poles = [&] {
    for (std::size_t i = 0; i < sellmeier_c.size(); ++i) {
      const double pole_nm = std::sqrt(sellmeier_c[i]) * 1e3;
      if (sellmeier_b[i] != 0.0 && pole_nm >= m.min_wavelength_nm() && pole_nm <= m.max_wavelength_nm()) {
        r.fail("C_um2[" + std::to_string(i) + "]", root["C_um2"][i],
               "puts a pole of the Sellmeier formula at " + std::to_string(pole_nm) +
                   " nm, inside wavelength_range_nm");
      }
    }
  };
  // The formula must give a finite index in (1, 5] wherever it claims to be valid (a wrong sign
  // shows up here); sampled each nm of the visible range, at the range ends and at 256
  // log-spaced wavelengths across the range.
  {
    std::vector<double> probe;
    for (double nm = 380.0; nm <= 780.0; nm += 1.0) {
      if (nm >= m.min_wavelength_nm() && nm <= m.max_wavelength_nm()) probe.push_back(nm);
    }
    const std::size_t visible_probes = probe.size();
    probe.push_back(m.min_wavelength_nm());
    if (std::isfinite(m.max_wavelength_nm())) probe.push_back(m.max_wavelength_nm());
    if (m.min_wavelength_nm() > 0.0 && std::isfinite(m.max_wavelength_nm())) {
      const double ratio = m.max_wavelength_nm() / m.min_wavelength_nm();
      for (int k = 1; k < 256; ++k) probe.push_back(m.min_wavelength_nm() * std::pow(ratio, k / 256.0));
    }
    for (std::size_t p = 0; p < probe.size(); ++p) {
      const double nm = probe[p];
      if (p == visible_probes) check_poles();
      if (nm <= 0.0 || nm < m.min_wavelength_nm() || nm > m.max_wavelength_nm()) continue;
      const double n = m.n(nm);
      if (!std::isfinite(n) || (gas ? n < 1.0 : n <= 1.0) || n > kMaxIndex) {
        r.fail("model", root["model"],
               "gives n = " + std::to_string(n) + " at " + std::to_string(nm) + " nm");
      }
    }
    check_poles();
  }

  if (root.contains("attenuation_per_mm") && root.contains("internal_transmittance")) {
    r.fail("attenuation_per_mm", root["attenuation_per_mm"],
           "give either attenuation_per_mm or internal_transmittance, not both");
  }
  if (root.contains("attenuation_per_mm")) {
    const double mu = r.number("attenuation_per_mm");
    if (mu < 0.0) r.fail("attenuation_per_mm", root["attenuation_per_mm"], "must be >= 0");
    m.set_attenuation_per_mm(mu);
  }
  if (root.contains("internal_transmittance")) {
    const json& t = root["internal_transmittance"];
    if (!t.is_object()) r.fail("internal_transmittance", t, "expected an object");
    const Reader tr(path, t);
    auto key = [](const std::string& k) { return "internal_transmittance." + k; };
    if (!t.contains("thickness_mm")) r.fail(key("thickness_mm"), json(), "missing required key");
    const double d = tr.number(t["thickness_mm"], key("thickness_mm"));
    if (d <= 0.0) r.fail(key("thickness_mm"), t["thickness_mm"], "must be > 0");
    if (!t.contains("wavelength_nm")) r.fail(key("wavelength_nm"), json(), "missing required key");
    if (!t.contains("tau_i")) r.fail(key("tau_i"), json(), "missing required key");
    const std::vector<double> wl = tr.numbers(t["wavelength_nm"], key("wavelength_nm"), 1);
    const std::vector<double> tau = tr.numbers(t["tau_i"], key("tau_i"), 1);
    if (tau.size() != wl.size()) r.fail(key("tau_i"), t["tau_i"], "needs one value per wavelength");
    std::vector<double> mu;
    for (std::size_t i = 0; i < wl.size(); ++i) {
      if (wl[i] <= 0.0 || (i > 0 && wl[i] <= wl[i - 1])) {
        r.fail(key("wavelength_nm[" + std::to_string(i) + "]"), t["wavelength_nm"][i],
               "wavelengths must be positive and strictly increasing");
      }
      if (!(tau[i] > 0.0 && tau[i] <= 1.0)) {
        r.fail(key("tau_i[" + std::to_string(i) + "]"), t["tau_i"][i], "must be in (0, 1]");
      }
      mu.push_back(-std::log(tau[i]) / d);  // Beer–Lambert: τ_i = e^(−μ·d)
    }
    m.set_attenuation_table(wl, mu);
  }

  // A stated catalogue n_d must be what the formula gives (catches mistyped coefficients); the
  // catalogue prints 5 decimals, so 1e-5 is its rounding plus the fit's residual.
  if (root.contains("catalogue")) {
    const json& c = root["catalogue"];
    if (!c.is_object()) r.fail("catalogue", c, "expected an object");
    if (c.contains("nd")) {
      const double nd = r.number(c["nd"], "catalogue.nd");
      if (!(587.5618 >= m.min_wavelength_nm() && 587.5618 <= m.max_wavelength_nm())) {
        r.fail("catalogue.nd", c["nd"], "the d line 587.5618 nm is outside wavelength_range_nm");
      }
      if (std::abs(m.nd() - nd) > 1e-5) {
        r.fail("catalogue.nd", c["nd"], "the dispersion formula gives n_d = " + std::to_string(m.nd()));
      }
    }
  }
  return m;
}

namespace {

struct Library {
  std::map<std::string, Medium> by_lower_name;
  std::vector<std::string> names;
};

Library load_library() {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(asset_dir()) / "materials";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw InputError(dir.string(), "", "", "material library folder not found (set PMSIM_ASSETS)");
  }
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  Library lib;
  AssetNames defined("medium");
  for (const auto& f : files) {
    Medium m = load_medium_file(f.string());
    const std::string key = lower_case(m.name());
    defined.add(m.name(), f.string());
    lib.names.push_back(m.name());
    lib.by_lower_name.emplace(key, std::move(m));
  }
  std::sort(lib.names.begin(), lib.names.end());
  return lib;
}

const Library& library() {
  static const Library lib = load_library();  // thread-safe one-time initialisation (C++11)
  return lib;
}

}  // namespace

const Medium& find_medium(std::string_view name) {
  const Library& lib = library();
  const auto it = lib.by_lower_name.find(lower_case(name));
  if (it == lib.by_lower_name.end()) {
    std::string known;
    for (const auto& n : lib.names) known += (known.empty() ? "" : ", ") + n;
    throw InputError("", "medium", std::string(name), "unknown medium (known: " + known + ")");
  }
  return it->second;
}

std::vector<std::string> available_media() { return library().names; }

}  // namespace pmsim
