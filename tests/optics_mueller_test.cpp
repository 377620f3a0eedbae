// Stokes vectors and Mueller blocks (core/optics/mueller.h) against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "core/base/units.h"
#include "core/optics/mueller.h"

namespace {

using pmsim::kPi;
using cd = std::complex<double>;

pmsim::Jones2 rotation(double a) { return {cd(std::cos(a)), cd(-std::sin(a)), cd(std::sin(a)), cd(std::cos(a))}; }

// A linear retarder of retardance δ with its slow axis at ψ (Jones, slow wave e^{+iδ/2}).
pmsim::Jones2 retarder(double psi, double delta) {
  const pmsim::Jones2 r = rotation(psi), rt = rotation(-psi);
  const pmsim::Jones2 d = {std::polar(1.0, 0.5 * delta), cd(0), cd(0), std::polar(1.0, -0.5 * delta)};
  const auto mul = [](const pmsim::Jones2& a, const pmsim::Jones2& b) {
    return pmsim::Jones2{a[0] * b[0] + a[1] * b[2], a[0] * b[1] + a[1] * b[3], a[2] * b[0] + a[3] * b[2],
                         a[2] * b[1] + a[3] * b[3]};
  };
  return mul(r, mul(d, rt));
}

// Malus: I = cos²(A − P) through nothing between the polars. Rounding only: 1e-14.
TEST(OpticsMueller, IdentityGivesMalusLaw) {
  const pmsim::Jones2 one = {cd(1), cd(0), cd(0), cd(1)};
  const pmsim::MuellerBlock m = pmsim::mueller_cross_block(one, one);
  for (double p = 0.0; p < kPi; p += 0.37)
    for (double a = 0.0; a < kPi; a += 0.41)
      EXPECT_NEAR(pmsim::analyzer_intensity(pmsim::linear_stokes(a), m, pmsim::linear_stokes(p)),
                  std::pow(std::cos(a - p), 2), 1e-14);
}

// A plate of retardance δ at φ between crossed polars: sin²2φ·sin²(δ/2) (Nesse 2012 §7, the
// interference-colour formula). Rounding only: 1e-14.
TEST(OpticsMueller, RetarderBetweenCrossedPolars) {
  for (double phi : {0.0, 0.3, kPi / 4, 1.1})
    for (double delta : {0.5, 2.0, 9.0, 3001.7}) {
      const pmsim::Jones2 j = retarder(phi, delta);
      const double i = pmsim::analyzer_intensity(pmsim::linear_stokes(kPi / 2), pmsim::mueller_cross_block(j, j),
                                                 pmsim::linear_stokes(0.0));
      EXPECT_NEAR(i, std::pow(std::sin(2 * phi) * std::sin(0.5 * delta), 2), 1e-12) << phi << " " << delta;
    }
}

// C(δ) = C0 + cos δ·C1 + sin δ·C2 for every δ, and C equals the Jones retarder's Mueller matrix
// (rows I Q U V, columns I Q U compared with the cross block). Rounding only: 1e-13.
TEST(OpticsMueller, RetarderTermsAreExact) {
  for (double psi : {0.0, kPi / 4, 0.9})
    for (double delta : {0.0, 0.7, 2.5, 40.0}) {
      const pmsim::RetarderTerms t = pmsim::retarder_terms(psi);
      const pmsim::Mueller4 c = pmsim::retarder_mueller(psi, delta);
      const pmsim::Jones2 j = retarder(psi, delta);
      const pmsim::MuellerBlock b = pmsim::mueller_cross_block(j, j);
      for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k) {
          const std::size_t e = std::size_t(4 * i + k);
          EXPECT_NEAR(c[e], t.c0[e] + std::cos(delta) * t.c1[e] + std::sin(delta) * t.c2[e], 1e-13);
          if (k < 3) {
            EXPECT_NEAR(c[e], b[std::size_t(3 * i + k)], 1e-13);
          }
        }
    }
}

// Two branches of one path summed coherently (γ = 1) are one Jones matrix: Re K(A,A) + Re K(B,B)
// + Re K(A,B) + Re K(B,A) = M(A + B). Rounding only: 1e-13.
TEST(OpticsMueller, CrossTermsSumToTheCoherentMatrix) {
  const pmsim::Jones2 a = {cd(0.3, 0.1), cd(-0.2, 0.4), cd(0.05, -0.3), cd(0.6, 0.2)};
  const pmsim::Jones2 b = {cd(-0.1, 0.2), cd(0.3, 0.0), cd(0.2, 0.25), cd(-0.4, 0.1)};
  pmsim::Jones2 s{};
  for (std::size_t i = 0; i < 4; ++i) s[i] = a[i] + b[i];
  const pmsim::MuellerBlock whole = pmsim::mueller_cross_block(s, s);
  const pmsim::MuellerBlock aa = pmsim::mueller_cross_block(a, a), bb = pmsim::mueller_cross_block(b, b),
                            ab = pmsim::mueller_cross_block(a, b), ba = pmsim::mueller_cross_block(b, a);
  for (std::size_t i = 0; i < 12; ++i) EXPECT_NEAR(whole[i], aa[i] + bb[i] + ab[i] + ba[i], 1e-13);
}

}  // namespace
