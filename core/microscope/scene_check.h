#pragma once
// Range and consistency checks of a Scene, shared by every input path (scene file, --set, the UI,
// ProgressiveRenderer::restart). Throws InputError naming file, key and value.
#include <string>

#include "core/microscope/scene.h"
#include "core/microscope/scene_limits.h"

namespace pmsim {

void check_scene(const Scene& scene, const std::string& file = "");

// Throws InputError on `key` (render.width or render.height, the one just set) when the pixel
// count exceeds kMaxRenderPixels (scene_limits.h).
void check_pixel_count(const Scene& scene, const std::string& file, const char* key);

}  // namespace pmsim
