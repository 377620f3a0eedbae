#include "core/optics/mueller.h"

#include "core/base/units.h"

namespace pmsim {

namespace {

using cd = std::complex<double>;

// σ_j as row-major 2×2 (see mueller.h).
constexpr std::array<std::array<cd, 4>, 4> kPauli = {{
    {cd(1), cd(0), cd(0), cd(1)},
    {cd(1), cd(0), cd(0), cd(-1)},
    {cd(0), cd(1), cd(1), cd(0)},
    {cd(0), cd(0, -1), cd(0, 1), cd(0)},
}};

Jones2 mul(const Jones2& a, const Jones2& b) {
  return {a[0] * b[0] + a[1] * b[2], a[0] * b[1] + a[1] * b[3], a[2] * b[0] + a[3] * b[2],
          a[2] * b[1] + a[3] * b[3]};
}

Jones2 dagger(const Jones2& a) { return {std::conj(a[0]), std::conj(a[2]), std::conj(a[1]), std::conj(a[3])}; }

cd trace(const Jones2& a) { return a[0] + a[3]; }

Mueller4 mueller_of(const Jones2& j) {
  Mueller4 m{};
  const Jones2 jd = dagger(j);
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k)
      m[std::size_t(4 * i + k)] = 0.5 * std::real(trace(mul(mul(kPauli[std::size_t(i)], j), mul(kPauli[std::size_t(k)], jd))));
  return m;
}

}  // namespace

MuellerBlock mueller_cross_block(const Jones2& a, const Jones2& b) {
  // K_ij = ½ tr(σ_i X_j) with X_j = A σ_j B†, written out for the Pauli matrices: with
  // P^{kl}_pq = A_pk·conj(B_ql), X_0 = P^00 + P^11, X_1 = P^00 − P^11, X_2 = P^01 + P^10, and
  // tr(σ_0 X) = X00 + X11, tr(σ_1 X) = X00 − X11, tr(σ_2 X) = X01 + X10, tr(σ_3 X) = i(X01 − X10).
  // (16 complex products where the matrix form takes ~100: it runs for every branch pair.)
  cd x[3][2][2];
  for (int p = 0; p < 2; ++p)
    for (int q = 0; q < 2; ++q) {
      const cd a0 = a[std::size_t(2 * p)], a1 = a[std::size_t(2 * p + 1)];
      const cd b0 = std::conj(b[std::size_t(2 * q)]), b1 = std::conj(b[std::size_t(2 * q + 1)]);
      const cd p00 = a0 * b0, p11 = a1 * b1, p01 = a0 * b1, p10 = a1 * b0;
      x[0][p][q] = p00 + p11;
      x[1][p][q] = p00 - p11;
      x[2][p][q] = p01 + p10;
    }
  MuellerBlock m{};
  for (std::size_t j = 0; j < 3; ++j) {
    m[j] = 0.5 * std::real(x[j][0][0] + x[j][1][1]);
    m[3 + j] = 0.5 * std::real(x[j][0][0] - x[j][1][1]);
    m[6 + j] = 0.5 * std::real(x[j][0][1] + x[j][1][0]);
    m[9 + j] = -0.5 * std::imag(x[j][0][1] - x[j][1][0]);
  }
  return m;
}

Mueller4 retarder_mueller(double slow_rad, double delta_rad) {
  // Slow axis along x: the slow wave lags, e^{+iδ} relative to the fast one in the e^{+i k n z}
  // convention of the specimen tracer (core/specimen/jones_path.cpp), then rotated to slow_rad.
  const double c = std::cos(slow_rad), s = std::sin(slow_rad);
  const Jones2 r = {cd(c), cd(-s), cd(s), cd(c)}, rt = {cd(c), cd(s), cd(-s), cd(c)};
  const Jones2 d = {std::polar(1.0, 0.5 * delta_rad), cd(0), cd(0), std::polar(1.0, -0.5 * delta_rad)};
  return mueller_of(mul(r, mul(d, rt)));
}

RetarderTerms retarder_terms(double slow_rad) {
  // C(δ) = C0 + cos δ·C1 + sin δ·C2 exactly (its entries are combinations of 1, e^{±iδ}):
  // C(0) = C0 + C1, C(π) = C0 − C1, C(π/2) = C0 + C2.
  const Mueller4 m0 = retarder_mueller(slow_rad, 0.0), mpi = retarder_mueller(slow_rad, kPi),
                 mhalf = retarder_mueller(slow_rad, 0.5 * kPi);
  RetarderTerms t;
  for (std::size_t i = 0; i < 16; ++i) {
    t.c0[i] = 0.5 * (m0[i] + mpi[i]);
    t.c1[i] = 0.5 * (m0[i] - mpi[i]);
    t.c2[i] = mhalf[i] - t.c0[i];
  }
  return t;
}

double analyzer_intensity(const std::array<double, 4>& s, const MuellerBlock& m, const std::array<double, 4>& t) {
  double sum = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) sum += s[std::size_t(i)] * m[std::size_t(3 * i + k)] * t[std::size_t(k)];
  return 0.5 * sum;
}

}  // namespace pmsim
