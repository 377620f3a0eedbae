// Bad input on the scene paths: scene files (load_scene_file) and `--set key=value`
// (apply_setting), which the CLI, the UI and saved scenes share. Every bad value must come back as
// an InputError naming the file, the key and the value — never a crash, a NaN image or a silent
// default — and a rejected --set must leave the scene as it was (the UI keeps the last good state).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/io/scene_file.h"
#include "tests/reliability_support.h"

namespace pmsim {
namespace {

using reliability::input_error_of;
using reliability::ScratchDir;

Scene load(const ScratchDir& d, const std::string& text, std::vector<std::string>* w = nullptr) {
  return load_scene_file(d.file("scene.json", text), w);
}

TEST(SceneFileInput, OutOfRangeValuesNameTheFileKeyAndValue) {
  ScratchDir d;
  struct Case {
    const char* json;
    const char* key;
    const char* value;
  };
  const Case cases[] = {
      {R"({"sample":{"crystal":{"no":1.0,"ne":1.5}}})", "sample.crystal", "1"},  // n ≤ 1
      {R"({"sample":{"crystal":{"no":0.5,"ne":1.5}}})", "sample.crystal", "0.5"},
      {R"({"sample":{"crystal":{"no":1.5,"ne":1e6}}})", "sample.crystal", "1000000"},  // absurd n
      {R"({"sample":{"crystal":{"nalpha":1.7,"nbeta":1.6,"ngamma":1.5}}})", "sample.crystal", "1.7"},
      {R"({"sample":{"thickness_um":-5}})", "sample.thickness_um", "-5"},
      {R"({"sample":{"thickness_um":0}})", "sample.thickness_um", "0"},
      {R"({"sample":{"thickness_um":1e9}})", "sample.thickness_um", "1000000000"},
      {R"({"objective":{"na":1.0}})", "objective.na", "1"},  // NA ≥ 1 in air
      {R"({"objective":{"na":1.4}})", "objective.na", "1.4"},
      {R"({"objective":{"na":-0.1}})", "objective.na", "-0.1"},
      {R"({"condenser":{"na":1.2}})", "condenser.na", "1.2"},
      {R"({"objective":{"magnification":0}})", "objective.magnification", "0"},
      {R"({"render":{"single_wavelength_nm":300}})", "render.single_wavelength_nm", "300"},
      {R"({"render":{"single_wavelength_nm":900}})", "render.single_wavelength_nm", "900"},
      {R"({"sample":{"optic_axis":[0,0,0]}})", "sample.optic_axis", "[0,0,0]"},
      {R"({"sample":{"optic_axis":[1,0]}})", "sample.optic_axis", "[1,0]"},
      {R"({"sample":{"z_axis":[0,0,0]}})", "sample.z_axis", "[0,0,0]"},
      {R"({"stage_deg":"abc"})", "stage_deg", "abc"},
      {R"({"stage_deg":null})", "stage_deg", "null"},
      {R"({"render":{"spp":1.5}})", "render.spp", "1.5"},
      {R"({"render":{"width":100000,"height":100000}})", "render.width", "100000"},  // 10¹⁰ pixels
      {R"({"render":{"width":-1}})", "render.width", "-1"},
      {R"({"render":{"wavelengths":1000000}})", "render.wavelengths", "1000000"},
      {R"({"optics":{"lens_depth":1000000}})", "optics.lens_depth", "1000000"},  // dT 10⁶
      {R"({"compensator_position":2})", "compensator_position", "2"},
      {R"({"compensator":"quartz"})", "compensator", "quartz"},
      {R"({"mode":"sideways"})", "mode", "sideways"},
      {R"({"sample":{"mineral":"unobtainium"}})", "sample.mineral", "unobtainium"},
      {R"({"sample":{"medium":"honey"}})", "sample.medium", "honey"},
      {R"({"sample":{"type":"section","section":"moon_rock"}})", "sample.section", "moon_rock"},
      {R"({"render":{"strategy":"magic"}})", "render.strategy", "magic"},
      {R"({"type":"scene3d"})", "type", "scene3d"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.json);
    const std::string path = d.file("scene.json", c.json);
    auto e = input_error_of([&] { load_scene_file(path); });
    if (!e) continue;
    EXPECT_EQ(e->file, path) << e->what();
    EXPECT_EQ(e->key, c.key) << e->what();
    EXPECT_TRUE(reliability::shows_value(e->value, c.value)) << "value '" << e->value << "': " << e->what();
    EXPECT_NE(std::string(e->what()).find(path), std::string::npos) << e->what();
  }
}

TEST(SceneFileInput, BiaxialAxesMustNotBeParallel) {
  // x_axis (nα) and z_axis (nγ) span the optic-axial plane; parallel ones define no orientation.
  ScratchDir d;
  EXPECT_INPUT_ERROR(load(d, R"({"sample":{"mineral":"muscovite","x_axis":[0,0,1],"z_axis":[0,0,2]}})"),
                     "sample.x_axis", "");
}

TEST(SceneFileInput, BiaxialAxesMustBePerpendicular) {
  // x_axis (nα) ⟂ z_axis (nγ) by definition; an oblique pair rendered silently (the renderer kept
  // only x_axis's part ⟂ z_axis) while --set refused nothing either: both now refuse it.
  ScratchDir d;
  EXPECT_INPUT_ERROR(load(d, R"({"sample":{"mineral":"muscovite","x_axis":[1,0,0.5],"z_axis":[0,0,1]}})"),
                     "sample.x_axis", "[1,0,0.5]");
  Scene s;
  EXPECT_INPUT_ERROR(apply_setting(s, "sample.x_axis=[1,0,0.5]"), "sample.x_axis", "[1,0,0.5]");
  // The tolerance is |x̂·ẑ| ≤ 1e-6: cos = 1e-7 (rounding of hand-written axes) passes, 1e-5 not.
  EXPECT_NO_THROW(load(d, R"({"sample":{"x_axis":[1,0,1e-7],"z_axis":[0,0,1]}})"));
  EXPECT_INPUT_ERROR(load(d, R"({"sample":{"x_axis":[1,0,1e-5],"z_axis":[0,0,1]}})"), "sample.x_axis", "");
}

TEST(SceneFileInput, AGroupOfTheWrongTypeIsAnError) {
  // "sample": "quartz" was warned as an unknown key and the default sample rendered.
  ScratchDir d;
  std::vector<std::string> warnings;
  EXPECT_INPUT_ERROR(load(d, R"({"sample":"quartz"})", &warnings), "sample", "quartz");
  for (const char* group : {"objective", "condenser", "render", "optics"}) {
    SCOPED_TRACE(group);
    EXPECT_INPUT_ERROR(load(d, std::string("{\"") + group + "\": 5}"), group, "5");
  }
}

TEST(SceneFileInput, NumbersBeyondDoubleRangeAreInputErrors) {
  // 1e400 is valid JSON syntax but overflows a double: nlohmann throws out_of_range (406), not a
  // parse_error. See docs/robustness.md, finding F1.
  ScratchDir d;
  auto e = input_error_of([&] { load(d, R"({"stage_deg": 1e400})"); });
  if (e) {
    EXPECT_NE(std::string(e->what()).find("scene.json"), std::string::npos) << e->what();
  }
}

TEST(SceneFileInput, UnknownKeysAreWarningsNamingTheKey) {
  ScratchDir d;
  std::vector<std::string> warnings;
  const Scene s =
      load(d, R"({"stgae_deg": 45, "sample": {"thicknes_um": 3, "thickness_um": 20}})", &warnings);
  ASSERT_EQ(warnings.size(), 2u);
  std::string all = warnings[0] + "\n" + warnings[1];
  EXPECT_NE(all.find("'stgae_deg'"), std::string::npos) << all;
  EXPECT_NE(all.find("'sample.thicknes_um'"), std::string::npos) << all;
  EXPECT_EQ(s.sample.thickness_um, 20.0);  // the known keys still apply
  EXPECT_EQ(s.stage_deg, Scene{}.stage_deg);
}

TEST(SceneFileInput, BrokenFilesAreInputErrorsNamingTheFile) {
  ScratchDir d;
  const std::string asset =
      reliability::read_file(std::string(PMSIM_SOURCE_DIR) + "/assets/scenes/quartz_wedge.json");
  ASSERT_GT(asset.size(), 20u);
  const std::vector<std::pair<const char*, std::string>> files = {
      {"truncated", asset.substr(0, asset.size() / 2)},
      {"empty", ""},
      {"non-UTF-8 string",
       "{\"sample\":{\"mineral\":\"qu\xff\xfe"
       "rtz\"}}"},
      {"Latin-1 byte in a key", "{\"st\xe4ge_deg\": 4}"},
      {"binary", std::string("\x00\x01\x02\x89PNG\r\n", 9)},
      {"NaN literal", R"({"stage_deg": NaN})"},
      {"Infinity literal", R"({"stage_deg": Infinity})"},
      {"array", "[1,2,3]"},
      {"trailing garbage", R"({"stage_deg": 4} x)"},
  };
  for (const auto& [what, bytes] : files) {
    SCOPED_TRACE(what);
    const std::string path = d.file("bad.json", bytes);
    auto e = input_error_of([&] { load_scene_file(path); });
    if (e) {
      EXPECT_EQ(e->file, path);
      EXPECT_NE(std::string(e->what()).find(path), std::string::npos) << e->what();
    }
  }
  EXPECT_INPUT_ERROR(load_scene_file(d / "missing.json"), "", "");
}

TEST(SceneFileInput, AFolderGivenAsTheSceneFileIsAnInputError) {
  // std::ifstream opens a folder; reading it throws std::ios_base::failure ("Is a directory")
  // through nlohmann's parser. Finding F5.
  ScratchDir d;
  auto e = input_error_of([&] { load_scene_file(d.path().string()); });
  if (e) {
    EXPECT_EQ(e->file, d.path().string());
  }
}

TEST(SceneFileInput, EveryAssetSceneLoadsWithoutWarnings) {
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(PMSIM_SOURCE_DIR) + "/assets/scenes")) {
    SCOPED_TRACE(entry.path().string());
    std::vector<std::string> warnings;
    EXPECT_NO_THROW(load_scene_file(entry.path().string(), &warnings));
    EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings.front());
  }
}

TEST(SetOption, BadValuesNameKeyAndValueAndKeepTheLastGoodScene) {
  struct Case {
    const char* assignment;
    const char* key;
    const char* value;
  };
  const Case cases[] = {
      {"objective.na=1", "objective.na", "1"},
      {"objective.na=1.3", "objective.na", "1.3"},
      {"condenser.na=0", "condenser.na", "0"},
      {"sample.thickness_um=-1", "sample.thickness_um", "-1"},
      {"sample.thickness_um=0", "sample.thickness_um", "0"},
      {"render.single_wavelength_nm=200", "render.single_wavelength_nm", "200"},
      {"render.single_wavelength_nm=1e6", "render.single_wavelength_nm", "1e6"},
      {"sample.optic_axis=[0,0,0]", "sample.optic_axis", "[0,0,0]"},
      {"sample.x_axis=[1,2]", "sample.x_axis", "[1,2]"},
      {"stage_deg=nan", "stage_deg", "nan"},
      {"stage_deg=NaN", "stage_deg", "NaN"},
      {"stage_deg=inf", "stage_deg", "inf"},
      {"stage_deg=-Infinity", "stage_deg", "-Infinity"},
      {"stage_deg=1e400", "stage_deg", "1e400"},
      {"stage_deg=", "stage_deg", ""},
      {"render.width=100000", "render.width", "100000"},
      {"render.height=1e10", "render.height", "1e10"},
      {"render.spp=-3", "render.spp", "-3"},
      {"optics.lens_depth=1000000", "optics.lens_depth", "1000000"},
      {"optics.lens_depth=1e6", "optics.lens_depth", "1e6"},
      {"sample.mineral=unobtainium", "sample.mineral", "unobtainium"},
      {"sample.crystal={\"no\":0.9,\"ne\":1.5}", "sample.crystal", "0.9"},
      {"sample.crystal={\"no\":1.5}", "sample.crystal", "1.5"},
      {"sample.crystal=[1.5,1.6]", "sample.crystal", "[1.5,1.6]"},
      {"analyzer=maybe", "analyzer", "maybe"},
      {"illuminant=F11", "illuminant", "F11"},
      {"compensator_position=-0.5", "compensator_position", "-0.5"},
      {"nosuchkey=1", "nosuchkey", "1"},
      {"sample=1", "sample", "1"},
      {"sample.thickness_um=\xff\xfe", "sample.thickness_um", "\xff\xfe"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.assignment);
    Scene s;
    s.stage_deg = 12.5;
    s.sample.thickness_um = 42.0;
    const nlohmann::json before = scene_to_json(s);
    auto e = input_error_of([&] { apply_setting(s, c.assignment); });
    if (e) {
      EXPECT_EQ(e->file, "");
      EXPECT_EQ(e->key, c.key) << e->what();
      EXPECT_TRUE(reliability::shows_value(e->value, c.value)) << "value '" << e->value << "': " << e->what();
      EXPECT_NE(std::string(e->what()).find("command line"), std::string::npos) << e->what();
    }
    EXPECT_EQ(scene_to_json(s), before) << "a rejected --set changed the scene";
  }
  Scene s;
  EXPECT_INPUT_ERROR(apply_setting(s, "stage_deg"), "stage_deg", "");  // no '='
  EXPECT_INPUT_ERROR(apply_setting(s, "=5"), "=5", "");
}

TEST(SetOption, SettingsValidOnlyTogetherAreCheckedOnceAllApply) {
  // x_axis = [0,0,1] is parallel to the default z_axis and z_axis = [1,0,0] to the default
  // x_axis: each alone is refused, together (in either order) they are a valid frame.
  for (const std::vector<std::string>& order :
       {std::vector<std::string>{"sample.x_axis=[0,0,1]", "sample.z_axis=[1,0,0]"},
        std::vector<std::string>{"sample.z_axis=[1,0,0]", "sample.x_axis=[0,0,1]"}}) {
    SCOPED_TRACE(order.front());
    Scene s;
    s.sample.mineral = "muscovite";
    ASSERT_NO_THROW(apply_settings(s, order));
    EXPECT_EQ(s.sample.x_axis, (std::array<double, 3>{0, 0, 1}));
    EXPECT_EQ(s.sample.z_axis, (std::array<double, 3>{1, 0, 0}));
  }
  // A single setting is still validated at once (the UI's --set keeps the scene consistent), and
  // a refused list changes nothing, not even the settings before the bad one.
  Scene s;
  const nlohmann::json before = scene_to_json(s);
  EXPECT_INPUT_ERROR(apply_setting(s, "sample.x_axis=[0,0,1]"), "sample.x_axis", "[0,0,1]");
  EXPECT_INPUT_ERROR(apply_settings(s, {"stage_deg=10", "objective.na=2"}), "objective.na", "2");
  EXPECT_EQ(scene_to_json(s), before);
}

TEST(SetOption, AnImageTooLargeForMemoryIsRefused) {
  // Each side within 1…16384 is accepted, but 16384² pixels need ~13 GB (float RGB + XYZ and the
  // double accumulators): pmsim-render died of std::bad_alloc (exit 134). The pixel count must be
  // bounded too. Finding F8.
  Scene s;
  apply_setting(s, "render.width=16384");
  EXPECT_INPUT_ERROR(apply_setting(s, "render.height=16384"), "render.height", "16384");
}

TEST(SetOption, AnUnknownMineralIsRefusedWhateverTheSampleType) {
  // On a thin-section scene sample.mineral is not used, and an unknown name passed silently (a
  // later switch to sample.type=plate then failed on a key the user did not touch). Finding F6.
  Scene s;
  apply_setting(s, "sample.section=granite_hand_placed");
  apply_setting(s, "sample.type=section");
  EXPECT_INPUT_ERROR(apply_setting(s, "sample.mineral=unobtainium"), "sample.mineral", "unobtainium");
}

TEST(SetOption, NonUtf8TextIsRefused) {
  // Found by the scene_setting fuzzer: a string key took bytes that are not UTF-8; saving the
  // scene (or writing it into image metadata) then threw a JSON type_error. Finding F10.
  Scene s;
  EXPECT_INPUT_ERROR(apply_setting(s,
                                   "sample.section=\xff\xfe"
                                   "basalt"),
                     "sample.section", "basalt");
  const nlohmann::json before = scene_to_json(s);
  EXPECT_NO_THROW(before.dump());
}

TEST(SetOption, ValidValuesAtTheEdgesOfTheirRangesAreAccepted) {
  // The guards must not reject the legitimate extremes a student will try.
  Scene s;
  for (const char* ok :
       {"objective.na=0.95", "render.single_wavelength_nm=380", "render.single_wavelength_nm=780",
        "sample.thickness_um=0.001", "sample.optic_axis=[0,0,5]", "stage_deg=-720", "compensator_position=1",
        "render.width=1", "optics.lens_depth=0", "sample.crystal={\"no\":1.0001,\"ne\":5}"}) {
    SCOPED_TRACE(ok);
    EXPECT_NO_THROW(apply_setting(s, ok));
  }
  EXPECT_DOUBLE_EQ(s.sample.optic_axis[2], 1.0);  // vectors are normalised
}

}  // namespace
}  // namespace pmsim
