#pragma once
// The convergence metric of a render: how far one spectral level's unit colours are from the
// previous level's, as the image would show it (the error estimate of RenderImage).
#include <atomic>
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "core/microscope/evaluation_plan.h"

namespace pmsim {

// Mean CIEDE2000 between two estimates of the units (XYZ, Y = 1 the exposure reference; a single
// wavelength's transmission in .y), weighted by the image area each unit covers, over units u with
// u % stride == 0; 0 when none is visible. Parallel (TBB); a raised `cancel` makes it return early
// with a partial value the caller discards.
double unit_error(const EvaluationPlan& plan, const std::vector<double>& area,
                  const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b, std::size_t stride,
                  const std::atomic<bool>& cancel);

}  // namespace pmsim
