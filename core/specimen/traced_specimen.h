#pragma once
// Which scenes are rendered by tracing light through a refracting 3-D specimen (issue 12), and
// the one entry that renders them: grain mounts (sample.type = grains) always; thin sections in
// the orthoscopic view (Bertrand lens out) with optics.relief on, in plane light (relief, outlines,
// cleavage cracks, pleochroism, focus and the aperture diaphragm) and between the polars (the
// interference colours with the outlines and cracks relief adds). Everything else — a compensator
// inserted with the analyzer in (the tracer has no accessory plate), the conoscopic view, an EBSD
// map with opaque points, optics.relief = off — is the progressive renderer's (core/render), unchanged.
#include <atomic>
#include <functional>

#include "core/microscope/scene.h"
#include "core/render/render_image.h"
#include "core/specimen/forward_response.h"

namespace pmsim {

bool is_traced_specimen(const Scene& scene);
// `cancel` (optional): as render_plane_light's. Throws for a scene is_traced_specimen refuses.
RenderImage render_traced_specimen(const Scene& scene, const std::function<void(const RenderImage&)>& progress = nullptr,
                                   const std::atomic<bool>* cancel = nullptr);

// The response/instrument split (specimen_response.h): a traced specimen's response, rendered
// progressively (the callback sees each developed state), to be composed at any instrument
// setting. Field: the scene's image only (a single render); Disc: everything the field sweeps as
// the stage turns (the app, a stage sweep).
// `hold`: ResponseRenderOptions::hold.
ResponseProgress render_traced_response(const Scene& scene, ResponseCoverage coverage,
                                        const std::function<void(const ResponseProgress&)>& progress = nullptr,
                                        const std::atomic<bool>* cancel = nullptr,
                                        const std::function<bool()>& hold = nullptr);

// Whether a response rendered for `rendered` serves `next` as it is: they differ only in the
// instrument (stage angle, polarizer, analyzer, accessory, wedge position) and in the exposure.
// A stage angle away from the response's frame needs coverage Disc.
bool same_specimen_response(const Scene& rendered, const Scene& next);

}  // namespace pmsim
