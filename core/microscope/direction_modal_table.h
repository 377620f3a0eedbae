#pragma once
// A conoscopic figure of one uniform plate is a function of the direction alone: its modal fits on
// a square grid in (k_x, k_y) interpolated bicubically (Catmull–Rom) at each pixel's direction, instead of three
// mode solutions per pixel (the cost of a biaxial figure). What is interpolated are the
// birefringence vectors B_m = Γ·(cos 2θ_m, sin 2θ_m) of both modes (θ_m the mode's angle in
// transverse_basis(k), which is smooth over the aperture) at each anchor: near an optic axis Γ has
// a cusp and the mode directions turn by π around it, but B is smooth there (it is linear in the
// offset from a conical point), and it does not care about the sign a mode was given.
// The table checks itself against exact fits at cell centres and refuses (build() false) when its
// error is above the tolerances stated in build().
#include <atomic>
#include <vector>

#include <glm/vec3.hpp>

#include "core/crystal/plate.h"
#include "core/microscope/modal_fit.h"

namespace pmsim {

class DirectionModalTable {
 public:
  static constexpr int kSide = 53;  // nodes per side, 48 cells across [−s_max, s_max]

  // The number of fits build() computes (nodes of the cells that meet the disk of radius s_max):
  // a caller compares it with the number of fits the table would replace.
  static int nodes_needed(double s_max);

  // Fits the plate (anchors[i] prepared at ModalFit::kAnchorNm[i]) at the nodes, in parallel
  // (TBB), then checks cell centres against exact fits. False when cancelled or when the check
  // fails (then the table must not be used).
  bool build(const PreparedPlate anchors[3], double s_max, const std::atomic<bool>* cancel = nullptr);

  // The fit at direction k_air (unit, k.z > 0, sin θ ≤ s_max).
  ModalFit at(const glm::dvec3& k_air) const;

  // Largest errors of the self-check (|ΔB| in nm, |Δt|), for the bench and the tests.
  double checked_b_error_nm() const { return check_b_nm_; }
  double checked_t_error() const { return check_t_; }

 private:
  struct Node {
    double b1[3][2], b2[3][2];  // [anchor][component] birefringence vectors of e1 and e2 (nm)
    double t1[3], t2[3];
  };
  static Node node_of(const ModalFit& fit);
  void set_grid(double s_max);
  bool fits_aperture() const;
  bool in_reach(int i, int j) const;
  std::vector<Node> n_;
  double s_max_ = 1.0, h_ = 1.0, origin_ = -1.0;
  double check_b_nm_ = 0.0, check_t_ = 0.0;
};

}  // namespace pmsim
