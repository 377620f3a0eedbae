#pragma once
// BENCH-SIDE physical-lens model of the conoscopic figure: the bench's independent, per-pixel
// implementation of optics.lens_model = physical, against which it measures the renderer's own
// (core/microscope/lens_polarization.h, lens_ghosts.h) and from which it builds the reference of
// the physical-lens scenes (reference_image.cpp). The condenser and the objective are SML lenses
// (core/lens trace_lens: real glass, exact Fresnel or Schlick, internal reflections up to
// optics.lens_depth = dT), the sample at their common focus.
//
// For every back-focal-plane pixel (a direction k through the sample, as in the ideal model):
//  * the condenser ray that reaches the sample along k (found by tracing −k backward through the
//    condenser, then forward along the reversed exit ray) gives the condenser's Jones matrix from
//    the polarizer (lab x, y) to the transverse basis of k (depth-0 path);
//  * the plate is the renderer's ModalFit (three exact mode solutions per pixel), its
//    interference term averaged over each band in closed form;
//  * the objective traced from the sample along k with two orthogonal input polarizations gives one
//    Jones matrix per outgoing forward path: the depth-0 path lands on the pixel itself; every
//    ghost path (2, 4, … internal reflections, up to dT) lands where its exit ray crosses the
//    back-focal plane, mapped to the image by the depth-0 rays' own height-to-pixel relation, and
//    adds its intensity there (light of different condenser directions is mutually incoherent).
// Intensities are relative to the axial ray's depth-0 transmission through both lenses (the
// exposure convention: empty stage, parallel polars, Y = 1 on the axis; docs/conventions.md), as in
// the renderer's own physical model, which differs from this one in tracing one meridional profile
// per lens instead of every pixel's rays and in adding the condenser's ghosts too (by reciprocity;
// here the condenser is its depth-0 path only). The lenses are traced at 550 nm (their dispersion shifts
// Fresnel losses by < 1 % across the visible); the plate keeps its full dispersion. The Bertrand lens is
// ideal (it images the back-focal plane; its own Fresnel losses are polarization-neutral to first order near
// the axis).
#include "core/bench/bench_strategy.h"
#include "core/microscope/scene.h"

namespace pmsim {

// Lens used for the condenser and the objective front element: assets/lenses/paper_rl425_rs43.json
// (the paper's near-hemispheric lens), placed as the renderer places it: physical_lens_spec() in
// core/microscope/lens_polarization.h (front vertex kLensWorkingDistanceMm from the sample).

// scene.optics: lens_depth (dT), schlick. Spectral bands: scene.render.wavelengths (0: 32).
// Runs on the calling thread's TBB arena.
StrategyResult render_physical_lens_model(const Scene& scene);

}  // namespace pmsim
