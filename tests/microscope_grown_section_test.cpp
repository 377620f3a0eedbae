// A rock grown by the texture engine, read as a thin section: the section the renderer, labels,
// grains and probes read is the engine's tiling, and sample.seed reaches it.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/base/input_error.h"
#include "core/microscope/scene.h"
#include "core/microscope/scene_check.h"
#include "core/microscope/section_map.h"
#include "core/texture/rock_growth.h"
#include "core/texture/rock_recipe.h"

namespace pmsim {
namespace {

RockRecipe small_andesite() {
  RockRecipe r = read_rock_recipe(rock_recipe_path("andesite"));
  r.width_mm = r.height_mm = 2.0;
  return r;
}

// Every point's grain is the crystal the engine's tiling gives it (or the glass), and every grain
// of the file owns some of the section: the file holds the grown rock, not an approximation.
TEST(GrownSection, DomainsAreTheEnginesTiling) {
  const RockRecipe r = small_andesite();
  const RockGrowth g = grow_rock(r, 5);
  const SectionMap m = section_from_json(rock_section_json(r, g, 5), "andesite test");
  std::vector<const GrownCrystal*> present;
  for (const GrownCrystal& c : g.crystals)
    if (c.area_mm2 > 0) present.push_back(&c);
  ASSERT_EQ(m.grains.size(), present.size() + 1);  // + the glass
  EXPECT_EQ(m.grains.back().mineral, "glass");
  EXPECT_TRUE(m.grains.back().matrix);
  std::vector<int> seen(m.grains.size() + 1, 0);
  int glass = 0, zoned = 0;
  for (int j = 0; j < 300; ++j)
    for (int i = 0; i < 300; ++i) {
      const glm::dvec2 p{(i + 0.5) / 150.0 - 1.0, (j + 0.5) / 150.0 - 1.0};
      const int d = m.domain_at(p);
      const int k = m.grain_label(d);
      ++seen[k];
      if (k == 0) continue;  // a crack
      const SectionGrain& gr = m.grain_by_label(k);
      glass += gr.matrix;
      if (!gr.matrix) {
        ASSERT_TRUE(gr.growth.has_value());
        // The grain's crystal reaches p no later than any other (the tiling's own definition).
        const double mine = gr.growth->from + growth_fraction(*gr.growth, p) * (gr.growth->to - gr.growth->from);
        zoned += gr.zones.size() > 1;
        if ((i + j) % 10 != 0) continue;  // the exhaustive check on a tenth of the points
        for (const SectionGrain& o : m.grains) {
          if (!o.growth || &o == &gr || growth_fraction(*o.growth, p) > 1.0) continue;
          ASSERT_LE(mine, o.growth->from + growth_fraction(*o.growth, p) * (o.growth->to - o.growth->from) + 1e-12);
        }
      }
    }
  // The glass fraction is the engine's (its raster and this one count the same section; 0.01 is
  // 4σ of the counting error of 9·10⁴ points). Cracks are counted as neither.
  EXPECT_NEAR(glass / 90000.0, g.area_fraction.back(), 0.01);
  EXPECT_GT(zoned, 0);  // oscillatory-zoned phenocrysts
}

// sample.seed: a scene key for rocks with a recipe; refused with file, key and value on a
// hand-placed section, which cannot be grown again.
TEST(GrownSection, SeedIsCheckedAgainstTheSection) {
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = "andesite";
  s.sample.seed = 4;
  EXPECT_NO_THROW(check_scene(s, "scene.json"));
  s.sample.section = "granite";
  try {
    check_scene(s, "scene.json");
    FAIL() << "sample.seed on a section file was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("sample.seed"), std::string::npos) << what;
    EXPECT_NE(what.find("scene.json"), std::string::npos) << what;
  }
  s.sample.section = "andesite";
  s.sample.seed = -1;
  EXPECT_THROW(check_scene(s, "scene.json"), InputError);
}

// A bad grown section file: growth that ends before it starts, named by file and key.
TEST(GrownSection, MalformedGrowthIsNamed) {
  nlohmann::json j = {{"size_mm", {1.0, 1.0}},
                      {"grains", {{{"mineral", "augite"}, {"centre_mm", {0.0, 0.0}}, {"size_mm", 0.5},
                                   {"euler_deg", {0, 0, 0}}, {"growth", {{"from", 0.5}, {"to", 0.2}}}}}}};
  try {
    (void)section_from_json(j, "bad.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("growth.to"), std::string::npos) << e.what();
  }
  j["grains"][0]["growth"]["to"] = 1.0;
  j["grains"].push_back({{"mineral", "quartz"}, {"centre_mm", {0.3, 0.0}}, {"size_mm", 0.5}, {"euler_deg", {0, 0, 0}}});
  EXPECT_THROW((void)section_from_json(j, "mixed.json"), InputError);  // grown and ellipse grains
}

}  // namespace
}  // namespace pmsim
