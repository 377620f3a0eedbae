#pragma once
// A uniaxial plate with its optic axis along the stage normal is symmetric about it: at any
// direction its modes vibrate radially (e) and tangentially (o), and Γ and the transmissions depend
// on sin θ alone. A conoscopic figure then needs a table of fits over sin²θ (in which Γ is nearly
// linear: Γ ≈ d·Δn·sin²θ/(2n) near the axis), each turned to its pixel's azimuth, instead of three
// mode solutions per pixel. Linear interpolation error ≈ h²/8·Γ'' ≈ 0.01 nm of Γ for 1 mm calcite
// at NA 0.85 with 1025 entries: 1e-4 rad of interference phase at 400 nm.
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/crystal/plate.h"
#include "core/microscope/modal_fit.h"

namespace pmsim {

class RadialModalTable {
 public:
  static constexpr int kEntries = 1025;

  // Fits the plate (anchors[i] prepared at ModalFit::kAnchorNm[i]) at kEntries directions evenly
  // spaced in sin²θ up to s_max, in parallel (TBB). False when the fits are not radial/tangential
  // (then the table must not be used).
  bool build(const PreparedPlate anchors[3], double s_max);

  // The fit at direction k_air (unit, k.z > 0), interpolated in sin²θ and turned to its azimuth.
  ModalFit at(const glm::dvec3& k_air) const;

 private:
  struct Entry {
    double gamma[3], t1[3], t2[3];
    glm::dvec2 e1[3], e2[3];  // (radial, tangential) components
  };
  std::vector<Entry> e_;
  double du_ = 1.0;
};

}  // namespace pmsim
