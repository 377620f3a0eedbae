#pragma once
// Wavelength sampling strategies as value types: which wavelengths to evaluate and the weight of
// each, so that ∫_{380}^{780} f(λ) dλ ≈ Σ weight_nm[i]·f(nm[i]). For Monte Carlo strategies
// weight_nm = 1 / (N·pdf) with pdf in 1/nm; for quadratures the weights are the rule's.
#include <cstdint>
#include <vector>

namespace pmsim {

struct SampledWavelengths {
  std::vector<double> nm;         // wavelengths in vacuum
  std::vector<double> pdf;        // sampling density (1/nm); for quadratures 1/(range) for each
  std::vector<double> weight_nm;  // quadrature or Monte Carlo weight
  int size() const { return static_cast<int>(nm.size()); }
};

// The paper's uniform set: n points from 380 to 780 nm inclusive (n = 81: 5 nm steps), trapezoidal
// weights. n ≥ 2.
SampledWavelengths uniform_wavelengths(int n);
// n strata of equal width, one jittered sample in each; u in [0,1)^n supplied by the caller.
SampledWavelengths stratified_wavelengths(int n, const std::vector<double>& u);
// Hero wavelength (Wilkie et al. 2014): one uniform λ_h = 380 + 400·u and n−1 companions at equal
// offsets 400·j/n, wrapped into [380, 780).
SampledWavelengths hero_wavelengths(int n, double u);

}  // namespace pmsim
