// The material library: lookup by name, the non-glass media, and validation of material files.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "core/base/input_error.h"
#include "core/materials/medium.h"

namespace pmsim {
namespace {

TEST(MaterialLibrary, EveryDeclaredNameIsPresentCaseInsensitively) {
  for (const char* name : {"N-BK7", "N-SF11", "N-SF6", "F2", "N-SK16", "air", "oil", "mounting"}) {
    EXPECT_NO_THROW(find_medium(name)) << name;
  }
  EXPECT_EQ(find_medium("n-bk7").name(), "N-BK7");
  EXPECT_EQ(find_medium("AIR").name(), "air");
  EXPECT_EQ(&find_medium("f2"), &find_medium("F2"));  // loaded once, same object
  EXPECT_EQ(available_media().size(), 8u);
}

TEST(MaterialLibrary, UnknownNameIsAnInputErrorNamingIt) {
  try {
    find_medium("unobtainium");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.value, "unobtainium");
    EXPECT_NE(std::string(e.what()).find("unobtainium"), std::string::npos);
  }
}

TEST(MaterialLibrary, ConcurrentFirstUseIsSafe) {
  // The library is a function-local static: every thread sees the same fully loaded object.
  std::vector<std::thread> threads;
  std::atomic<int> ok{0};
  for (int i = 0; i < 4; ++i) {
    threads.emplace_back([&] {
      if (std::abs(find_medium("N-BK7").nd() - 1.5168) < 1e-5) ++ok;
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(ok.load(), 4);
}

TEST(OtherMedia, AirIsConstantAndTransparent) {
  const Medium& air = find_medium("air");
  // Indices are relative to air (SCHOTT convention), so air is exactly 1 on this scale.
  EXPECT_EQ(air.n(380.0), 1.0);
  EXPECT_EQ(air.n(780.0), 1.0);
  EXPECT_EQ(air.attenuation_per_mm(550.0), 0.0);
}

TEST(OtherMedia, ImmersionOilMeetsIso8036) {
  // ISO 8036: n_e = 1.5180 ± 0.0004 at 546.07 nm, v_e = (n_e − 1)/(n_F' − n_C') = 44 ± 5 with the
  // cadmium lines F' = 479.99 nm, C' = 643.85 nm. Our Cauchy curve is fitted through the nominal
  // values; its coefficients are stored to 7 digits, so n_e to 1e-6 and v_e to 0.01.
  const Medium& oil = find_medium("oil");
  EXPECT_NEAR(oil.n(546.0740), 1.5180, 1e-6);
  EXPECT_NEAR((oil.n(546.0740) - 1.0) / (oil.n(479.9914) - oil.n(643.8469)), 44.0, 0.01);
  EXPECT_NEAR(oil.nd(), 1.5150, 5e-4);  // Cargille type A n_D = 1.5150 within the ISO tolerance
  EXPECT_GT(oil.n(400.0), oil.n(700.0));
}

TEST(OtherMedia, MountingMediumIsCanadaBalsamLike) { EXPECT_EQ(find_medium("mounting").n(589.0), 1.54); }

TEST(MediumFactories, BeerLambertWithConstantAttenuation) {
  // I = I0·e^(−μx): 2 mm of μ = 0.5/mm transmits e^(−1).
  const Medium m = Medium::constant("grey", 1.5, 0.5);
  EXPECT_NEAR(std::exp(-m.attenuation_per_mm(500.0) * 2.0), std::exp(-1.0), 1e-15);
  EXPECT_THROW(Medium::constant("bad", 0.9), std::invalid_argument);
  EXPECT_THROW(Medium::constant("bad", 1.5, -1.0), std::invalid_argument);
  Medium t = Medium::constant("t", 1.5);
  EXPECT_THROW(t.set_attenuation_table({500.0, 400.0}, {0.1, 0.2}), std::invalid_argument);
  EXPECT_THROW(t.set_attenuation_table({400.0}, {0.1, 0.2}), std::invalid_argument);
  EXPECT_THROW(t.set_wavelength_range(500.0, 400.0), std::invalid_argument);
}

// Writes a material file into the build tree and loads it.
class MaterialFile : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const std::filesystem::path dir =
        std::filesystem::path(PMSIM_BINARY_DIR) / "test-tmp" / "materials_library_test";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / name).string();
    std::ofstream(path) << text;
    return path;
  }
  // Loads text expecting an InputError; returns it.
  InputError expect_error(const std::string& text) {
    const std::string path = write("bad.json", text);
    try {
      load_medium_file(path);
    } catch (const InputError& e) {
      EXPECT_EQ(e.file, path);
      return e;
    }
    ADD_FAILURE() << "no InputError for " << text;
    return InputError("", "", "", "");
  }
};

constexpr const char* kGood = R"({"name": "test", "source": "unit test", "model": "sellmeier3",
  "B": [1.03961212, 0.231792344, 1.01046945], "C_um2": [0.00600069867, 0.0200179144, 103.560653],
  "wavelength_range_nm": [300, 2500],
  "internal_transmittance": {"thickness_mm": 10, "wavelength_nm": [400, 700], "tau_i": [0.9, 0.99]},
  "catalogue": {"nd": 1.5168}})";

TEST_F(MaterialFile, ValidFileLoads) {
  const Medium m = load_medium_file(write("good.json", kGood));
  EXPECT_EQ(m.name(), "test");
  EXPECT_NEAR(m.nd(), 1.5168, 1e-5);
  EXPECT_NEAR(m.attenuation_per_mm(400.0), -std::log(0.9) / 10.0, 1e-15);  // μ = −ln τ_i / d
}

TEST_F(MaterialFile, BadInputNamesKeyAndValue) {
  struct Case {
    std::string text, key, value_part;
  };
  const std::string base = kGood;
  auto replace = [&](const std::string& from, const std::string& to) {
    std::string s = base;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  const std::vector<Case> cases = {
      {replace(R"("name": "test", )", ""), "name", ""},
      {replace(R"("source": "unit test", )", ""), "source", ""},
      {replace(R"("model": "sellmeier3")", R"("model": "lorentz")"), "model", "lorentz"},
      {replace("[1.03961212, 0.231792344, 1.01046945]", "[1.0, 0.2]"), "B", "[1.0,0.2]"},
      {replace("[1.03961212, 0.231792344, 1.01046945]", R"([1.0, "x", 1.0])"), "B[1]", "x"},
      {replace("103.560653]", "-103.560653]"), "C_um2[2]", "-103.560653"},
      // JSON has no NaN/Inf; a number overflowing a double is rejected by the parser.
      {replace("[1.03961212, 0.231792344, 1.01046945]", "[1.0, 0.2, 1e999]"), "", ""},
      {replace("[300, 2500]", "[900, 800]"), "wavelength_range_nm", "[900,800]"},
      {replace(R"("wavelength_range_nm": [300, 2500],)", ""), "wavelength_range_nm", ""},
      {replace("[0.9, 0.99]", "[0.9, 1.5]"), "internal_transmittance.tau_i[1]", "1.5"},
      {replace("[0.9, 0.99]", "[0.0, 0.99]"), "internal_transmittance.tau_i[0]", "0.0"},
      {replace("[0.9, 0.99]", "[0.9]"), "internal_transmittance.tau_i", "[0.9]"},
      {replace(R"("thickness_mm": 10)", R"("thickness_mm": -1)"), "internal_transmittance.thickness_mm",
       "-1"},
      {replace("[400, 700]", "[700, 400]"), "internal_transmittance.wavelength_nm[1]", "400"},
      {replace(R"({"nd": 1.5168})", R"({"nd": 1.6})"), "catalogue.nd", "1.6"},
      {replace(R"("name": "test")", R"("name": "test", "sauce": 1)"), "sauce", "1"},
      {R"({"name": "thin", "source": "s", "model": "constant", "n": 0.95})", "n", "0.95"},
      {R"({"name": "thin", "source": "s", "model": "constant", "n": 1.0})", "n", "1.0"},
      {R"({"name": "thin", "source": "s", "model": "constant", "n": "1.5"})", "n", "1.5"},
      // A Sellmeier pole at λ² = C = 0.25 µm² (500 nm) inside the visible range.
      {replace("103.560653]", "0.25]"), "model", ""},
  };
  for (const auto& c : cases) {
    const InputError e = expect_error(c.text);
    EXPECT_EQ(e.key, c.key) << c.text;
    if (!c.value_part.empty()) {
      EXPECT_EQ(e.value, c.value_part) << c.text;
    }
  }
}

TEST_F(MaterialFile, AirMayHaveIndexOne) {
  EXPECT_NO_THROW(load_medium_file(
      write("vac.json", R"({"name": "air", "source": "s", "model": "constant", "n": 1.0})")));
}

TEST_F(MaterialFile, MalformedJsonAndMissingFileAreInputErrors) {
  expect_error(R"({"name": "x", )");
  expect_error("[1, 2]");
  EXPECT_THROW(load_medium_file("/nonexistent/dir/none.json"), InputError);
}

}  // namespace
}  // namespace pmsim
