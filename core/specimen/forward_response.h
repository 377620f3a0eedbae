#pragma once
// The specimen response (specimen_response.h) traced forward from the condenser: the forward
// renderer's passes (forward_plane_light.h: one cone direction and in-pixel point a pass for every
// source point, rays started where the empty stack images them onto their points, tent splats
// that are exact wherever light is only translated, the reference λ everywhere and the bands on a
// chroma subgrid), but each path carries the Jones matrix of both input vibrations instead of one
// field, and each branch the objective collects splats its share of the path's Mueller matrix
// (core/optics/mueller.h) instead of one intensity. The input and output vibrations are carried
// through the condenser and the objective by the aplanatic map (the s and p components of a ray
// keep their amplitudes between the ray's direction and the lens's collimated space), so a
// polarizer at angle ψ enters every ray as cos ψ·X_d + sin ψ·Y_d and the response is linear in
// the polarizer's and analyzer's Stokes vectors.
//
// Progress: after the preview (a coarse grid, coloured: bands on every other coarse point) and
// after every pass the callback gets a developed response; the split-half estimate (even against
// odd passes, composed at `estimate_at`) decides the stop at light.tolerance_de2000, and
// light.spp caps the traces a pixel. `stopped`: "tolerance", "cap" or "cancelled".
#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "core/specimen/plane_light_image.h"
#include "core/specimen/specimen_response.h"
#include "core/specimen/specimen_scene.h"

namespace pmsim {

struct ResponseRenderOptions {
  // Geometry, optics, spectrum, spp, tolerance, preview and seed; its stage_rad is the response's
  // frame angle; its polarizer, analyzer and bands are not used (32 bands always: the analyzer
  // may go in on any frame).
  PlaneLightOptions light;
  ResponseCoverage coverage = ResponseCoverage::Field;
  InstrumentSettings estimate_at;  // the settings the split-half estimate is judged at
  std::string model_report;        // the specimen's words for what it became
  // Polled before every source row (from the worker threads): while it returns true the pass
  // waits, so that an interactive client can give the cores to composing and drawing while the
  // user turns the stage (the response keeps serving every frame meanwhile). Null: never.
  std::function<bool()> hold;
};

struct ResponseProgress {
  std::shared_ptr<const SpecimenResponse> response;
  std::optional<double> error_estimate;
  bool preview = false;    // the coarse first image
  bool converged = false;  // estimate below the tolerance
  std::string stopped;     // "" while running, else "tolerance" | "cap" | "cancelled"
};

ResponseProgress render_specimen_response(const SpecimenScene& scene, const ResponseRenderOptions& options,
                                          const std::function<void(const ResponseProgress&)>& progress = nullptr,
                                          const std::atomic<bool>* cancel = nullptr);

// The response for `options` (Field coverage) composed at its own polarizer, analyzer and stage:
// the image render_plane_light_forward gives, through the response (the bench's and the tests'
// drop-in; `counters` unused).
RenderImage render_response_image(const SpecimenScene& scene, const PlaneLightOptions& options,
                                  const std::function<void(const RenderImage&)>& progress = nullptr,
                                  InterfaceCounters* counters = nullptr, const std::atomic<bool>* cancel = nullptr);

// A progress state composed at `instrument`: the image with the progress's estimate, converged
// flag and stop reason.
RenderImage compose_progress(const ResponseProgress& progress, const InstrumentSettings& instrument);

}  // namespace pmsim
