// Wavelength sampling strategies integrate ∫_{380}^{780} f(λ) dλ and converge as n grows.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "core/spectrum/cie.h"
#include "core/spectrum/wavelength_sampling.h"

namespace pmsim {
namespace {

double integrate(const SampledWavelengths& s, double (*f)(double)) {
  double sum = 0.0;
  for (int i = 0; i < s.size(); ++i) sum += s.weight_nm[i] * f(s.nm[i]);
  return sum;
}

double ybar(double nm) { return cie1931_xyz_bar(nm).y; }
double quadratic(double nm) {
  const double t = (nm - 380.0) / 400.0;
  return t * t;
}
// ∫ t² dλ with t = (λ − 380)/400 over 400 nm = 400/3.
constexpr double kQuadraticIntegral = 400.0 / 3.0;

// ȳ is piecewise linear between 5 nm nodes, so the trapezoid rule on any grid containing those
// nodes is exact: a 0.5 nm grid is the reference.
double ybar_reference() {
  double sum = 0.0;
  for (int i = 0; i <= 800; ++i) sum += ((i == 0 || i == 800) ? 0.25 : 0.5) * ybar(380.0 + 0.5 * i);
  return sum;
}

// Portable uniform [0,1) numbers from a fixed seed (53 random bits).
struct Uniform01 {
  std::mt19937_64 gen;
  explicit Uniform01(unsigned seed) : gen(seed) {}
  double operator()() { return static_cast<double>(gen() >> 11) * 0x1.0p-53; }
};

void expect_consistent(const SampledWavelengths& s, int n) {
  ASSERT_EQ(s.size(), n);
  ASSERT_EQ(s.pdf.size(), s.nm.size());
  ASSERT_EQ(s.weight_nm.size(), s.nm.size());
  double wsum = 0.0;
  for (int i = 0; i < n; ++i) {
    EXPECT_GE(s.nm[i], 380.0);
    EXPECT_LE(s.nm[i], 780.0);
    EXPECT_DOUBLE_EQ(s.pdf[i], 1.0 / 400.0);  // all three strategies sample λ uniformly
    wsum += s.weight_nm[i];
  }
  EXPECT_NEAR(wsum, 400.0, 1e-11);  // ∫1 dλ = 400 nm exactly, up to rounding of n terms
}

TEST(UniformWavelengths, PaperSetIs81PointsAt5nm) {
  const SampledWavelengths s = uniform_wavelengths(81);
  expect_consistent(s, 81);
  for (int i = 0; i < 81; ++i) EXPECT_DOUBLE_EQ(s.nm[i], 380.0 + 5.0 * i);
  EXPECT_DOUBLE_EQ(s.weight_nm[0], 2.5);
  EXPECT_DOUBLE_EQ(s.weight_nm[40], 5.0);
  EXPECT_DOUBLE_EQ(s.weight_nm[80], 2.5);
}

TEST(UniformWavelengths, TrapezoidErrorOnQuadraticIsH2Over2400) {
  // Composite trapezoid error (b−a)·h²·f''/12 with f'' = 2/400² gives exactly h²/2400 nm;
  // the test checks the rule's order, not just smallness (rounding ~1e-13).
  for (int n : {2, 5, 11, 21, 41, 81}) {
    const double h = 400.0 / (n - 1);
    EXPECT_NEAR(integrate(uniform_wavelengths(n), quadratic) - kQuadraticIntegral, h * h / 2400.0, 1e-11)
        << n;
  }
}

TEST(UniformWavelengths, PhotopicCurveConvergesAndIsExactOnTheTableGrid) {
  const double ref = ybar_reference();
  // CIE 15:2004: Σ ȳ·Δλ over 380–780 nm at 5 nm is 106.857 (the known 683/K_m-free "∫ȳ").
  EXPECT_NEAR(ref, 106.857, 1e-3);
  double previous = 1e9;
  for (int n : {11, 21, 41}) {
    const double err = std::abs(integrate(uniform_wavelengths(n), ybar) - ref);
    EXPECT_LT(err, previous) << n;
    previous = err;
  }
  EXPECT_NEAR(integrate(uniform_wavelengths(81), ybar), ref, 1e-12);  // grid contains every node
}

// Root-mean-square error of a Monte Carlo strategy over many fixed-seed trials.
template <class Make>
double rms_error(Make make, double (*f)(double), double exact, int trials) {
  double sq = 0.0;
  for (int t = 0; t < trials; ++t) {
    const double e = integrate(make(t), f) - exact;
    sq += e * e;
  }
  return std::sqrt(sq / trials);
}

SampledWavelengths stratified_seeded(int n, int trial) {
  Uniform01 rng(1000u + static_cast<unsigned>(trial));
  std::vector<double> u(n);
  for (double& x : u) x = rng();
  return stratified_wavelengths(n, u);
}

TEST(StratifiedWavelengths, OneSamplePerStratumAndConsistentWeights) {
  const int n = 16;
  const SampledWavelengths s = stratified_seeded(n, 0);
  expect_consistent(s, n);
  for (int i = 0; i < n; ++i) {
    EXPECT_GE(s.nm[i], 380.0 + 25.0 * i);
    EXPECT_LT(s.nm[i], 380.0 + 25.0 * (i + 1));
    EXPECT_DOUBLE_EQ(s.weight_nm[i], 1.0 / (n * s.pdf[i]));  // Monte Carlo weight 1/(N·pdf)
  }
}

TEST(StratifiedWavelengths, ErrorFallsLikeNToTheMinus1Point5) {
  // For a smooth integrand one jittered sample per stratum has RMS error ∝ n^(−3/2): going from
  // 8 to 64 samples should divide it by 8^1.5 ≈ 22.6; we require > 12 (statistical margin of
  // 400 trials), which plain Monte Carlo (ratio ≈ 2.8) would fail.
  for (auto f : {quadratic, ybar}) {
    const double exact = f == quadratic ? kQuadraticIntegral : ybar_reference();
    const double e8 = rms_error([](int t) { return stratified_seeded(8, t); }, f, exact, 400);
    const double e64 = rms_error([](int t) { return stratified_seeded(64, t); }, f, exact, 400);
    EXPECT_GT(e8 / e64, 12.0) << "e8 " << e8 << " e64 " << e64;
  }
}

TEST(StratifiedWavelengths, IsUnbiased) {
  // Mean of 2000 estimates within 4 standard errors of the exact integral.
  const double exact = ybar_reference();
  double sum = 0.0, sq = 0.0;
  const int trials = 2000;
  for (int t = 0; t < trials; ++t) {
    const double v = integrate(stratified_seeded(4, t), ybar);
    sum += v;
    sq += v * v;
  }
  const double mean = sum / trials, sd = std::sqrt(sq / trials - mean * mean);
  EXPECT_NEAR(mean, exact, 4.0 * sd / std::sqrt(trials));
}

SampledWavelengths hero_seeded(int n, int trial) {
  Uniform01 rng(5000u + static_cast<unsigned>(trial));
  return hero_wavelengths(n, rng());
}

TEST(HeroWavelengths, EquallySpacedCompanionsWrapIntoRange) {
  const SampledWavelengths s = hero_wavelengths(4, 0.9);  // hero at 740 nm
  expect_consistent(s, 4);
  EXPECT_DOUBLE_EQ(s.nm[0], 740.0);
  EXPECT_NEAR(s.nm[1], 440.0, 1e-12);  // 740 + 100 wraps to 440
  EXPECT_NEAR(s.nm[2], 540.0, 1e-12);
  EXPECT_NEAR(s.nm[3], 640.0, 1e-12);
  for (int i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(s.weight_nm[i], 1.0 / (4 * s.pdf[i]));
  const SampledWavelengths z = hero_wavelengths(3, 0.0);
  EXPECT_DOUBLE_EQ(z.nm[0], 380.0);
  for (double nm : hero_wavelengths(7, std::nextafter(1.0, 0.0)).nm) EXPECT_LT(nm, 780.0);
}

TEST(HeroWavelengths, ErrorShrinksWithCompanionCount) {
  // A randomly shifted equally spaced rule: for t² (whose periodic extension jumps at 780 nm)
  // the RMS error falls like 1/n, so 8 → 64 gains ≈ 8 (require > 5); ȳ vanishes at both ends, so
  // its periodic extension is continuous and the gain is larger (require > 12).
  const double eq8 = rms_error([](int t) { return hero_seeded(8, t); }, quadratic, kQuadraticIntegral, 400);
  const double eq64 = rms_error([](int t) { return hero_seeded(64, t); }, quadratic, kQuadraticIntegral, 400);
  EXPECT_GT(eq8 / eq64, 5.0) << eq8 << " " << eq64;
  const double ref = ybar_reference();
  const double ey8 = rms_error([](int t) { return hero_seeded(8, t); }, ybar, ref, 400);
  const double ey64 = rms_error([](int t) { return hero_seeded(64, t); }, ybar, ref, 400);
  EXPECT_GT(ey8 / ey64, 12.0) << ey8 << " " << ey64;
}

TEST(WavelengthSampling, BadArgumentsThrowInvalidArgument) {
  EXPECT_THROW(uniform_wavelengths(1), std::invalid_argument);
  EXPECT_THROW(uniform_wavelengths(-3), std::invalid_argument);
  EXPECT_THROW(stratified_wavelengths(0, {}), std::invalid_argument);
  EXPECT_THROW(stratified_wavelengths(3, {0.1, 0.2}), std::invalid_argument);
  EXPECT_THROW(stratified_wavelengths(2, {0.1, 1.0}), std::invalid_argument);
  EXPECT_THROW(stratified_wavelengths(2, {-0.1, 0.5}), std::invalid_argument);
  EXPECT_THROW(stratified_wavelengths(1, {std::nan("")}), std::invalid_argument);
  EXPECT_THROW(hero_wavelengths(0, 0.5), std::invalid_argument);
  EXPECT_THROW(hero_wavelengths(4, 1.0), std::invalid_argument);
  EXPECT_THROW(hero_wavelengths(4, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace pmsim
