#pragma once
// What the two plane-light renderers (backward: plane_light_image.h, forward:
// forward_plane_light.h) share of their progressive passes: the grey preview spread over the full
// grid, and the split-half estimate.
#include <cstddef>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "core/render/render_image.h"

namespace pmsim {

// Spreads a grey image of cw × ch (1/f of img's size, row-major) bilinearly over img, each pixel
// v·open_xyz and v·open_rgb (v ≥ 0: a splatted estimate may undershoot 0); img then counts one
// pass of 1/f² samples a pixel, not converged.
void spread_preview(const std::vector<double>& coarse, int cw, int ch, int f, const glm::dvec3& open_xyz,
                    const glm::dvec3& open_rgb, RenderImage& img);

// Mean CIEDE2000 between the even and odd passes' colours (`half_xyz(i, 0 or 1)`) of n items,
// over at most 65536 of them taken at an even stride.
double split_half_de2000(std::size_t n, const std::function<glm::dvec3(std::size_t, int)>& half_xyz,
                         const glm::dvec3& white);

}  // namespace pmsim
