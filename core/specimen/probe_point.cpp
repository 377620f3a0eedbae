#include "core/specimen/probe_point.h"

#include <cmath>

#include "core/specimen/grain_mount_render.h"

namespace pmsim {

ProbePoint probe_point(const Scene& scene, double x, double y) {
  const PlaneLightOptions o = plane_light_options(scene);
  const double fx = (x - 0.5) * o.width * o.um_per_px, fy = (0.5 - y) * o.height * o.um_per_px;
  const double c = std::cos(-o.stage_rad), s = std::sin(-o.stage_rad);
  ProbePoint p;
  p.specimen_um = {o.centre_um.x + c * fx - s * fy, o.centre_um.y + s * fx + c * fy};
  p.vibration = {c * std::cos(o.polarizer_rad) - s * std::sin(o.polarizer_rad),
                 s * std::cos(o.polarizer_rad) + c * std::sin(o.polarizer_rad), 0.0};
  return p;
}

}  // namespace pmsim
