#include "core/materials/medium.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/optics/cauchy.h"

namespace pmsim {

namespace {

std::string format_nm(double nm) {
  std::ostringstream s;
  s << nm;
  return s.str();
}

}  // namespace

void Medium::check_range(double wavelength_nm, const char* what) const {
  if (!(wavelength_nm > 0.0 && wavelength_nm >= min_nm_ && wavelength_nm <= max_nm_)) {
    throw std::out_of_range(name_ + ": " + what + " at wavelength " + format_nm(wavelength_nm) +
                            " nm is outside the data range " + format_nm(min_nm_) + "-" + format_nm(max_nm_) +
                            " nm");
  }
}

double Medium::n(double wavelength_nm) const {
  check_range(wavelength_nm, "refractive index");
  switch (model_) {
    case Model::Constant:
      return n0_;
    case Model::Sellmeier3: {
      // SCHOTT TIE-29 / catalogue formula: n² − 1 = Σ_i B_i·λ²/(λ² − C_i), λ in µm.
      const double l2 = wavelength_nm * wavelength_nm * 1e-6;
      double s = 1.0;
      for (int i = 0; i < 3; ++i) s += B_[i] * l2 / (l2 - C_[i]);
      return std::sqrt(s);
    }
    case Model::Cauchy2:
      return cauchy_index(cauchy_a_, cauchy_b_nm2_, 0.0, wavelength_nm);  // two terms, λ in nm
  }
  return n0_;
}

double Medium::abbe_vd() const { return (nd() - 1.0) / (n(486.1327) - n(656.2725)); }

double Medium::attenuation_per_mm(double wavelength_nm) const {
  check_range(wavelength_nm, "attenuation");
  if (mu_wl_nm_.empty()) return mu_const_per_mm_;
  if (!(wavelength_nm >= mu_wl_nm_.front() && wavelength_nm <= mu_wl_nm_.back())) {
    throw std::out_of_range(name_ + ": attenuation at wavelength " + format_nm(wavelength_nm) +
                            " nm is outside the transmittance data " + format_nm(mu_wl_nm_.front()) + "-" +
                            format_nm(mu_wl_nm_.back()) + " nm");
  }
  if (mu_wl_nm_.size() == 1) return mu_per_mm_.front();
  // Linear interpolation of μ between the catalogue's wavelengths.
  const auto it = std::upper_bound(mu_wl_nm_.begin(), mu_wl_nm_.end(), wavelength_nm);
  const std::size_t hi = std::min<std::size_t>(it - mu_wl_nm_.begin(), mu_wl_nm_.size() - 1);
  const std::size_t lo = hi - 1;
  const double f = (wavelength_nm - mu_wl_nm_[lo]) / (mu_wl_nm_[hi] - mu_wl_nm_[lo]);
  return mu_per_mm_[lo] + f * (mu_per_mm_[hi] - mu_per_mm_[lo]);
}

Medium Medium::constant(std::string name, double n, double attenuation_per_mm) {
  if (!std::isfinite(n) || n < 1.0)
    throw std::invalid_argument(name + ": refractive index must be finite and >= 1");
  if (!std::isfinite(attenuation_per_mm) || attenuation_per_mm < 0.0) {
    throw std::invalid_argument(name + ": attenuation must be finite and >= 0");
  }
  Medium m;
  m.name_ = std::move(name);
  m.model_ = Model::Constant;
  m.n0_ = n;
  m.mu_const_per_mm_ = attenuation_per_mm;
  return m;
}

Medium Medium::sellmeier(std::string name, const double B[3], const double C_um2[3]) {
  Medium m;
  m.name_ = std::move(name);
  m.model_ = Model::Sellmeier3;
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(B[i]) || !std::isfinite(C_um2[i]) || C_um2[i] < 0.0) {
      throw std::invalid_argument(m.name_ + ": Sellmeier coefficients must be finite, C >= 0");
    }
    m.B_[i] = B[i];
    m.C_[i] = C_um2[i];
  }
  m.min_nm_ = 310.0;
  m.max_nm_ = 2500.0;
  return m;
}

Medium Medium::cauchy(std::string name, double A, double B_nm2) {
  if (!std::isfinite(A) || !std::isfinite(B_nm2)) {
    throw std::invalid_argument(name + ": Cauchy coefficients must be finite");
  }
  Medium m;
  m.name_ = std::move(name);
  m.model_ = Model::Cauchy2;
  m.cauchy_a_ = A;
  m.cauchy_b_nm2_ = B_nm2;
  m.min_nm_ = 380.0;
  m.max_nm_ = 780.0;
  return m;
}

void Medium::set_attenuation_table(std::vector<double> wavelength_nm, std::vector<double> mu_per_mm) {
  if (wavelength_nm.empty() || wavelength_nm.size() != mu_per_mm.size()) {
    throw std::invalid_argument(name_ +
                                ": attenuation table needs equally many (>= 1) wavelengths and values");
  }
  for (std::size_t i = 0; i < wavelength_nm.size(); ++i) {
    if (!std::isfinite(wavelength_nm[i]) || wavelength_nm[i] <= 0.0 ||
        (i > 0 && !(wavelength_nm[i] > wavelength_nm[i - 1]))) {
      throw std::invalid_argument(name_ + ": attenuation wavelengths must be positive and increasing");
    }
    if (!std::isfinite(mu_per_mm[i]) || mu_per_mm[i] < 0.0) {
      throw std::invalid_argument(name_ + ": attenuation coefficients must be finite and >= 0");
    }
  }
  mu_wl_nm_ = std::move(wavelength_nm);
  mu_per_mm_ = std::move(mu_per_mm);
}

void Medium::set_attenuation_per_mm(double mu_per_mm) {
  if (!std::isfinite(mu_per_mm) || mu_per_mm < 0.0) {
    throw std::invalid_argument(name_ + ": attenuation must be finite and >= 0");
  }
  mu_wl_nm_.clear();
  mu_per_mm_.clear();
  mu_const_per_mm_ = mu_per_mm;
}

void Medium::set_wavelength_range(double min_nm, double max_nm) {
  if (!(min_nm > 0.0 && max_nm > min_nm) || std::isnan(max_nm)) {
    throw std::invalid_argument(name_ + ": wavelength range must satisfy 0 < min < max");
  }
  min_nm_ = min_nm;
  max_nm_ = max_nm;
}

}  // namespace pmsim
