#pragma once
// The fixed scenes of pmsim-bench (issue 5): each one a case a mineralogist looks at, chosen so
// that together they exercise every part of the renderer's "model only what the scene needs".
#include <string>
#include <vector>

#include "core/microscope/scene.h"

namespace pmsim {

struct BenchScene {
  std::string name;
  std::string description;
  Scene scene;
  bool conoscopic = false;
  bool physical_lenses = false;  // the lens-model strategies (dT, Fresnel/Schlick) apply
};

// size: image width = height in pixels. A thin-section scene is included only when a section
// (granite preferred) is available in assets/sections; `notes` (may be null) says when it is not.
std::vector<BenchScene> bench_scenes(int size, std::vector<std::string>* notes = nullptr);

}  // namespace pmsim
