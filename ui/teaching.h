#pragma once
// Private to the App: what the teaching panels keep between frames, so the core is asked again
// only when the scene or the probed point changes.
#include <cstdint>
#include <string>
#include <vector>

#include "core/microscope/pixel_probe.h"
#include "ui/app.h"

namespace pmsim::ui {

struct App::Teaching {
  PixelProbe probe;
  std::string probe_error;
  std::uint64_t probe_generation = ~0ull;
  float probe_x = -1, probe_y = -1;
  std::vector<float> spectrum;  // probe.transmission as floats for the plot
};

}  // namespace pmsim::ui
