#pragma once
// The upsampler of a preview: an image developed on a coarse grid spread bilinearly over the full
// one.
#include "core/microscope/evaluation_plan.h"
#include "core/microscope/scene.h"
#include "core/render/render_image.h"

namespace pmsim {

// Fills full.rgb and full.xyz (full.width × full.height = the scene's render size, buffers sized)
// from `coarse`, developed from `coarse_plan` (the same scene on a coarser grid). Unlit coarse
// cells carry no weight; a back focal plane stays black outside its lit disk. Rows in parallel
// (TBB).
void upsample_preview(const Scene& scene, const EvaluationPlan& coarse_plan, const RenderImage& coarse,
                      RenderImage& full);

}  // namespace pmsim
