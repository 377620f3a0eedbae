// Forward-tracing vignetting estimate: closed-form transmission on the axis, no light from a
// field point whose cone misses the lens, and the shipped objective loaded from its file.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/base/input_error.h"
#include "core/scene3d/vignetting.h"

namespace pmsim {
namespace {

Objective single_lens(double na) {
  Objective o;
  LensSpec s;
  s.glass = "N-SF11";
  s.center = glm::dvec3(0, 0, 10);
  s.radius_mm = 3.0;
  s.front_radius_mm = 20.0;
  s.back_radius_mm = -20.0;
  s.ledge_mm = 1.0;
  o.lenses = {s};
  o.object_z_mm = 0.0;
  o.na = na;
  o.field_max_mm = 20.0;
  return o;
}

TEST(Vignetting, OnAxisNarrowConeTransmitsTwoFresnelFactorsAndBeerLambert) {
  // NA 1e-4: every ray is within 1e-4 rad of normal incidence at both vertices, where
  // T = 1 − ((n − 1)/(n + 1))² (Born & Wolf 1.5 (21)) and the path is the vertex thickness t:
  // power = (1 − R)²·e^(−μt). The cone's spread changes T by O(θ²) ~ 1e-8.
  const Objective o = single_lens(1e-4);
  const Lens lens(o.lenses[0]);
  const LensMedia m = lens.media(o.wavelength_nm);
  const double R = std::pow((m.n_glass - 1.0) / (m.n_glass + 1.0), 2);
  const double t = lens.geometry().thickness_mm();
  const auto v = vignetting(o, 1, 8);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_DOUBLE_EQ(v[0].passed, 1.0);
  EXPECT_NEAR(v[0].transmitted, (1 - R) * (1 - R) * std::exp(-m.attenuation_per_mm * t), 1e-6);
}

TEST(Vignetting, FieldPointOutsideTheApertureIsFullyVignetted) {
  // From x = 20 mm with NA 0.05 the cone reaches at most 20 − 10·tan(asin 0.05) ≈ 19.5 mm from
  // the axis at the lens, far outside its 3 mm aperture: nothing passes.
  const auto v = vignetting(single_lens(0.05), 2, 8);
  EXPECT_DOUBLE_EQ(v[0].passed, 1.0);  // on the axis the 0.5 mm wide cone fits the aperture
  EXPECT_DOUBLE_EQ(v[1].passed, 0.0);
  EXPECT_DOUBLE_EQ(v[1].transmitted, 0.0);
}

TEST(Vignetting, ShippedObjectiveVignettesTowardTheFieldEdge) {
  const std::string file = std::string(PMSIM_SOURCE_DIR) + "/assets/scenes3d/objective_vignetting.json";
  std::ifstream in(file);
  const Objective o = objective_from_json(nlohmann::json::parse(in), file);
  const auto v = vignetting(o, 6, 24);
  EXPECT_DOUBLE_EQ(v.front().passed, 1.0);
  EXPECT_LT(v.back().passed, v.front().passed);
  for (std::size_t i = 1; i < v.size(); ++i) EXPECT_LE(v[i].passed, v[i - 1].passed + 1e-12);
}

TEST(Vignetting, BadObjectiveNamesTheKey) {
  nlohmann::json j = {{"type", "objective"}, {"na", 1.5}, {"lenses", nlohmann::json::array()}};
  try {
    objective_from_json(j, "obj.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "na");
    EXPECT_EQ(e.file, "obj.json");
  }
}

}  // namespace
}  // namespace pmsim
