#pragma once
// Public entry point of the 3-D scene renderer (pmsim-render dispatches "type": "scene3d" here).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene3d/scene3d_description.h"

namespace pmsim {

struct Scene3dImage {
  int width = 0, height = 0;
  std::vector<float> rgb_linear;  // width*height*3, top row first, linear sRGB
  nlohmann::json settings;        // the scene as rendered plus the derived settings
  double time_ms = 0.0;           // wall time of the render (scene build excluded)
};

// Parses (InputError naming file/key/value on bad input), builds the Embree scene and renders
// with TBB over 16×16 tiles.
Scene3dImage render_scene3d(const nlohmann::json& scene, const std::string& file);
Scene3dImage render_scene3d(const Scene3dDescription& desc);

}  // namespace pmsim
