#pragma once
// From per-unit tristimulus values to the image: every pixel is the weighted sum of the units it
// shows, converted to linear sRGB only here (the accumulators stay XYZ in double until then).
#include <atomic>
#include <vector>

#include <glm/vec3.hpp>

#include "core/microscope/evaluation_plan.h"
#include "core/render/progressive_renderer.h"

namespace pmsim {

// monochromatic: unit values are relative intensities T; the image then holds R = G = B = T and
// XYZ = T × the illuminant white. A set `cancel` stops it between rows (the image is then
// incomplete: discard it); a progressive renderer restarting on every slider step needs that.
void develop_image(const EvaluationPlan& plan, const std::vector<glm::dvec3>& units, bool monochromatic,
                   RenderImage& out, const std::atomic<bool>* cancel = nullptr);

// Mean CIEDE2000 between two XYZ images of the plan's size over its lit pixels (a regular subset
// of at most ~65k of them), white = the scene illuminant with Y = 1.
double mean_ciede2000(const EvaluationPlan& plan, const std::vector<float>& xyz_a,
                      const std::vector<float>& xyz_b);

}  // namespace pmsim
