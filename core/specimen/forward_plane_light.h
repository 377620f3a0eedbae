#pragma once
// Plane-polarized light traced forward, from the condenser to the objective (issue 12: "trace
// backward ... or forward, whichever converges faster"). The image is the same quantity as
// render_plane_light's (plane_light_image.h) — by reciprocity the light a pixel's pupil collects
// from the condenser's cone equals the light the cone sends into that pixel through the pupil —
// but it converges far faster where the condenser's cone is small against the objective's NA,
// as it is with the diaphragm stopped down (NA_c 0.03 under NA 0.25–0.65): backward, a pixel
// finds the light bent toward it only with the rare pupil rays that end in the small cone
// (weight (NA/NA_c)² ≈ 68–470 empty fields); forward, every ray carries its share and lands
// where refraction sends it.
//
// A pass: one direction d_j inside the condenser's cone (sin θ = NA_c·√u, uniform in projected
// solid angle, as the backward pupil) and one point offset inside the pixel, both the pass's
// point of a randomly shifted Kronecker sequence, the SAME for every pixel. Each ray starts in
// the air below the slide where the empty stack would image it onto its pixel point q (the
// empty stack's lateral shift for d_j at its λ is traced once a pass), goes up through slide,
// specimen and cover glass (core/specimen/jones_path.h, forward mode: exact Fresnel, eigenmode
// splitting, pleochroic absorption), and every branch that leaves the cover glass within the
// objective's NA is imaged where its line crosses the focal plane (the thin-lens camera of the
// backward renderer: a ray through the focal-plane point q' is imaged at q'). Its power, over
// the empty stack's transmittance for d_j, is splatted there with a tent (bilinear) filter.
// So a pass's rays form a grid of the pixel's period; wherever the specimen only translates
// them (the empty field, a grain's flat interior) every pixel receives exactly weight 1 a pass
// (a tent's weights over a grid of its period sum to 1): no noise at all there. What a pass
// adds is the light crowded together or spread apart by inclined boundaries, cracks and the
// top's roughness — relief, the Becke line, shagreen.
//
// The source grid reaches past the image by the farthest a collected ray can be imaged from
// its start (a deviation within the objective's NA over the specimen's depth and the defocus).
//
// White light: every source point traces the reference λ (555 nm); every third one in x and y
// (kChromaPeriod) also traces one λ in each of the bands, its reference and band splats spread
// with a tent of radius 3 pixels (over a grid of that period those tents also sum to 1). A band's
// value is the reference image plus [band splats − subgrid reference splats]: a control variate
// exact in expectation, whose difference in flat regions is only the smooth change of absorption
// and Fresnel terms with λ, so the colour is resolved at a third of the pixel grid (as video's
// chroma subsampling) and complete after one pass, for 1 + 8/9 traces a pixel a pass.
//
// Split half (an estimate after 2 passes), tolerance stop, spp (traces a pixel: 1.89 a pass in
// white light), preview (grey, at the reference λ; 1/factor of the size or smaller, at most ~80
// pixels across), cancel and progress: as render_plane_light.
// Analyzer in is not traced forward: the branches' coherent sum needs the backward pairing.
#include <atomic>
#include <functional>
#include <string>

#include "core/render/render_image.h"
#include "core/specimen/plane_light_image.h"
#include "core/specimen/specimen_scene.h"

namespace pmsim {

// Throws std::invalid_argument with the scalar tracer asked for.
RenderImage render_plane_light_forward(const SpecimenScene& scene, const PlaneLightOptions& options,
                                       const std::function<void(const RenderImage&)>& progress = nullptr,
                                       InterfaceCounters* counters = nullptr,
                                       const std::atomic<bool>* cancel = nullptr);

// What the renderer says of its model (RenderImage::model_report), with the analyzer in or out.
std::string forward_model_report(bool analyzer_in);

// The same render with `report` as the model_report of every image it gives (a specimen's own
// words for what it became, e.g. "thin section slab: " + forward_model_report(...)).
RenderImage render_plane_light_forward_as(const std::string& report, const SpecimenScene& scene,
                                          const PlaneLightOptions& options,
                                          const std::function<void(const RenderImage&)>& progress,
                                          const std::atomic<bool>* cancel);

}  // namespace pmsim
