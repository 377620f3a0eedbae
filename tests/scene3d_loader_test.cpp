// The scene3d loader accepts the shipped scenes and rejects bad input with an InputError that
// names the file, the key and the value.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/base/input_error.h"
#include "core/scene3d/scene3d_description.h"
#include "core/scene3d/scene3d_world.h"
#include "core/scene3d/vignetting.h"

namespace pmsim {
namespace {

nlohmann::json minimal() {
  return nlohmann::json::parse(R"({
    "type": "scene3d",
    "camera": {"position": [0, 10, 50], "look_at": [0, 0, 0]},
    "lights": [{"type": "point", "position": [0, 50, 0], "intensity": 100}],
    "materials": {"white": {"type": "diffuse", "rgb": [0.8, 0.8, 0.8]}},
    "objects": [{"type": "plane", "material": "white"}]
  })");
}

// Expects parse (and geometry build) to fail naming `key` and containing `value`.
void expect_rejected(const nlohmann::json& j, const std::string& key, const std::string& value) {
  try {
    const Scene3dDescription d = parse_scene3d(j, "bad.json");
    const Scene3dWorld w(d);
    FAIL() << "accepted; expected an error at " << key;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file, "bad.json");
    EXPECT_EQ(e.key, key) << e.what();
    EXPECT_NE(e.value.find(value), std::string::npos) << e.what();
  }
}

TEST(Scene3dLoader, ShippedScenesLoad) {
  const std::string dir = std::string(PMSIM_SOURCE_DIR) + "/assets/scenes3d";
  int scenes = 0;
  for (const auto& f : std::filesystem::directory_iterator(dir)) {
    if (f.path().extension() != ".json") continue;
    std::ifstream in(f.path());
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_TRUE(j.contains("source")) << f.path() << " must name the source of its numbers";
    if (j.value("type", "") == "objective") {
      EXPECT_NO_THROW(objective_from_json(j, f.path().string())) << f.path();
      continue;
    }
    const Scene3dDescription d = load_scene3d_file(f.path().string());
    EXPECT_NO_THROW(Scene3dWorld w(d)) << f.path();
    ++scenes;
  }
  EXPECT_GE(scenes, 3);
}

TEST(Scene3dLoader, MinimalSceneTakesDefaults) {
  const Scene3dDescription d = parse_scene3d(minimal(), "ok.json");
  EXPECT_EQ(d.render.wavelengths, 81);  // the paper's nSp
  EXPECT_EQ(d.render.mode, Scene3dMode::Spectral);
  EXPECT_FALSE(d.camera.filter_angle_deg.has_value());
}

TEST(Scene3dLoader, RejectsBadInputNamingFileKeyAndValue) {
  nlohmann::json j = minimal();
  j["camera"]["fov"] = 40;  // misspelt
  expect_rejected(j, "camera.fov", "40");

  j = minimal();
  j["type"] = "scene";
  expect_rejected(j, "type", "scene");

  j = minimal();
  j["render"] = {{"wavelengths", 500}};
  expect_rejected(j, "render.wavelengths", "500");

  j = minimal();
  j["render"] = {{"fresnel", "approximate"}};
  expect_rejected(j, "render.fresnel", "approximate");

  j = minimal();
  j["objects"][0]["material"] = "gold";
  expect_rejected(j, "objects[0].material", "gold");

  j = minimal();
  j["materials"]["white"]["rgb"] = {0.5, 2.0, 0.5};
  expect_rejected(j, "materials.white.rgb", "2.0");

  j = minimal();
  j["materials"]["glass"] = {{"type", "glass"}, {"medium", "unobtainium"}};
  expect_rejected(j, "materials.glass.medium", "unobtainium");

  j = minimal();
  j["lights"][0]["position"] = {0, "up", 0};
  expect_rejected(j, "lights[0].position", "up");

  j = minimal();
  j["camera"]["look_at"] = {0, 10, 50};  // equal to the position
  expect_rejected(j, "camera.look_at", "50");

  j = minimal();
  j["objects"].push_back({{"type", "box"}, {"material", "white"}, {"size_mm", {1, -2, 1}}});
  expect_rejected(j, "objects[1].size_mm", "-2");

  j = minimal();
  j["objects"].push_back({{"type", "mesh"},
                          {"material", "white"},
                          {"vertices", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
                          {"triangles", {{0, 1, 3}}}});
  expect_rejected(j, "objects[1].triangles[0]", "3");

  // Lens keys are the lens module's; the error is re-rooted at the object.
  j = minimal();
  j["objects"].push_back({{"type", "lens"},
                          {"glass", "N-BK7"},
                          {"radius_mm", 5},
                          {"front", {{"radius_mm", 3}}},
                          {"ledge_mm", 1}});
  expect_rejected(j, "objects[1].front.radius_mm", "3");

  j = minimal();
  j["camera"]["filter"] = {{"angle", 90}};
  expect_rejected(j, "camera.filter.angle", "90");
}

TEST(Scene3dLoader, MissingFileIsAnInputError) {
  EXPECT_THROW(load_scene3d_file("/nonexistent/scene.json"), InputError);
}

}  // namespace
}  // namespace pmsim
