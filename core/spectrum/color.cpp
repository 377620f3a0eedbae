#include "core/spectrum/color.h"

#include <algorithm>
#include <cmath>
#include <glm/mat3x3.hpp>

#include "core/base/units.h"

namespace pmsim {

namespace {

// IEC 61966-2-1:1999 §5.2, eq. (7): XYZ (D65, Y = 1) → linear sRGB, as printed (4 decimals).
// glm is column-major: each glm::dvec3 below is a column of the printed matrix.
const glm::dmat3 kXyzToRgb(glm::dvec3(3.2406, -0.9689, 0.0557), glm::dvec3(-1.5372, 1.8758, -0.2040),
                           glm::dvec3(-0.4986, 0.0415, 1.0570));
// Its exact inverse (agrees with the standard's printed eq. (10) to its 4 decimals) so that a
// round trip XYZ → RGB → XYZ is the identity to rounding.
const glm::dmat3 kRgbToXyz = glm::inverse(kXyzToRgb);

}  // namespace

glm::dvec3 xyz_to_linear_srgb(const glm::dvec3& xyz) { return kXyzToRgb * xyz; }
glm::dvec3 linear_srgb_to_xyz(const glm::dvec3& rgb) { return kRgbToXyz * rgb; }

// IEC 61966-2-1 eq. (8): V = 12.92·L for L ≤ 0.0031308, else 1.055·L^(1/2.4) − 0.055.
// Negative input is mirrored (extended-range convention), NaN gives 0.
double srgb_encode(double linear) {
  if (std::isnan(linear)) return 0.0;
  if (linear < 0.0) return -srgb_encode(-linear);
  if (linear <= 0.0031308) return 12.92 * linear;
  return 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// IEC 61966-2-1 eq. (9), the inverse: L = V/12.92 for V ≤ 0.04045, else ((V + 0.055)/1.055)^2.4.
double srgb_decode(double encoded) {
  if (std::isnan(encoded)) return 0.0;
  if (encoded < 0.0) return -srgb_decode(-encoded);
  if (encoded <= 0.04045) return encoded / 12.92;
  return std::pow((encoded + 0.055) / 1.055, 2.4);
}

std::uint8_t linear_to_srgb8(double linear) {
  if (!(linear > 0.0)) return 0;  // also NaN
  if (linear >= 1.0) return 255;
  return static_cast<std::uint8_t>(std::lround(255.0 * srgb_encode(linear)));
}

// CIE 15:2004 §8.2.1: L* = 116 f(Y/Yn) − 16, a* = 500 [f(X/Xn) − f(Y/Yn)],
// b* = 200 [f(Y/Yn) − f(Z/Zn)], f(t) = t^(1/3) for t > (6/29)³, else (841/108)·t + 4/29.
namespace {
double cielab_f(double t) {
  constexpr double eps = 216.0 / 24389.0;  // (6/29)^3
  return t > eps ? std::cbrt(t) : (841.0 / 108.0) * t + 4.0 / 29.0;
}
double lightness_of_f(double fy) { return 116.0 * fy - 16.0; }
}  // namespace

double cielab_lightness(double Y_relative) { return lightness_of_f(cielab_f(Y_relative)); }

glm::dvec3 xyz_to_lab(const glm::dvec3& xyz, const glm::dvec3& white_xyz) {
  const double fx = cielab_f(xyz.x / white_xyz.x);
  const double fy = cielab_f(xyz.y / white_xyz.y);
  const double fz = cielab_f(xyz.z / white_xyz.z);
  return {lightness_of_f(fy), 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

// CIEDE2000 (CIE 142-2001), written as in Sharma, Wu & Dalal, Color Res. Appl. 30 (2005) 21–30,
// eqs. (1)–(22), with k_L = k_C = k_H = 1; hue angles in degrees as in the paper.
double ciede2000(const glm::dvec3& lab1, const glm::dvec3& lab2) {
  constexpr double pi = kPi;
  constexpr double deg = 180.0 / pi;
  constexpr double pow25_7 = 6103515625.0;  // 25^7
  const double L1 = lab1.x, a1 = lab1.y, b1 = lab1.z;
  const double L2 = lab2.x, a2 = lab2.y, b2 = lab2.z;

  const double C1 = std::hypot(a1, b1), C2 = std::hypot(a2, b2);  // (2)
  const double Cbar = 0.5 * (C1 + C2);                            // (3)
  const double Cbar7 = std::pow(Cbar, 7.0);
  const double G = 0.5 * (1.0 - std::sqrt(Cbar7 / (Cbar7 + pow25_7)));  // (4)
  const double a1p = (1.0 + G) * a1, a2p = (1.0 + G) * a2;              // (5)
  const double C1p = std::hypot(a1p, b1), C2p = std::hypot(a2p, b2);    // (6)
  auto hue = [&](double b, double ap) {                                 // (7)
    if (b == 0.0 && ap == 0.0) return 0.0;
    double h = std::atan2(b, ap) * deg;
    return h < 0.0 ? h + 360.0 : h;
  };
  const double h1p = hue(b1, a1p), h2p = hue(b2, a2p);

  const double dLp = L2 - L1;    // (8)
  const double dCp = C2p - C1p;  // (9)
  double dhp = 0.0;              // (10)
  if (C1p * C2p != 0.0) {
    dhp = h2p - h1p;
    if (dhp > 180.0)
      dhp -= 360.0;
    else if (dhp < -180.0)
      dhp += 360.0;
  }
  const double dHp = 2.0 * std::sqrt(C1p * C2p) * std::sin(0.5 * dhp / deg);  // (11)

  const double Lbarp = 0.5 * (L1 + L2);    // (12)
  const double Cbarp = 0.5 * (C1p + C2p);  // (13)
  double hbarp = h1p + h2p;                // (14)
  if (C1p * C2p != 0.0) {
    if (std::abs(h1p - h2p) <= 180.0)
      hbarp *= 0.5;
    else if (h1p + h2p < 360.0)
      hbarp = 0.5 * (hbarp + 360.0);
    else
      hbarp = 0.5 * (hbarp - 360.0);
  }
  const double T = 1.0 - 0.17 * std::cos((hbarp - 30.0) / deg) +  // (15)
                   0.24 * std::cos(2.0 * hbarp / deg) + 0.32 * std::cos((3.0 * hbarp + 6.0) / deg) -
                   0.20 * std::cos((4.0 * hbarp - 63.0) / deg);
  const double dTheta = 30.0 * std::exp(-std::pow((hbarp - 275.0) / 25.0, 2.0));  // (16)
  const double Cbarp7 = std::pow(Cbarp, 7.0);
  const double RC = 2.0 * std::sqrt(Cbarp7 / (Cbarp7 + pow25_7));  // (17)
  const double L50 = (Lbarp - 50.0) * (Lbarp - 50.0);
  const double SL = 1.0 + 0.015 * L50 / std::sqrt(20.0 + L50);  // (18)
  const double SC = 1.0 + 0.045 * Cbarp;                        // (19)
  const double SH = 1.0 + 0.015 * Cbarp * T;                    // (20)
  const double RT = -std::sin(2.0 * dTheta / deg) * RC;         // (21)
  const double tL = dLp / SL, tC = dCp / SC, tH = dHp / SH;
  return std::sqrt(tL * tL + tC * tC + tH * tH + RT * tC * tH);  // (22)
}

}  // namespace pmsim
