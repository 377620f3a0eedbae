// render.vision's matrices (core/spectrum/colour_vision.h) against what they model: Machado et al.
// (2009) keep white white, and a dichromat (protanope, deuteranope) sees a two-dimensional colour
// space, so Φ has rank 2; the model's strongest tritanomaly is not a dichromacy.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "core/spectrum/colour_vision.h"

using pmsim::ColourVision;

namespace {
const ColourVision kAll[] = {ColourVision::Normal, ColourVision::Protanopia, ColourVision::Deuteranopia,
                             ColourVision::Tritanopia};
}

// Φ·(1, 1, 1) = (1, 1, 1): an achromatic stimulus stays achromatic. The published entries have
// six decimals, so a row sum is off by at most 3 × 0.5e-6 = 1.5e-6.
TEST(ColourVision, WhiteStaysWhite) {
  for (ColourVision v : kAll) {
    const glm::dvec3 w = pmsim::colour_vision_matrix(v) * glm::dvec3(1.0);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(w[c], 1.0, 1.5e-6) << pmsim::colour_vision_name(v) << " channel " << c;
  }
}

// Dichromacy projects onto a plane: det Φ = 0. Rounding the nine entries to 1e-6 moves the
// determinant by at most Σ|cofactor| × 0.5e-6 (< 2e-6 for these matrices, whose cofactors are < 1.5).
TEST(ColourVision, ProtanopesAndDeuteranopesSeeAPlaneOfColours) {
  EXPECT_NEAR(glm::determinant(pmsim::colour_vision_matrix(ColourVision::Protanopia)), 0.0, 2e-6);
  EXPECT_NEAR(glm::determinant(pmsim::colour_vision_matrix(ColourVision::Deuteranopia)), 0.0, 2e-6);
  // Machado's tritan model at full severity (a 20 nm shift of the S cone) keeps three dimensions.
  EXPECT_GT(glm::determinant(pmsim::colour_vision_matrix(ColourVision::Tritanopia)), 0.1);
  EXPECT_EQ(pmsim::colour_vision_matrix(ColourVision::Normal), glm::dmat3(1.0));
}

TEST(ColourVision, NamesRoundTripAndUnknownNamesAreRefused) {
  for (ColourVision v : kAll) {
    ColourVision back = ColourVision::Normal;
    ASSERT_TRUE(pmsim::parse_colour_vision(pmsim::colour_vision_name(v), back));
    EXPECT_EQ(back, v);
  }
  ColourVision v = ColourVision::Protanopia;
  EXPECT_FALSE(pmsim::parse_colour_vision("colourblind", v));
  EXPECT_EQ(v, ColourVision::Protanopia);
}
