#pragma once
// Range and consistency checks of a Scene, shared by every input path (scene file, --set, the UI,
// ProgressiveRenderer::restart). Throws InputError naming file, key and value.
#include <string>

#include "core/microscope/scene.h"

namespace pmsim {

void check_scene(const Scene& scene, const std::string& file = "");

// render.strategy: "auto" (the cheapest accurate plate model per scene), "modal" (eigenmodes fitted
// across the spectrum, band-averaged interference terms), "exact" (plate Jones matrix at every
// wavelength sample, plain midpoint quadrature: the paper's uniform sampling).
bool render_strategy_known(const std::string& strategy);
std::string render_strategy_list();

}  // namespace pmsim
