#pragma once
// Image measurements used by the paper's figure experiments and their tests: which pixels see a
// lens first, the difference of two renders, and the total-internal-reflection spot.
#include <vector>

#include "core/scene3d/scene3d_description.h"

namespace pmsim {

struct LensMask {
  int width = 0, height = 0, count = 0;
  std::vector<unsigned char> inside;  // 1 where the pixel-centre ray meets a lens first
};
LensMask lens_mask(const Scene3dDescription& desc);

struct DifferenceStats {
  double mean_inside = 0.0, mean_outside = 0.0, max = 0.0;  // mean |a − b| over channels
};
DifferenceStats difference_stats(const std::vector<float>& a, const std::vector<float>& b,
                                 const LensMask& mask);
// |a − b|·gain per channel; negative = true gives 1 − that (the paper's "negative difference").
std::vector<float> difference_image(const std::vector<float>& a, const std::vector<float>& b, double gain,
                                    bool negative);

// Rec. 709 / sRGB luminance of linear RGB.
inline double luminance(const float* rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

struct TirSpotStats {
  double threshold = 0.01;  // luminance below which a pixel counts as black
  int dark_pixels = 0;      // black pixels inside the lens silhouette
  int dark_with_tir = 0;    // of those, pixels whose natural-light SML tree (n at 587.56 nm)
                            // loses more than half of the transmitted light to TIR events
  int tir_pixels = 0;       // lens pixels with that TIR loss, dark or not
};
TirSpotStats tir_spot_stats(const Scene3dDescription& desc, const std::vector<float>& rgb,
                            const LensMask& mask, double threshold = 0.01);

}  // namespace pmsim
