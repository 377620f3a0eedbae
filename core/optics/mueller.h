#pragma once
// Stokes vectors and Mueller matrices of the instrument's polarizing elements, and the Mueller
// block a pair of Jones matrices adds to a partially coherent sum (docs/physics.md, "One response,
// many settings").
//
// Conventions (Born & Wolf §10.8; Goldstein, Polarized Light, 3rd ed., ch. 5–6): a field
// E = (E_x, E_y) in the lab (or specimen) frame; the coherency matrix ρ = E E† = ½ Σ_j S_j σ_j with
// σ_0 = 1, σ_1 = diag(1, −1) (Q: x minus y), σ_2 = [[0, 1], [1, 0]] (U: +45° minus −45°),
// σ_3 = [[0, −i], [i, 0]] (V), so S_j = tr(ρ σ_j). A Jones matrix J acts as ρ → J ρ J†; its Mueller
// matrix is M_ij = ½ tr(σ_i J σ_j J†) (Azzam & Bashara ch. 2). For two Jones matrices A, B (two
// branches of one path, summed with coherence γ) the cross term A ρ B† has the matrix
// K(A, B)_ij = ½ tr(σ_i A σ_j B†); Re(h† A p (h† B p)*) = ½ Σ_ij s_i Re K_ij t_j for a real Stokes
// pair (s of the analyzer's state h, t of the input p), so Re K is what a branch's share adds.
//
// Linear polarizers only on the input side (t_3 = 0): a block holds rows I, Q, U, V (V is needed
// once a retarder follows the specimen) and columns I, Q, U: 12 numbers.
#include <array>
#include <cmath>
#include <complex>

namespace pmsim {

using Jones2 = std::array<std::complex<double>, 4>;  // row-major [[a, b], [c, d]]
using MuellerBlock = std::array<double, 12>;        // row-major, rows I Q U V, columns I Q U
using Mueller4 = std::array<double, 16>;            // row-major 4×4

// Re K(A, B) restricted to columns I, Q, U (see above); K(A, A) is A's Mueller matrix.
MuellerBlock mueller_cross_block(const Jones2& a, const Jones2& b);

// The Stokes vector (I, Q, U, V) of unit power behind an ideal linear polarizer at angle_rad
// from +x: (1, cos 2ψ, sin 2ψ, 0).
inline std::array<double, 4> linear_stokes(double angle_rad) {
  return {1.0, std::cos(2.0 * angle_rad), std::sin(2.0 * angle_rad), 0.0};
}

// The Mueller matrix of a linear retarder of retardance delta_rad whose slow axis lies at
// slow_rad from +x (from its Jones matrix R(ψ)·diag(e^{iδ/2}, e^{−iδ/2})·R(−ψ)): written as
// C0 + cos δ·C1 + sin δ·C2 with C0, C1, C2 depending on the axis only, so that a spectrum of
// retardances is summed as three weighted sums (core/specimen/specimen_response.h).
struct RetarderTerms {
  Mueller4 c0{}, c1{}, c2{};
};
RetarderTerms retarder_terms(double slow_rad);
Mueller4 retarder_mueller(double slow_rad, double delta_rad);

// I = ½ sᵀ · M · t for an analyzer state s (Stokes of the light it passes, unit power) and the
// input t: the intensity a block passes (½: an ideal analyzer passes half of unpolarized light).
double analyzer_intensity(const std::array<double, 4>& s, const MuellerBlock& m, const std::array<double, 4>& t);

}  // namespace pmsim
