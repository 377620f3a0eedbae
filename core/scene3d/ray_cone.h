#pragma once
// The ray-cone experiment of the paper's section 8 (Fig. 6, Tables 1 and 2). A camera C on the
// axis of a lens (height OC above the reference point O, or at infinity) sends rays at the lens;
// the cone radius Rc at level O is as large as possible while every path, from the entry P1 to
// the fifth internal node P6 (Fig. 5, dT = 5), stays off the ledge. Inside that cone the branches
// Out4 and Out6 (two and four internal reflections) are compared with the direct Out2:
// η4 = I4/I, η6 = I6/I, I = I2 + I4 + I6, each path lit with the same I0 behind the lens
// (natural light: the ⟂ and ∥ halves traced separately by the SML and added).
//
// The lens is a body of revolution and the camera is on its axis, so every ray stays in its
// meridional plane: sampling the radius at level O along one half-line covers the whole cone.
#include <limits>
#include <string>

#include "core/lens/lens.h"

namespace pmsim {

struct RayConeSetup {
  enum class Form { PlanoConvex, Biconvex };
  enum class Reference { CameraSideVertex, CameraSideRim };
  Form form = Form::PlanoConvex;
  bool curved_side_to_camera = true;  // plano-convex: which face looks at the camera
  Reference reference = Reference::CameraSideRim;
  std::string glass = "N-SF11";
  double wavelength_nm = 587.5618;
  double sphere_radius_mm = 8.0;  // Rs
  double lens_radius_mm = 4.25;   // RL
  double ledge_mm = 0.3;
  double camera_height_mm = std::numeric_limits<double>::infinity();  // OC
  int max_depth = 5;                                                  // dT
  // Intensities: the SML's default mode 1 (TIR ends the branch, paper §7) or mode 2 (split).
  // The cleanliness of a path is always judged on its geometry, TIR or not.
  // Paths without a direct image (TIR at P2, I2 = 0) are left out of the η4, η6 maxima: their
  // ratios would describe a ghost only, not a correction to an image.
  bool tir_stops_intensity = false;
};

// Lens of the setup: axis +z, camera on the +z side looking down −z, centre at the origin.
LensSpec ray_cone_lens(const RayConeSetup& s);
// z of the reference point O on the axis.
double ray_cone_reference_z(const RayConeSetup& s);

struct RayConePath {
  bool clean = false;                   // enters the lens and reaches P6 without touching the ledge
  double I2 = 0.0, I4 = 0.0, I6 = 0.0;  // intensities of Out2, Out4, Out6 for I0 = 1
  double eta4() const { return I2 + I4 + I6 > 0.0 ? I4 / (I2 + I4 + I6) : 0.0; }
  double eta6() const { return I2 + I4 + I6 > 0.0 ? I6 / (I2 + I4 + I6) : 0.0; }
};
// The path of the ray aimed at radius r_mm at level O.
RayConePath trace_ray_cone_path(const Lens& lens, const RayConeSetup& s, double r_mm);

struct RayConeResult {
  double eta = 0.0;       // Rc/RL: largest cone whose sampled paths are all clean
  double eta4_max = 0.0;  // max over the clean paths in that cone
  double eta6_max = 0.0;
  int samples = 0;
};
// Samples r = RL·k/(samples−1), k = 0…samples−1, at level O.
RayConeResult ray_cone(const RayConeSetup& s, int samples = 2001);
// Maxima of η4, η6 over a cone of given η (paper: "recalculating ... for a cone with η = 20%").
RayConeResult ray_cone_at(const RayConeSetup& s, double eta, int samples = 2001);

}  // namespace pmsim
