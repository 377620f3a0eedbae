// Scene files and --set: every key round-trips, and bad input names file, key and value.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/base/input_error.h"
#include "core/io/scene_file.h"

using namespace pmsim;
using nlohmann::json;

namespace {

std::string temp_dir() {
  const auto d = std::filesystem::temp_directory_path() / ("pmsim_io_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d.string();
}

// Expects InputError from f() whose file, key and value are the given ones.
template <class F>
void expect_input_error(F&& f, const std::string& file, const std::string& key, const std::string& value) {
  try {
    f();
    ADD_FAILURE() << "no InputError for key " << key << " = " << value;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file, file);
    EXPECT_EQ(e.key, key);
    EXPECT_EQ(e.value, value);
    const std::string msg = e.what();
    EXPECT_NE(msg.find(key), std::string::npos) << msg;
    if (!value.empty()) {
      EXPECT_NE(msg.find(value), std::string::npos) << msg;
    }
  }
}

}  // namespace

TEST(SceneFile, EveryKeyRoundTripsThroughSaveAndLoad) {
  Scene s;
  s.mode = ViewMode::Cono;
  s.polarizer_deg = 12.5;
  s.analyzer_deg = 101.0;
  s.analyzer_in = false;
  s.stage_deg = 33.0;
  s.bertrand_in = false;  // cono with the Bertrand lens out: must survive the round trip
  s.illuminant = Illuminant::A;
  s.objective = {40.0, 0.65};
  s.condenser.na = 0.7;
  s.sample.type = SampleType::Wedge;
  s.sample.mineral = "calcite";
  s.sample.crystal = CrystalIndices{false, 1.5, 1.5, 1.5};
  s.sample.crystal->nalpha = 1.51;
  s.sample.crystal->nbeta = 1.52;
  s.sample.crystal->ngamma = 1.55;
  s.sample.thickness_um = 77.0;
  s.sample.optic_axis = {0.0, 0.6, 0.8};
  s.sample.x_axis = {0.0, 1.0, 0.0};
  s.sample.z_axis = {0.0, 0.0, 1.0};
  s.sample.section = "basalt";
  s.compensator = Compensator::QuartzWedge;
  s.compensator_position = 0.25;
  s.render = {320, 200, 4, 40, 0.0, 0.8, RenderStrategy::Modal};
  s.optics = {LensModel::Ideal, 3, FresnelModel::Schlick};
  const std::string path = temp_dir() + "/round_trip.json";
  save_scene_file(s, path);
  const Scene back = load_scene_file(path);
  EXPECT_EQ(scene_to_json(back).dump(), scene_to_json(s).dump());
  EXPECT_FALSE(back.bertrand_in);
  ASSERT_TRUE(back.sample.crystal.has_value());
  EXPECT_FALSE(back.sample.crystal->uniaxial);
  EXPECT_DOUBLE_EQ(back.sample.crystal->ngamma, 1.55);
}

TEST(SceneFile, ConoAloneImpliesBertrandIn) {
  const Scene s = scene_from_json(json{{"mode", "cono"}}, "x.json");
  EXPECT_TRUE(s.bertrand_in);
  Scene t;
  apply_setting(t, "mode=cono");
  EXPECT_TRUE(t.bertrand_in);
  apply_setting(t, "bertrand=out");
  EXPECT_FALSE(t.bertrand_in);
  EXPECT_EQ(t.mode, ViewMode::Cono);
}

TEST(SceneFile, VectorsAreNormalisedAndCrystalReplacesMineral) {
  const Scene s =
      scene_from_json(json::parse(R"({"sample": {"mineral": "calcite", "crystal": {"no": 1.6, "ne": 1.5},
                                  "optic_axis": [0, 3, 4]}})"),
                      "x.json");
  ASSERT_TRUE(s.sample.crystal.has_value());
  EXPECT_DOUBLE_EQ(s.sample.optic_axis[1], 0.6);
  EXPECT_DOUBLE_EQ(s.sample.optic_axis[2], 0.8);
}

TEST(SceneFile, UnknownKeysAreWarningsNamingTheKey) {
  std::vector<std::string> warnings;
  scene_from_json(json::parse(R"({"stage_deg": 10, "sample": {"colour": "red"}})"), "w.json", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("sample.colour"), std::string::npos);
}

TEST(SceneFile, BadValuesNameFileKeyAndValue) {
  auto load = [](const char* text) { return [text] { scene_from_json(json::parse(text), "bad.json"); }; };
  expect_input_error(load(R"({"sample": {"thickness_um": -1}})"), "bad.json", "sample.thickness_um", "-1");
  expect_input_error(load(R"({"sample": {"thickness_um": 0}})"), "bad.json", "sample.thickness_um", "0");
  expect_input_error(load(R"({"objective": {"na": 1.2}})"), "bad.json", "objective.na", "1.2");
  expect_input_error(load(R"({"condenser": {"na": 1}})"), "bad.json", "condenser.na", "1");
  expect_input_error(load(R"({"render": {"single_wavelength_nm": 300}})"), "bad.json",
                     "render.single_wavelength_nm", "300");
  expect_input_error(load(R"({"sample": {"optic_axis": [0, 0, 0]}})"), "bad.json", "sample.optic_axis",
                     "[0,0,0]");
  expect_input_error(load(R"({"sample": {"crystal": {"no": 1.0, "ne": 1.5}}})"), "bad.json", "sample.crystal",
                     R"({"ne":1.5,"no":1.0})");
  expect_input_error(load(R"({"render": {"width": 20000}})"), "bad.json", "render.width", "20000");
  expect_input_error(load(R"({"sample": {"mineral": "unobtainium"}})"), "bad.json", "sample.mineral",
                     "unobtainium");
  expect_input_error(load(R"({"stage_deg": "ten"})"), "bad.json", "stage_deg", "ten");
  expect_input_error(load(R"({"mode": "sideways"})"), "bad.json", "mode", "sideways");
  expect_input_error(load(R"({"sample": {"type": "section", "section": "no_such_rock"}})"), "bad.json",
                     "sample.section", "no_such_rock");
}

TEST(SceneFile, CommandLineSettingsAreCheckedToo) {
  Scene s;
  expect_input_error([&] { apply_setting(s, "sample.thickness_um=-5"); }, "", "sample.thickness_um", "-5");
  expect_input_error([&] { apply_setting(s, "objective.na=1e999"); }, "", "objective.na", "1e999");
  expect_input_error([&] { apply_setting(s, "no.such.key=1"); }, "", "no.such.key", "1");
  // A failed setting leaves the scene as it was.
  EXPECT_DOUBLE_EQ(s.sample.thickness_um, 30.0);
  apply_setting(s, "sample.optic_axis=[1,1,0]");
  EXPECT_NEAR(s.sample.optic_axis[0], std::sqrt(0.5), 1e-15);
  apply_setting(s, "sample.crystal={\"no\":1.6,\"ne\":1.5}");
  ASSERT_TRUE(s.sample.crystal.has_value());
  apply_setting(s, "sample.mineral=calcite");  // the latest choice of sample wins
  EXPECT_FALSE(s.sample.crystal.has_value());
}

TEST(SceneFile, MissingFileAndBrokenJsonAreInputErrors) {
  expect_input_error([] { load_scene_file("/nonexistent/scene.json"); }, "/nonexistent/scene.json", "", "");
  const std::string path = temp_dir() + "/broken.json";
  std::ofstream(path) << "{ \"mode\": ";
  expect_input_error([&] { load_scene_file(path); }, path, "", "");
}

TEST(SceneFile, ShippedScenesLoadWithoutWarnings) {
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(PMSIM_SOURCE_DIR) + "/assets/scenes")) {
    std::vector<std::string> warnings;
    EXPECT_NO_THROW(load_scene_file(e.path().string(), &warnings)) << e.path();
    EXPECT_TRUE(warnings.empty()) << e.path() << ": " << (warnings.empty() ? "" : warnings[0]);
  }
}

TEST(SceneFile, FuzzFindingsAreInputErrors) {
  // A number beyond double range is a JSON error of the file, not a crash (fuzz finding F1).
  const std::string path = temp_dir() + "/overflow.json";
  std::ofstream(path) << R"({"stage_deg": 1e400})";
  expect_input_error([&] { load_scene_file(path); }, path, "", "");
  // Parallel biaxial axes leave no frame (fuzz finding F7).
  expect_input_error(
      [] {
        scene_from_json(json::parse(R"({"sample": {"x_axis": [0, 0, 1], "z_axis": [0, 0, 2]}})"), "p.json");
      },
      "p.json", "sample.x_axis", "[0,0,1]");
}

// A mineral name that is refused says why: a composition outside 0..100 mol %, a component the
// series does not have, or an unknown name, whose list of known names includes the aliases.
TEST(SceneFile, BadMineralCompositionsSayWhatIsWrong) {
  auto reason_for = [](const std::string& mineral) -> std::string {
    const json j = {{"sample", {{"mineral", mineral}}}};
    try {
      scene_from_json(j, "bad.json");
    } catch (const InputError& e) {
      EXPECT_EQ(e.file, "bad.json");
      EXPECT_EQ(e.key, "sample.mineral");
      EXPECT_EQ(e.value, mineral);
      return e.reason;
    }
    ADD_FAILURE() << mineral << " was taken";
    return "";
  };
  const std::string an140 = reason_for("plagioclase:An140");
  EXPECT_NE(an140.find("outside 0..100 mol %"), std::string::npos) << an140;
  EXPECT_EQ(an140.find("unknown mineral"), std::string::npos) << "plagioclase is known: " << an140;
  const std::string xy3 = reason_for("olivine:Xy3");
  EXPECT_NE(xy3.find("olivine:Fo35"), std::string::npos) << "shows how it is written: " << xy3;
  EXPECT_EQ(xy3.find("unknown mineral"), std::string::npos) << xy3;
  const std::string quartz = reason_for("quartz:An10");
  EXPECT_NE(quartz.find("not a solid-solution series"), std::string::npos) << quartz;
  const std::string unknown = reason_for("unobtainium");
  EXPECT_NE(unknown.find("unknown mineral"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("opx = enstatite"), std::string::npos) << "aliases are listed: " << unknown;
}
