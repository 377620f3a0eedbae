#pragma once
// One developed image of a render, with what was done to make it.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace pmsim {

struct RenderImage {
  int width = 0, height = 0;
  std::vector<float> rgb;          // linear sRGB, row-major, top row first, 3 floats a pixel
  std::vector<float> xyz;          // CIE XYZ (Y = 1: the exposure reference), same layout
  double samples_per_pixel = 0.0;  // spatial × spectral samples done per pixel
  int wavelengths = 0;             // spectral samples per pixel so far
  int passes = 0;
  // Estimated mean CIEDE2000 against the converged image; none before two spectral levels could
  // be compared (a preview, the first pass of a progressive render).
  std::optional<double> error_estimate;
  bool converged = false;        // estimate below the scene's tolerance (a cap stop is not: `stopped`)
  // Why the render ended (empty while it runs): "tolerance" (the estimate fell below
  // render.tolerance: converged), "cap" (render.spp / render.wavelengths or a renderer's own cap
  // was reached first: `converged` is then false unless the estimate is below the tolerance too),
  // "cancelled".
  std::string stopped;
  double time_ms = 0.0;          // wall time since the last restart
  std::uint64_t generation = 0;  // increments with every restart()
  std::string model_report;      // which model each element uses, e.g. "objective: ideal (err 0.02)"
};

}  // namespace pmsim
