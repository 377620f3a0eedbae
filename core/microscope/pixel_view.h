#pragma once
// The view of an evaluation plan: which evaluation units there are (a domain seen in one direction,
// or integrated over the illuminating cone, at one thickness) and which units every pixel shows
// with what weights. One function per view:
//   conoscopic_figure_view    Bertrand lens in, convergent light: the back focal plane, one unit
//                             per lit pixel, in the pixel's direction, of the domain under the
//                             field centre;
//   parallel_light_spot_view  Bertrand lens in, parallel light: the whole field's light focused to
//                             a small spot of sin θ = kParallelBeamSinTheta;
//   field_view                the image plane, in parallel light or lit by the whole cone: one unit
//                             per domain (a uniform plate is ONE spectral evaluation for the whole
//                             field) or per thickness step of a wedge, sub-pixel samples only where
//                             a section's pixel straddles a grain or lamella boundary.
#include <atomic>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "core/microscope/optical_domains.h"
#include "core/microscope/scene.h"

namespace pmsim {

struct EvalUnit {
  int domain = 0;
  double thickness_um = 0.0;
  glm::dvec3 k_air{0.0, 0.0, 1.0};
  bool cone = false;  // integrate over the illuminating cone instead of k_air
};

struct PixelRef {
  int unit = 0;
  float weight = 1.0f;
};

enum class ViewKind { ConoscopicFigure, ParallelLightSpot, Field };

struct PixelView {
  ViewKind kind = ViewKind::Field;
  std::vector<EvalUnit> units;
  std::vector<int> pixel_offset;  // refs of pixel i: [pixel_offset[i], pixel_offset[i+1])
  std::vector<PixelRef> refs;
  std::vector<glm::dvec3> cone_dirs;  // directions (air) of the illuminating cone; empty: none
  int spatial_samples = 1;            // sub-pixel positions per pixel
};

// Each returns nullopt when `cancel` (may be null) is raised while it runs; the per-pixel passes run
// in parallel (TBB) and poll it per row.
std::optional<PixelView> conoscopic_figure_view(const Scene& scene, const OpticalDomains& domains,
                                                const std::atomic<bool>* cancel = nullptr);
PixelView parallel_light_spot_view(const Scene& scene, const OpticalDomains& domains);
std::optional<PixelView> field_view(const Scene& scene, const OpticalDomains& domains,
                                    const std::atomic<bool>* cancel = nullptr);
// The view the scene's mode and Bertrand lens select.
std::optional<PixelView> pixel_view(const Scene& scene, const OpticalDomains& domains,
                                    const std::atomic<bool>* cancel = nullptr);

// Points spread evenly over the disk of radius s_max in the sin θ plane (Vogel's spiral): equal
// areas of the condenser aperture, which a condenser filling its aperture lights evenly.
std::vector<glm::dvec3> cone_directions(int n, double s_max);

}  // namespace pmsim
