#pragma once
// The scale bar of a micrograph: a bar of a round length (1, 2 or 5 × 10ⁿ µm or mm) with its
// length written under it, burned into the image (exports) or drawn by the UI over the field.
// It is an annotation of the image, not part of the optics: it is added after developing.
#include <string>
#include <vector>

namespace pmsim {

struct ScaleBar {
  double length_mm = 0.0;
  double length_px = 0.0;  // length_mm / mm_per_px
  std::string label;       // "200 um", "1 mm"
};

// The longest 1-2-5 length not longer than max_fraction of the image width. mm_per_px > 0.
ScaleBar choose_scale_bar(double mm_per_px, int image_width, double max_fraction = 0.25);

// Burns the bar (white, with a one-pixel black outline so it reads on bright and dark fields) and
// its label into interleaved linear RGB, bottom left with a margin. Text and bar grow with the image
// (one glyph pixel per 256 image rows).
void burn_scale_bar(std::vector<float>& rgb, int width, int height, const ScaleBar& bar);

}  // namespace pmsim
