#pragma once
// An optically isotropic medium (glass, air, oil, mounting medium): spectral refractive index and
// linear attenuation coefficient, as the paper's §1 asks of a lens glass.
//
// Glass indices are the catalogue's, i.e. relative to air (SCHOTT: dry air at 20 °C, 101.325 kPa);
// they reproduce the catalogue n_d. Outside a medium's validity range n() and
// attenuation_per_mm() throw std::out_of_range naming the medium, the wavelength and the range.
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace pmsim {

class Medium {
 public:
  // Dispersion models, each with its formula cited in medium.cpp.
  enum class Model { Constant, Sellmeier3, Cauchy2 };

  const std::string& name() const { return name_; }
  Model model() const { return model_; }
  double n(double wavelength_nm) const;                   // refractive index n(λ)
  double attenuation_per_mm(double wavelength_nm) const;  // μ(λ): Beer–Lambert I = I0·e^(−μx)
  double nd() const { return n(587.5618); }               // helium d line
  // Abbe number v_d = (n_d − 1)/(n_F − n_C), F = 486.1327 nm, C = 656.2725 nm (hydrogen lines).
  double abbe_vd() const;

  static Medium constant(std::string name, double n, double attenuation_per_mm = 0.0);
  static Medium sellmeier(std::string name, const double B[3], const double C_um2[3]);
  // n(λ) = A + B/λ² (λ in nm): a two-term Cauchy fit, for liquids given by n and an Abbe number.
  static Medium cauchy(std::string name, double A, double B_nm2);
  // μ(λ) from tabulated internal transmittance τ_i at thickness d: μ = −ln(τ_i)/d, interpolated.
  // Wavelengths strictly increasing, μ finite and ≥ 0, else std::invalid_argument.
  void set_attenuation_table(std::vector<double> wavelength_nm, std::vector<double> mu_per_mm);
  // A wavelength-independent μ (replaces any table); finite and ≥ 0, else std::invalid_argument.
  void set_attenuation_per_mm(double mu_per_mm);
  // Range in which the dispersion formula is valid (defaults: Sellmeier 310–2500 nm, the SCHOTT
  // catalogue's; Cauchy 380–780 nm; constant: any positive wavelength).
  void set_wavelength_range(double min_nm, double max_nm);
  double min_wavelength_nm() const { return min_nm_; }
  double max_wavelength_nm() const { return max_nm_; }

 private:
  void check_range(double wavelength_nm, const char* what) const;

  std::string name_;
  Model model_ = Model::Constant;
  double n0_ = 1.0;
  double B_[3] = {0, 0, 0}, C_[3] = {0, 0, 0};
  double cauchy_a_ = 1.0, cauchy_b_nm2_ = 0.0;
  double mu_const_per_mm_ = 0.0;
  double min_nm_ = 0.0, max_nm_ = std::numeric_limits<double>::infinity();
  std::vector<double> mu_wl_nm_, mu_per_mm_;
};

// The material library (assets/materials/*.json, or $PMSIM_ASSETS/materials), loaded once. Names:
// "N-BK7", "N-SF11", "N-SF6", "F2", "N-SK16", "air", "oil", "mounting" (case-insensitive). Throws
// InputError for an unknown name, naming it.
const Medium& find_medium(std::string_view name);
// Names of every medium in the library, as written in their files, sorted.
std::vector<std::string> available_media();
// Parses one material file; throws InputError naming the file, key and value on bad input.
Medium load_medium_file(const std::string& path);

}  // namespace pmsim
