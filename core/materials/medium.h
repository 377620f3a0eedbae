#pragma once
// An optically isotropic medium (glass, air, oil, mounting medium): spectral refractive index and
// linear attenuation coefficient, as the paper's §1 asks of a lens glass.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace pmsim {

class Medium {
 public:
  // Dispersion models, each with its formula cited in medium.cpp.
  enum class Model { Constant, Sellmeier3 };

  const std::string& name() const { return name_; }
  double n(double wavelength_nm) const;                   // refractive index n(λ)
  double attenuation_per_mm(double wavelength_nm) const;  // μ(λ): Beer–Lambert I = I0·e^(−μx)
  double nd() const { return n(587.5618); }               // helium d line

  static Medium constant(std::string name, double n, double attenuation_per_mm = 0.0);
  static Medium sellmeier(std::string name, const double B[3], const double C_um2[3]);
  // μ(λ) from tabulated internal transmittance τ_i at thickness d: μ = −ln(τ_i)/d, interpolated.
  void set_attenuation_table(std::vector<double> wavelength_nm, std::vector<double> mu_per_mm);

 private:
  std::string name_;
  Model model_ = Model::Constant;
  double n0_ = 1.0;
  double B_[3] = {0, 0, 0}, C_[3] = {0, 0, 0};
  std::vector<double> mu_wl_nm_, mu_per_mm_;
};

// The material library (assets/materials/*.json), loaded once. Names: "N-BK7", "N-SF11", "N-SF6",
// "F2", "N-SK16", "air", "oil", "mounting" (case-insensitive). Throws InputError for an unknown
// name, naming it.
const Medium& find_medium(std::string_view name);
// Parses one material file; throws InputError naming the file, key and value on bad input.
Medium load_medium_file(const std::string& path);

}  // namespace pmsim
