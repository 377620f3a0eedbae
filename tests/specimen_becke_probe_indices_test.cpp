// The teaching panel's probe of a grain mount (core/specimen/becke_probe.h): the fragment's index
// along the polarizer and, for crossed polars, its two vibration indices for vertical light, both
// from the indicatrix (closed forms for a uniaxial crystal).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "core/crystal/crystal.h"
#include "core/materials/medium.h"
#include "core/microscope/scene.h"
#include "core/specimen/becke_probe.h"
#include "core/specimen/specimen_scene.h"

namespace {

constexpr double kLambdaD = 589.26;

std::unique_ptr<pmsim::SpecimenScene> one_fragment(const pmsim::Crystal& c, const glm::dmat3& orientation) {
  pmsim::FragmentShape shape;  // centred on the stage's origin, under the image centre
  shape.crystal_to_lab = orientation;
  return std::make_unique<pmsim::SpecimenScene>(std::vector<pmsim::FragmentShape>{shape}, c,
                                                pmsim::immersion_liquid(1.54, 0.0), pmsim::find_medium("N-BK7"),
                                                pmsim::find_medium("air"));
}

// Calcite with its optic axis horizontal along the polarizer (E–W): the section ⟂ the microscope
// axis contains c, so its vibration indices are exactly nε and nω (to rounding, 1e-12), and the
// index along the polarizer is nε. With c vertical both are nω (a circular section): the panel
// says the grain stays dark.
TEST(SpecimenBeckeProbe, CrossedPolarIndicesAreTheSectionsPrincipalIndices) {
  const pmsim::Crystal& calcite = pmsim::find_mineral("calcite");
  const glm::dvec3 n = calcite.principal_indices(kLambdaD);  // (nω, nω, nε)
  pmsim::Scene scene;  // stage at 0, polarizer 0° (E–W), analyzer in
  {
    const auto s = one_fragment(calcite, pmsim::uniaxial_orientation({1.0, 0.0, 0.0}));
    const pmsim::BeckeProbe p = pmsim::probe_becke_line(*s, scene, 0.5, 0.5);
    ASSERT_TRUE(p.on_fragment);
    EXPECT_NEAR(p.mineral_n, n.z, 1e-12);
    EXPECT_NEAR(p.n_fast, n.z, 1e-12);
    EXPECT_NEAR(p.n_slow, n.x, 1e-12);
    EXPECT_NE(pmsim::describe_crossed_polars(p).find("two waves"), std::string::npos);
  }
  {
    const auto s = one_fragment(calcite, pmsim::uniaxial_orientation({0.0, 0.0, 1.0}));
    const pmsim::BeckeProbe p = pmsim::probe_becke_line(*s, scene, 0.5, 0.5);
    ASSERT_TRUE(p.on_fragment);
    EXPECT_NEAR(p.n_fast, n.x, 1e-12);
    EXPECT_NEAR(p.n_slow, n.x, 1e-12);
    EXPECT_NE(pmsim::describe_crossed_polars(p).find("dark at every stage angle"), std::string::npos);
  }
}

}  // namespace
