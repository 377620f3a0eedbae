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
// White light: a pass traces the reference λ (555 nm) and one band's λ (pass j: band (j/2)
// mod n, so both split halves cycle through all bands); a band's value is the reference image
// plus the mean over its passes of [band splats − reference splats] (a control variate exact in
// expectation; in flat regions both splats land on the same pixels and the difference is only
// the smooth change of absorption and Fresnel terms with λ).
//
// Split half, tolerance stop, spp (traces a pixel: 2 a pass in white light), preview (1/factor
// size, grey, at the reference λ), cancel and progress: as render_plane_light.
// Analyzer in is not traced forward: the branches' coherent sum needs the backward pairing.
#include <atomic>
#include <functional>

#include "core/render/render_image.h"
#include "core/specimen/plane_light_image.h"
#include "core/specimen/specimen_scene.h"

namespace pmsim {

// Throws std::invalid_argument with the analyzer in or the scalar tracer asked for.
RenderImage render_plane_light_forward(const SpecimenScene& scene, const PlaneLightOptions& options,
                                       const std::function<void(const RenderImage&)>& progress = nullptr,
                                       InterfaceCounters* counters = nullptr,
                                       const std::atomic<bool>* cancel = nullptr);

}  // namespace pmsim
