#pragma once
// Where the teaching panel's probe looks in a traced specimen (a grain mount or a section slab):
// the specimen point under an image point and the direction the polarizer's light vibrates in
// there, both in the specimen frame (µm; a section's frame is its section coordinates × 1000).
// The map is render_plane_light's for plane_light_options(scene): the image offset from the
// centre, turned back by the stage angle, plus the specimen point under the centre.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/microscope/scene.h"

namespace pmsim {

struct ProbePoint {
  glm::dvec2 specimen_um{0.0};
  // Unit, horizontal: the polarizer's direction turned back by the stage.
  glm::dvec3 vibration{1.0, 0.0, 0.0};
};

// `x`, `y`: fractions of the image from its top left (as the app's probe).
ProbePoint probe_point(const Scene& scene, double x, double y);

}  // namespace pmsim
