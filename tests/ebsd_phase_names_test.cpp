// Phase names of EBSD files to library minerals: the automatic table, explicit maps, qualifiers,
// and the errors. Only minerals present in assets/minerals are expected to resolve here.
#include <gtest/gtest.h>

#include "core/base/asset_locator.h"
#include "core/base/json_reader.h"
#include "core/base/text.h"
#include "core/ebsd/phase_names.h"
#include "tests/ebsd_test_files.h"

namespace pmsim {
namespace {

using ebsd_test::input_error_of;
const std::map<std::string, std::string> kNone;

TEST(EbsdPhaseNames, LibraryNamesAndAliasesResolve) {
  EXPECT_EQ(map_phase_name("Quartz", kNone), "quartz");
  EXPECT_EQ(map_phase_name("CALCITE", kNone), "calcite");
  EXPECT_EQ(map_phase_name("  Diopside ", kNone), "diopside");
  EXPECT_EQ(map_phase_name("Enstatite", kNone), "enstatite");
  EXPECT_EQ(map_phase_name("Opx", kNone), "enstatite");
  EXPECT_EQ(map_phase_name("Clinopyroxene", kNone), "augite");
  EXPECT_EQ(map_phase_name("cpx", kNone), "augite");
  EXPECT_EQ(map_phase_name("Albite", kNone), "plagioclase");
  EXPECT_EQ(map_phase_name("Anorthite", kNone), "plagioclase");
  EXPECT_EQ(map_phase_name("K-Feldspar", kNone), "orthoclase");
  // Forsterite is olivine of composition Fo100; the composition is the mineral library's to read.
  EXPECT_EQ(map_phase_name("Forsterite", kNone).substr(0, 8), "olivine:");
}

TEST(EbsdPhaseNames, QualifiersAreIgnored) {
  EXPECT_EQ(map_phase_name("Quartz-new", kNone), "quartz");
  EXPECT_EQ(map_phase_name("Quartz low", kNone), "quartz");
  EXPECT_EQ(map_phase_name("Quartz_low", kNone), "quartz");
  EXPECT_EQ(map_phase_name("Low albite", kNone), "plagioclase");
  EXPECT_EQ(map_phase_name("Calcite-new", kNone), "calcite");
}

TEST(EbsdPhaseNames, IsotropicAndNone) {
  EXPECT_EQ(map_phase_name("Isotropic", kNone), "isotropic");
  EXPECT_EQ(map_phase_name("none", kNone), "none");
}

TEST(EbsdPhaseNames, ExplicitMapWins) {
  const std::map<std::string, std::string> m = {
      {"Phase 3", "olivine:Fo90"}, {"Quartz", "none"}, {"Px", "opx"}, {"Glass", "isotropic"}};
  EXPECT_EQ(map_phase_name("Phase 3", m), "olivine:Fo90");
  EXPECT_EQ(map_phase_name("phase 3", m), "olivine:Fo90");  // the key ignoring case
  EXPECT_EQ(map_phase_name("Quartz", m), "none");
  EXPECT_EQ(map_phase_name("Px", m), "enstatite");  // a value may be an alias
  EXPECT_EQ(map_phase_name("GLASS", m), "isotropic");
  EXPECT_EQ(map_phase_name("Calcite", m), "calcite");  // not in the map: automatic
}

TEST(EbsdPhaseNames, UnknownPhaseNamesTheNameAndHowToMapIt) {
  const InputError e = input_error_of([] { map_phase_name("Garnett-xyz", kNone, "rock.ctf"); });
  EXPECT_EQ(e.file, "rock.ctf");
  EXPECT_EQ(e.key, "sample.phases");
  EXPECT_EQ(e.value, "Garnett-xyz");
  const std::string what = e.what();
  EXPECT_NE(what.find("'Garnett-xyz'"), std::string::npos) << what;
  EXPECT_NE(what.find("\"phases\": {\"Garnett-xyz\""), std::string::npos) << what;
  EXPECT_NE(what.find("isotropic"), std::string::npos) << what;
}

TEST(EbsdPhaseNames, BadExplicitValuesAreRefused) {
  const std::map<std::string, std::string> m = {{"Phase 1", "unobtainium"}, {"Phase 2", "marble:Fo90"}};
  const InputError a = input_error_of([&] { map_phase_name("Phase 1", m, "scene.json"); });
  EXPECT_EQ(a.key, "sample.phases.Phase 1");
  EXPECT_EQ(a.value, "unobtainium");
  const InputError b = input_error_of([&] { map_phase_name("Phase 2", m, "scene.json"); });
  EXPECT_EQ(b.key, "sample.phases.Phase 2");
  EXPECT_NE(std::string(b.what()).find("'marble'"), std::string::npos) << b.what();
}

TEST(EbsdPhaseNames, EveryTableEntryGivesAMineralAndWhy) {
  const nlohmann::json j = read_json_file(asset_dir() + "/ebsd/phase_names.json", "table");
  ASSERT_TRUE(j.contains("source"));
  ASSERT_TRUE(j["names"].is_object());
  EXPECT_GE(j["names"].size(), 20u);
  for (const auto& [name, entry] : j["names"].items()) {
    EXPECT_EQ(name, lower_case(name)) << "keys are matched in lower case";
    EXPECT_FALSE(entry.value("mineral", "").empty()) << name;
    EXPECT_GE(entry.value("why", "").size(), 10u) << name << ": a rationale per entry";
  }
}

}  // namespace
}  // namespace pmsim
