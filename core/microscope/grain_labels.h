#pragma once
// Ground truth of a rendered thin section: the grain under every pixel centre, as
// SectionMap::grain_label numbers it (0: mounting medium or slide, k ≥ 1: grain k, the same k in
// every render of the same section). pmsim-render --labels writes it as a 16-bit grey PNG.
#include <cstdint>
#include <vector>

#include "core/microscope/scene.h"
#include "core/microscope/section_map.h"

namespace pmsim {

// render.width × render.height labels, top row first. Orthoscopic field (Bertrand lens out): the
// grain at section_point_from_pixel of each pixel centre, the point the renderer samples there.
// Bertrand lens in, the image is the back focal plane and every lit pixel shows the grain under
// the crosshair (stage.x_mm, stage.y_mm): those pixels carry its label, unlit ones 0. Throws
// std::invalid_argument for a section of more than 65535 grains (a label must fit 16 bits).
std::vector<std::uint16_t> grain_label_image(const Scene& scene, const SectionMap& section);

// Pixels per label: result[k] = number of pixels labelled k (size: grains + 1).
std::vector<long long> label_counts(const std::vector<std::uint16_t>& labels, const SectionMap& section);

}  // namespace pmsim
