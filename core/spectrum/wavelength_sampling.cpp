#include "core/spectrum/wavelength_sampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/spectrum/cie.h"

namespace pmsim {

namespace {

constexpr double kRangeNm = kVisibleMaxNm - kVisibleMinNm;

void require_unit_interval(double u, const char* who) {
  if (!(u >= 0.0 && u < 1.0)) {
    throw std::invalid_argument(std::string(who) + ": random number " + std::to_string(u) +
                                " outside [0, 1)");
  }
}

}  // namespace

// Composite trapezoid rule on n equally spaced nodes including both ends: weights h/2, h, …, h/2.
SampledWavelengths uniform_wavelengths(int n) {
  if (n < 2) {
    throw std::invalid_argument("uniform_wavelengths: need n >= 2 points, got " + std::to_string(n));
  }
  SampledWavelengths s;
  const double h = kRangeNm / (n - 1);
  for (int i = 0; i < n; ++i) {
    s.nm.push_back(i == n - 1 ? kVisibleMaxNm : kVisibleMinNm + h * i);
    s.pdf.push_back(1.0 / kRangeNm);
    s.weight_nm.push_back((i == 0 || i == n - 1) ? 0.5 * h : h);
  }
  return s;
}

// Stratified Monte Carlo: λ_i = 380 + (i + u_i)·400/n, uniform pdf 1/400, weight 1/(n·pdf) = 400/n.
SampledWavelengths stratified_wavelengths(int n, const std::vector<double>& u) {
  if (n < 1) {
    throw std::invalid_argument("stratified_wavelengths: need n >= 1, got " + std::to_string(n));
  }
  if (static_cast<int>(u.size()) != n) {
    throw std::invalid_argument("stratified_wavelengths: need " + std::to_string(n) +
                                " random numbers, got " + std::to_string(u.size()));
  }
  SampledWavelengths s;
  const double width = kRangeNm / n;
  for (int i = 0; i < n; ++i) {
    require_unit_interval(u[i], "stratified_wavelengths");
    s.nm.push_back(kVisibleMinNm + width * (i + u[i]));
    s.pdf.push_back(1.0 / kRangeNm);
    s.weight_nm.push_back(width);
  }
  return s;
}

// Hero wavelength sampling (Wilkie, Nawaz, Droske, Weidlich, Hanika, EGSR 2014, eq. 5): the
// companions λ_j = λ_h + 400·j/n wrapped into [380, 780) are each uniformly distributed, so each
// has pdf 1/400 and weight 400/n.
SampledWavelengths hero_wavelengths(int n, double u) {
  if (n < 1) {
    throw std::invalid_argument("hero_wavelengths: need n >= 1, got " + std::to_string(n));
  }
  require_unit_interval(u, "hero_wavelengths");
  SampledWavelengths s;
  for (int j = 0; j < n; ++j) {
    double offset = std::fmod(u + static_cast<double>(j) / n, 1.0);
    if (offset >= 1.0) offset = 0.0;
    // 380 + 400·offset can round up to 780 for offset just below 1; keep the range half-open.
    s.nm.push_back(std::min(kVisibleMinNm + kRangeNm * offset, std::nextafter(kVisibleMaxNm, 0.0)));
    s.pdf.push_back(1.0 / kRangeNm);
    s.weight_nm.push_back(kRangeNm / n);
  }
  return s;
}

}  // namespace pmsim
