#include "core/microscope/figure_info.h"

#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "core/base/units.h"
#include "core/crystal/opacity.h"
#include "core/microscope/evaluation_plan.h"
#include "core/spectrum/reference_wavelengths.h"

namespace pmsim {

namespace {
// Angle between an axis (either sense) and the microscope axis z.
double tilt_deg(const glm::dvec3& v) {
  return degrees(std::acos(std::min(1.0, std::fabs(glm::normalize(v).z))));
}
std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}
}  // namespace

FigureInfo describe_figure(const Scene& scene_in) {
  Scene scene = scene_in;
  scene.render.width = scene.render.height = 8;
  scene.render.spp = 1;
  scene.render.strategy = RenderStrategy::Exact;
  const auto plan = compile_evaluation_plan(scene);
  const int dom = std::max(0, domain_at_image_point(*plan, 0.5, 0.5));
  const OpticalDomain& D = plan->domains()[dom];
  FigureInfo f;
  f.mineral = D.mineral;
  if (!D.crystal) {
    f.kind = "empty stage";
    f.summary = "empty stage: no figure";
    return f;
  }
  if (is_opaque(*D.crystal, D.thickness_um)) {
    // Magnetite, ilmenite: no light reaches the Bertrand lens, whatever the crystal's symmetry.
    f.kind = "opaque";
    f.orientation = "no interference figure (opaque: no light passes)";
    f.summary = f.mineral + ": opaque, " + f.orientation;
    return f;
  }
  const glm::dmat3& R = D.crystal_to_lab;  // columns X, Y, Z in the lab (stage applied)
  const glm::dvec3 n = D.crystal->principal_indices(kMineralTableDNm);
  const std::string comp = scene.compensator == Compensator::Gypsum        ? "gypsum plate"
                           : scene.compensator == Compensator::Mica        ? "mica plate"
                           : scene.compensator == Compensator::QuartzWedge ? "quartz wedge"
                                                                           : "a compensator";
  const bool gypsum_like = scene.compensator != Compensator::QuartzWedge;
  const std::string add =
      gypsum_like ? "addition (colours rise: blue with gypsum)" : "addition (isochromes move in)";
  const std::string sub =
      gypsum_like ? "subtraction (colours fall: yellow with gypsum)" : "subtraction (isochromes move out)";
  switch (D.crystal->symmetry()) {
    case CrystalSymmetry::Isotropic:
      f.kind = "isotropic";
      f.orientation = "no interference figure (extinct in every position)";
      break;
    case CrystalSymmetry::Uniaxial: {
      f.kind = "uniaxial";
      const bool positive = n.z > n.x;
      f.optic_sign = positive ? "positive" : "negative";
      f.axis_tilt_deg = tilt_deg(R[2]);
      const double sin_e = n.x * std::sin(radians(f.axis_tilt_deg));
      f.orientation = f.axis_tilt_deg < 5          ? "centred optic-axis figure"
                      : sin_e < scene.objective.na ? "off-centre optic-axis figure (melatope in the field)"
                      : f.axis_tilt_deg > 75       ? "flash figure (optic axis near the stage plane)"
                                                   : "off-centre figure (melatope outside the field)";
      // In the NE and SW quadrants the extraordinary wave vibrates radially, i.e. NE–SW, parallel
      // to the accessory's slow direction; it is the slow wave when the crystal is positive.
      f.compensator = (positive ? add : sub) + " in the NE and SW quadrants, " + (positive ? sub : add) +
                      " in NW and SE → " + f.optic_sign;
      break;
    }
    case CrystalSymmetry::Biaxial: {
      f.kind = "biaxial";
      const double two_vz = optic_angle_2v_rad(n.x, n.y, n.z);
      const bool positive = two_vz < kPi / 2;
      f.optic_sign = positive ? "positive" : "negative";
      f.two_v_deg = degrees(positive ? two_vz : kPi - two_vz);
      const glm::dvec3 bxa = positive ? R[2] : R[0], bxo = positive ? R[0] : R[2];
      f.axis_tilt_deg = tilt_deg(bxa);
      const double v = 0.5 * (positive ? two_vz : kPi - two_vz);
      const double a1 = tilt_deg(std::cos(v) * bxa + std::sin(v) * bxo);
      const double a2 = tilt_deg(std::cos(v) * bxa - std::sin(v) * bxo);
      if (f.axis_tilt_deg < 10)
        f.orientation = "acute bisectrix figure";
      else if (std::min(a1, a2) < 10)
        f.orientation = "optic-axis figure";
      else if (tilt_deg(bxo) < 10)
        f.orientation = "obtuse bisectrix figure";
      else if (tilt_deg(R[1]) < 10)
        f.orientation = "optic normal (flash) figure";
      else
        f.orientation = "off-centre figure";
      // Around the acute bisectrix the slow vibration is Y (⟂ the optic-axial plane) for a
      // positive crystal and Z (in the plane) for a negative one.
      const double oap_deg = degrees(std::atan2(bxo.y, bxo.x));
      double turn = std::fmod(45.0 - oap_deg, 180.0);
      if (turn < 0) turn += 180.0;
      f.compensator = "with the optic-axial plane NE–SW (turn the stage by " + fmt("%.0f", turn) +
                      "°): " + (positive ? sub : add) + " between the isogyres, " + (positive ? add : sub) +
                      " outside → " + f.optic_sign;
      break;
    }
  }
  if (scene.compensator == Compensator::None) f.compensator = "insert " + comp + ": " + f.compensator;
  f.summary = f.mineral + ": " + f.kind + (f.optic_sign.empty() ? "" : " " + f.optic_sign) +
              (f.kind == "biaxial" ? ", 2V = " + fmt("%.0f", f.two_v_deg) + "°" : "") + ", " + f.orientation +
              (f.compensator.empty() ? "" : "; " + f.compensator);
  return f;
}

}  // namespace pmsim
