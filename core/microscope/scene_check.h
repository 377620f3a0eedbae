#pragma once
// Range and consistency checks of a Scene, shared by every input path (scene file, --set, the UI,
// ProgressiveRenderer::restart). Throws InputError naming file, key and value.
#include <string>

#include "core/microscope/scene.h"

namespace pmsim {

void check_scene(const Scene& scene, const std::string& file = "");

// Bound on render.width × render.height: 8192² pixels already take ~3.5 GB (float RGB + XYZ and
// the double accumulators); 16384² (each side within range) would take ~13 GB.
inline constexpr long long kMaxRenderPixels = 8192LL * 8192LL;
// Throws InputError on `key` (render.width or render.height, the one just set) when the pixel
// count exceeds kMaxRenderPixels.
void check_pixel_count(const Scene& scene, const std::string& file, const char* key);

}  // namespace pmsim
