#include "core/ebsd/ebsd_frames.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace pmsim {

namespace {

enum class AxisX { A, AStar };
enum class AxisZ { C, CStar };

// The frame with x along a or a*, z along c or c*, y = z × x, in pmsim's crystal frame.
glm::dmat3 frame_from_axes(const UnitCell& cell, AxisX ax, AxisZ az) {
  const glm::dmat3 direct = direct_basis(cell), reciprocal = reciprocal_basis(cell);
  const glm::dvec3 x = glm::normalize(ax == AxisX::A ? direct[0] : reciprocal[0]);
  const glm::dvec3 z = glm::normalize(az == AxisZ::C ? direct[2] : reciprocal[2]);
  // a ⟂ c* and a* ⟂ c always; a ⟂ c only when β = 90° (hexagonal and trigonal cells) — the
  // conventions below pair them only so.
  return glm::dmat3(x, glm::cross(z, x), z);
}

}  // namespace

glm::dmat3 vendor_crystal_frame(EbsdVendor vendor, CrystalSystem system, const UnitCell& cell) {
  if (vendor == EbsdVendor::OxfordChannel5) return frame_from_axes(cell, AxisX::AStar, AxisZ::C);
  switch (system) {
    case CrystalSystem::Hexagonal:
    case CrystalSystem::Trigonal: return frame_from_axes(cell, AxisX::A, AxisZ::C);
    case CrystalSystem::Monoclinic: return frame_from_axes(cell, AxisX::AStar, AxisZ::C);
    default: return frame_from_axes(cell, AxisX::A, AxisZ::CStar);
  }
}

glm::dmat3 vendor_specimen_frame(EbsdVendor vendor) {
  if (vendor == EbsdVendor::OxfordChannel5) return glm::dmat3(1.0);
  // EDAX x along the map's y (down = south), y along the map's x (east), z toward the observer.
  return glm::dmat3(glm::dvec3(0, -1, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1));
}

glm::dmat3 crystal_to_section(EbsdVendor vendor, const glm::dmat3& R, const EulerBunge& e) {
  return vendor_specimen_frame(vendor) * crystal_to_sample_from_bunge(e) * glm::transpose(R);
}

glm::dvec2 section_position_mm(const OrientationMap& m, std::size_t i) {
  const double x = m.x_um(i) - 0.5 * m.width_um(), y = m.y_um(i) - 0.5 * m.height_um();
  return {x * 1e-3, -y * 1e-3};
}

}  // namespace pmsim
