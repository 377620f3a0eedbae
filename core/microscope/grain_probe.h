#pragma once
// The grain under a point of the image: what the app's teaching panel reports at the cursor, and
// what a script can ask for the same point.
#include <optional>

#include "core/microscope/grain_report.h"
#include "core/microscope/scene.h"

namespace pmsim {

// (x_frac, y_frac): 0…1 from the left and from the TOP of the image, as probe_pixel takes them.
// nullopt unless a thin section is on the stage in orthoscopic view and a grain (not the
// mounting medium or the slide) lies under the point. Throws InputError for a bad section file.
std::optional<GrainReport> grain_at_image_point(const Scene& scene, double x_frac, double y_frac);

}  // namespace pmsim
