#pragma once
// The photographer's exposure of an 8-bit output (render.exposure_ev): linear RGB × 2^ev before
// the sRGB encoding, so that light above the empty field (a Becke line's excess, > 1) can be
// brought under 255 instead of clipping. Linear outputs (EXR, float TIFF) stay unscaled: the
// scene in their metadata records the exposure for whoever encodes them.
#include <vector>

#include <glm/mat3x3.hpp>

#include "core/microscope/scene_limits.h"  // kMinExposureEv, kMaxExposureEv
#include "core/spectrum/colour_vision.h"

namespace pmsim {

// 2^ev, the linear gain of `ev` stops.
double exposure_gain(double ev);
// rgb_linear × 2^ev (a copy; the input untouched, it may be a shared render buffer).
std::vector<float> exposed(const std::vector<float>& rgb_linear, double ev);

// What an 8-bit output shows of a linear image: the exposure and the observer's colour vision
// (render.vision, core/spectrum/colour_vision.h) as one matrix on linear sRGB, 2^ev · Φ.
glm::dmat3 display_matrix(double ev, ColourVision vision);
// rgb_linear through display_matrix (a copy), before the 8-bit encoding clips it.
std::vector<float> displayed(const std::vector<float>& rgb_linear, double ev, ColourVision vision);

}  // namespace pmsim
