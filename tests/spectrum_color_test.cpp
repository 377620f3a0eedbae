// XYZ ↔ sRGB, the sRGB transfer function, CIELAB and CIEDE2000.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"

namespace pmsim {
namespace {

TEST(Srgb, D65WhiteMapsToEqualPrimaries) {
  // IEC 61966-2-1 reference white: D65 with x = 0.3127, y = 0.3290, Y = 1 → R = G = B = 1.
  // The printed 4-decimal matrix reproduces it to ~2e-4.
  const double x = 0.3127, y = 0.3290;
  const glm::dvec3 rgb = xyz_to_linear_srgb({x / y, 1.0, (1.0 - x - y) / y});
  EXPECT_NEAR(rgb.r, 1.0, 5e-4);
  EXPECT_NEAR(rgb.g, 1.0, 5e-4);
  EXPECT_NEAR(rgb.b, 1.0, 5e-4);
}

TEST(Srgb, InverseMatrixMatchesTheStandardsPrintedDecodingMatrix) {
  // IEC 61966-2-1 eq. (10) prints RGB → XYZ with 4 decimals; our exact inverse agrees to 1e-4.
  const double printed[3][3] = {{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
  for (int c = 0; c < 3; ++c) {
    glm::dvec3 e(0.0);
    e[c] = 1.0;
    const glm::dvec3 xyz = linear_srgb_to_xyz(e);
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(xyz[r], printed[r][c], 1e-4) << r << "," << c;
  }
}

TEST(Srgb, RoundTripIsIdentity) {
  const glm::dvec3 xyz(0.2, 0.35, 0.7);
  const glm::dvec3 back = linear_srgb_to_xyz(xyz_to_linear_srgb(xyz));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(back[i], xyz[i], 1e-14);  // rounding only
}

TEST(SrgbTransfer, PiecewiseCurveValuesAndContinuity) {
  // IEC 61966-2-1 eq. (8): linear segment below 0.0031308, power segment above; both pieces meet
  // at 0.04045 (to 1e-7, the standard's rounded breakpoint).
  EXPECT_DOUBLE_EQ(srgb_encode(0.0), 0.0);
  EXPECT_DOUBLE_EQ(srgb_encode(1.0), 1.0);
  EXPECT_DOUBLE_EQ(srgb_encode(0.001), 0.01292);
  EXPECT_NEAR(srgb_encode(0.18), 0.46135612950044164, 1e-15);  // 1.055·0.18^(1/2.4) − 0.055
  EXPECT_NEAR(12.92 * 0.0031308, 1.055 * std::pow(0.0031308, 1 / 2.4) - 0.055, 1e-7);
  EXPECT_NEAR(srgb_encode(0.0031308), 0.04045, 1e-7);
  for (double v = 0.0; v <= 1.0; v += 0.01) EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 1e-12);
  EXPECT_EQ(srgb_encode(std::nan("")), 0.0);
  EXPECT_EQ(srgb_decode(std::nan("")), 0.0);
  EXPECT_DOUBLE_EQ(srgb_encode(-0.18), -srgb_encode(0.18));  // extended-range mirror
}

TEST(Srgb8, ClipsPerChannelRoundsAndMapsNanToBlack) {
  EXPECT_EQ(linear_to_srgb8(0.0), 0);
  EXPECT_EQ(linear_to_srgb8(1.0), 255);
  EXPECT_EQ(linear_to_srgb8(7.5), 255);  // over-exposed: clipped in linear RGB
  EXPECT_EQ(linear_to_srgb8(-0.3), 0);   // out of gamut: clipped
  EXPECT_EQ(linear_to_srgb8(std::nan("")), 0);
  EXPECT_EQ(linear_to_srgb8(std::numeric_limits<double>::infinity()), 255);
  EXPECT_EQ(linear_to_srgb8(0.18), 118);                        // round(255·0.461356) = round(117.65)
  EXPECT_EQ(linear_to_srgb8(0.5), 188);                         // round(255·0.735357) = round(187.52)
  EXPECT_EQ(linear_to_srgb8(srgb_decode(128.0 / 255.0)), 128);  // exact code values survive
}

TEST(Cielab, WhiteIsL100AndNeutralsHaveNoChroma) {
  const glm::dvec3 white = illuminant_white_xyz(Illuminant::D65);
  const glm::dvec3 lab = xyz_to_lab(white, white);
  EXPECT_NEAR(lab.x, 100.0, 1e-12);
  EXPECT_NEAR(lab.y, 0.0, 1e-12);
  EXPECT_NEAR(lab.z, 0.0, 1e-12);
  // 18 % grey: L* = 116·0.18^(1/3) − 16 = 49.496.
  const glm::dvec3 grey = xyz_to_lab(0.18 * white, white);
  EXPECT_NEAR(grey.x, 116.0 * std::cbrt(0.18) - 16.0, 1e-12);
  EXPECT_NEAR(grey.y, 0.0, 1e-12);
  // Dark branch: L* = 903.3·Y for Y ≤ 0.008856 (CIE 15:2004 eq. 8.5, κ = 24389/27).
  const glm::dvec3 dark = xyz_to_lab(0.001 * white, white);
  EXPECT_NEAR(dark.x, 24389.0 / 27.0 * 0.001, 1e-12);
  // Continuity at the branch point (6/29)^3.
  const double t = 216.0 / 24389.0;
  EXPECT_NEAR(xyz_to_lab((t * (1 + 1e-12)) * white, white).x, xyz_to_lab((t * (1 - 1e-12)) * white, white).x,
              1e-8);
}

// Sharma, Wu & Dalal, "The CIEDE2000 color-difference formula: implementation notes,
// supplementary test data, and mathematical observations", Color Res. Appl. 30 (2005) 21–30,
// Table 1: the 34 test pairs (L1 a1 b1 L2 a2 b2 ΔE00).
struct De2000Pair {
  double L1, a1, b1, L2, a2, b2, dE;
};
constexpr De2000Pair kSharmaPairs[34] = {
    {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},
    {50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615},
    {50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412},
    {50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},
    {50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461},
    {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},
    {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},
    {50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977},
    {50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030},
    {50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000},
    {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
    {63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630},
    {61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731},
    {35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645},
    {22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373},
    {36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146},
    {90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441},
    {90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381},
    {6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377},
    {2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082},
};

TEST(Ciede2000, SharmaWuDalalTestPairs) {
  // The paper prints ΔE00 with 4 decimals (rounding ±5e-5); 1e-4 covers that and nothing more.
  // Pairs 9–15 straddle the hue-angle discontinuities the paper designed them to probe.
  for (int i = 0; i < 34; ++i) {
    const auto& p = kSharmaPairs[i];
    const glm::dvec3 lab1(p.L1, p.a1, p.b1), lab2(p.L2, p.a2, p.b2);
    EXPECT_NEAR(ciede2000(lab1, lab2), p.dE, 1e-4) << "pair " << i + 1;
    EXPECT_NEAR(ciede2000(lab2, lab1), p.dE, 1e-4) << "pair " << i + 1 << " swapped";
  }
}

TEST(Ciede2000, IdenticalColoursHaveZeroDifference) {
  EXPECT_EQ(ciede2000({50, 10, -20}, {50, 10, -20}), 0.0);
  EXPECT_EQ(ciede2000({0, 0, 0}, {0, 0, 0}), 0.0);  // achromatic: hue undefined, no NaN
  // Pure lightness difference at L̄ = 50: S_L = 1, so ΔE00 = ΔL.
  EXPECT_NEAR(ciede2000({49, 0, 0}, {51, 0, 0}), 2.0, 1e-12);
}

}  // namespace
}  // namespace pmsim
