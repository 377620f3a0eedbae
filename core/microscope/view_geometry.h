#pragma once
// Where a pixel looks: field coordinates, the stage and the conoscopic mapping of
// docs/conventions.md (field x east, y north, the shorter image side spanning −1…1).
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/microscope/scene.h"

namespace pmsim {

// Pixel position (px to the right, py down, both continuous: pixel centres at i + 0.5).
glm::dvec2 field_from_pixel(int width, int height, double px, double py);
// The same point in the sample frame, i.e. undoing the stage rotation.
glm::dvec2 sample_from_field(const glm::dvec2& f, double stage_deg);
// sample_from_field with the stage angle's cosine and sine computed once (per-pixel loops).
struct StageToSample {
  explicit StageToSample(double stage_deg);
  glm::dvec2 operator()(const glm::dvec2& f) const { return {c * f.x - s * f.y, s * f.x + c * f.y}; }
  double c, s;
};

// Thin sections at physical scale (docs/conventions.md, "Section coordinates"). The diameter of
// the field of view at the specimen is the eyepiece's field number over the objective's
// magnification (the field stop sits in the intermediate image, magnified M× from the specimen);
// the shorter image side spans it.
double field_of_view_mm(const Scene& scene);
// Millimetres of section per pixel of a width × height image: field_of_view_mm / min(width, height).
double mm_per_pixel(const Scene& scene, int width, int height);
// The section point (mm, section coordinates: origin at the section's centre, x east, y north at
// stage 0°) a pixel position shows in orthoscopic view (px to the right, py down, continuous:
// pixel centres at i + 0.5): p = (stage.x_mm, stage.y_mm) + R(−stage_deg)·(f·FOV/2), f the field
// point — the stage turns the section about the point under the crosshair.
glm::dvec2 section_point_from_pixel(const Scene& scene, int width, int height, double px, double py);
// The same map from a field point, with the constants computed once (per-pixel loops).
struct FieldToSection {
  explicit FieldToSection(const Scene& scene);
  glm::dvec2 operator()(const glm::dvec2& f) const {
    const glm::dvec2 g = f * half_fov_mm;
    return centre_mm + rotate(g);
  }
  StageToSample rotate;
  double half_fov_mm;
  glm::dvec2 centre_mm;  // stage.x_mm, stage.y_mm: the point under the crosshair
};

// Conoscopic (Bertrand lens in): the direction in air of the light that reaches back-focal-plane
// point f: sin θ_air = |f|·objective.na, azimuth of f. False outside the disk or beyond the
// condenser NA (unlit).
bool bfp_direction(const Scene& scene, const glm::dvec2& f, glm::dvec3& k_air);
// Its lit test alone, for a back-focal-plane point at distance rho = |f| from the centre.
inline bool bfp_lit(const Scene& scene, double rho) {
  return !(rho > 1.0) && !(rho * scene.objective.na > scene.condenser.na);
}

// Half-width of the field in field units along x (≥ 1).
double field_half_width(int width, int height);

// Wedge: thickness at a sample-frame point, 0 at the left edge of the field (stage 0°) growing
// linearly to thickness_um at the right edge, clamped.
double wedge_thickness_um(const Scene& scene, const glm::dvec2& sample_point);

// ortho + Bertrand in: light parallel to the axis comes to a focus in the back focal plane; the
// spot radius (in sin θ) of the slightly convergent "parallel" beam of a stopped-down condenser.
constexpr double kParallelBeamSinTheta = 0.02;

}  // namespace pmsim
