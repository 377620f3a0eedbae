// Bad input in the data files a user may edit or add: material files (assets/materials), mineral
// files (assets/minerals) and lens files (the pmsim-trace lens JSON). Each defect must be an
// InputError naming the file, the key and the value — not a crash, not an exception of another
// type, and not a medium that later yields NaN at some wavelength.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "core/crystal/crystal.h"
#include "core/lens/lens.h"
#include "core/materials/medium.h"
#include "tests/reliability_support.h"

namespace pmsim {
namespace {

using nlohmann::json;
using reliability::input_error_of;
using reliability::ScratchDir;

json asset(const std::string& rel) {
  return json::parse(reliability::read_file(std::string(PMSIM_SOURCE_DIR) + "/assets/" + rel));
}

// Loads `j` from a file with `loader`, expecting an InputError naming that file, `key`, `value`.
template <class Loader>
void expect_rejected(const ScratchDir& d, const std::string& text, Loader loader, const std::string& key,
                     const std::string& value) {
  SCOPED_TRACE(text.substr(0, 200));
  const std::string path = d.file("data.json", text);
  auto e = input_error_of([&] { loader(path); });
  if (!e) return;
  EXPECT_EQ(e->file, path) << e->what();
  EXPECT_EQ(e->key, key) << e->what();
  EXPECT_TRUE(reliability::shows_value(e->value, value)) << "value '" << e->value << "': " << e->what();
}

const auto kMaterial = [](const std::string& p) { load_medium_file(p); };
const auto kMineral = [](const std::string& p) { load_mineral_file(p); };
const auto kLens = [](const std::string& p) { Lens lens(load_lens_spec(p)); };

TEST(MaterialFileInput, BadIndicesAndRangesNameKeyAndValue) {
  ScratchDir d;
  json c = {{"name", "test"}, {"source", "test"}, {"model", "constant"}, {"n", 1.5}};
  auto with = [&](json base, const std::string& k, json v) {
    base[k] = v;
    return base.dump();
  };
  expect_rejected(d, with(c, "n", 1.0), kMaterial, "n", "1");  // n ≤ 1 for a solid
  expect_rejected(d, with(c, "n", 0.5), kMaterial, "n", "0.5");
  expect_rejected(d, with(c, "n", 1e6), kMaterial, "n", "1000000");  // absurd
  expect_rejected(d, with(c, "n", "1.5"), kMaterial, "n", "1.5");    // wrong type
  expect_rejected(d, with(c, "nn", 1.5), kMaterial, "nn", "1.5");    // typo of a key
  expect_rejected(d, with(c, "attenuation_per_mm", -1), kMaterial, "attenuation_per_mm", "-1");

  json bk7 = asset("materials/N-BK7.json");
  json bad = bk7;
  bad["wavelength_range_nm"] = {780, 380};
  expect_rejected(d, bad.dump(), kMaterial, "wavelength_range_nm", "780");
  bad = bk7;
  bad["B"][0] = -5.0;  // n² < 0 somewhere
  expect_rejected(d, bad.dump(), kMaterial, "model", "sellmeier3");
}

TEST(MaterialFileInput, SellmeierPoleInsideTheValidRangeIsRejected) {
  // C = 0.1225 µm² puts a pole at 350 nm, inside N-BK7's 310–2500 nm but outside the visible
  // probes: pmsim-trace at 350 nm would get n = ∞ or NaN. Regression for the fix in
  // core/materials/medium_library.cpp (analytic pole check).
  ScratchDir d;
  json bad = asset("materials/N-BK7.json");
  bad["C_um2"][0] = 0.1225;
  bad.erase("catalogue");
  expect_rejected(d, bad.dump(), kMaterial, "C_um2[0]", "0.1225");
}

TEST(MaterialFileInput, BrokenFilesNameTheFile) {
  ScratchDir d;
  const std::string text = asset("materials/N-BK7.json").dump(2);
  for (const std::string& bytes : {text.substr(0, text.size() / 3), std::string(""),
                                   std::string("{\"name\":\"N-BK\xff\"}"), std::string("{\"n\": 1e400}")}) {
    const std::string path = d.file("m.json", bytes);
    auto e = input_error_of([&] { load_medium_file(path); });
    if (e) {
      EXPECT_EQ(e->file, path) << e->what();
    }
  }
}

TEST(MineralFileInput, BadIndicesNameKeyAndValue) {
  ScratchDir d;
  const json calcite = asset("minerals/calcite.json");
  json bad = calcite;
  bad["indices"] = {{"no", 0.9}, {"ne", 1.486}};
  expect_rejected(d, bad.dump(), kMineral, "indices.no", "0.9");
  bad["indices"] = {{"no", 1.658}, {"ne", 1e9}};
  expect_rejected(d, bad.dump(), kMineral, "indices.ne", "1000000000");
  bad["indices"] = {{"no", 1.658}, {"nee", 1.486}};  // typo: must not fall back silently
  expect_rejected(d, bad.dump(), kMineral, "indices.nee", "1.486");
  bad["indices"] = {{"no", 1.658}, {"ne", 1.486}, {"nx", 1.5}};
  expect_rejected(d, bad.dump(), kMineral, "indices.nx", "1.5");
  bad = calcite;
  bad["symmetry"] = "triaxial";
  expect_rejected(d, bad.dump(), kMineral, "symmetry", "triaxial");
  bad = calcite;
  bad["rotatory_powr"] = {{"A_deg_um2_per_mm", 1}};  // a misspelt optional key drops its data
  expect_rejected(d, bad.dump(), kMineral, "rotatory_powr", "A_deg");
  const json muscovite = asset("minerals/muscovite.json");
  bad = muscovite;
  bad["indices"] = {{"nalpha", 1.6}, {"nbeta", 1.59}, {"ngamma", 1.61}};
  expect_rejected(d, bad.dump(), kMineral, "indices", "1.59");
}

TEST(MineralFileInput, DispersionPoleInTheVisibleIsRejected) {
  // Ghosh's n² = A + B/(1 − C/λ²) + … has a pole at λ² = C. C = 0.25 µm² (500 nm) sits between the
  // old probes at 400, 589.3 and 700 nm; the renderer samples 500 nm and got NaN. Regression for
  // the fix in core/crystal/mineral_library.cpp (every nm of 380–780 is probed).
  ScratchDir d;
  json bad = asset("minerals/quartz.json");
  ASSERT_TRUE(bad["indices"]["no"].is_object());
  bad["indices"]["no"]["C"] = 0.2500001;
  expect_rejected(d, bad.dump(), kMineral, "indices.no", "ghosh1999");
}

TEST(MineralFileInput, NumberOverflowIsAnInputErrorNotAJsonException) {
  // 1e400 overflows a double: nlohmann throws out_of_range (406), which the loader did not catch
  // (only parse_error). Regression for the fix in core/crystal/mineral_library.cpp.
  ScratchDir d;
  json m = asset("minerals/calcite.json");
  std::string text = m.dump();
  text.replace(text.find("\"indices\""), 9, "\"x\":1e400,\"indices\"");
  const std::string path = d.file("overflow.json", text);
  auto e = input_error_of([&] { load_mineral_file(path); });
  if (e) {
    EXPECT_EQ(e->file, path);
  }
}

TEST(MineralFileInput, BrokenFilesNameTheFile) {
  ScratchDir d;
  const std::string text = asset("minerals/quartz.json").dump(2);
  for (const std::string& bytes : {text.substr(0, text.size() / 2), std::string(""),
                                   std::string("{\"name\":\"qu\xe4rtz\"}"), std::string("\x89PNG")}) {
    const std::string path = d.file("m.json", bytes);
    auto e = input_error_of([&] { load_mineral_file(path); });
    if (e) {
      EXPECT_EQ(e->file, path) << e->what();
    }
  }
  EXPECT_INPUT_ERROR(find_mineral("unobtainium"), "", "unobtainium");  // the caller adds its key
}

TEST(MineralFileInput, EveryAssetMineralLoads) {
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(PMSIM_SOURCE_DIR) + "/assets/minerals")) {
    SCOPED_TRACE(e.path().string());
    if (e.path().filename() == "aliases.json") continue;  // the alias table, not a mineral
    EXPECT_NO_THROW(load_mineral_file(e.path().string()));
  }
  EXPECT_NO_THROW(mineral_aliases());  // and the alias table loads with the library
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(PMSIM_SOURCE_DIR) + "/assets/materials")) {
    SCOPED_TRACE(e.path().string());
    EXPECT_NO_THROW(load_medium_file(e.path().string()));
  }
}

TEST(LensFileInput, BadGeometryNamesKeyAndValue) {
  ScratchDir d;
  const json base = asset("lenses/biconvex_bk7.json");
  auto with = [&](const std::string& k, json v) {
    json j = base;
    j[k] = v;
    return j.dump();
  };
  expect_rejected(d, with("radius_mm", 0), kLens, "radius_mm", "0");
  expect_rejected(d, with("radius_mm", -4), kLens, "radius_mm", "-4");
  expect_rejected(d, with("ledge_mm", -0.3), kLens, "ledge_mm", "-0.3");
  expect_rejected(d, with("axis", json::array({0, 0, 0})), kLens, "axis", "0");
  expect_rejected(d, with("axis", json::array({0, 0})), kLens, "axis", "0");
  expect_rejected(d, with("center", json::array({0, "x", 0})), kLens, "center", "x");
  expect_rejected(d, with("glass", "unobtainium"), kLens, "glass", "unobtainium");
  expect_rejected(d, with("medium", "honey"), kLens, "medium", "honey");
  expect_rejected(d, with("radius_mm", 9), kLens, "front.radius_mm", "8");  // aperture 9 > |R| = 8
  expect_rejected(d, with("thickness_mm", 5.0), kLens, "ledge_mm", "0.3");  // disagrees with ledge
  expect_rejected(d, with("radius_mmm", 4), kLens, "radius_mmm", "4");
  json j = base;
  j["front"] = {{"radius_mm", "eight"}};
  expect_rejected(d, j.dump(), kLens, "front.radius_mm", "eight");
  j = base;
  j.erase("ledge_mm");
  j["thickness_mm"] = 0.0;
  expect_rejected(d, j.dump(), kLens, "thickness_mm", "0");
}

TEST(LensFileInput, BrokenFilesNameTheFile) {
  ScratchDir d;
  const std::string text = asset("lenses/biconvex_bk7.json").dump(2);
  for (const std::string& bytes : {text.substr(0, text.size() / 2), std::string(""),
                                   std::string("{\"glass\":\"N-BK\xff\"}"), std::string("[]")}) {
    const std::string path = d.file("l.json", bytes);
    auto e = input_error_of([&] { Lens lens(load_lens_spec(path)); });
    if (e) {
      EXPECT_EQ(e->file, path) << e->what();
    }
  }
}

TEST(DataFileInput, AFolderGivenAsTheFileIsAnInputError) {
  // std::ifstream opens a folder; reading it throws std::ios_base::failure ("Is a directory").
  // Fixed in the material and mineral loaders (any read failure is an InputError); the lens
  // loader is finding F5.
  ScratchDir d;
  const std::string folder = d.path().string();
  auto m = input_error_of([&] { load_medium_file(folder); });
  if (m) {
    EXPECT_EQ(m->file, folder);
  }
  auto c = input_error_of([&] { load_mineral_file(folder); });
  if (c) {
    EXPECT_EQ(c->file, folder);
  }
}

TEST(LensFileInput, AFolderGivenAsTheLensFileIsAnInputError) {
  // Finding F5 (load_lens_spec).
  ScratchDir d;
  auto e = input_error_of([&] { load_lens_spec(d.path().string()); });
  if (e) {
    EXPECT_EQ(e->file, d.path().string());
  }
}

TEST(LensFileInput, NumberOverflowIsAnInputErrorNotAJsonException) {
  // See docs/robustness.md, finding F2 (load_lens_spec catches only parse_error).
  ScratchDir d;
  const std::string path = d.file("l.json", R"({"glass":"N-BK7","radius_mm":1e400,"ledge_mm":1})");
  auto e = input_error_of([&] { load_lens_spec(path); });
  if (e) {
    EXPECT_EQ(e->file, path);
  }
}

}  // namespace
}  // namespace pmsim
