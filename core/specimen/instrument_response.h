#pragma once
// One pipeline, chosen in core (issue 21): which source serves a scene while only the instrument
// changes, and the one response type every frame is composed from. pmsim-render's --sweep, the
// app's render feed and the bench ask these functions instead of deciding for themselves.
//
//   Traced — a traced specimen (is_traced_specimen): its Mueller response per grid point
//            (specimen_response.h), rendered over the field or over the disc the stage sweeps.
//   Figure — a conoscopic figure (figure_response_applies): its nine probes, and its plan for
//            frames with an accessory (figure_response.h).
//   Flat   — a thin section's flat orthoscopic view (flat_response_applies: optics.relief off, or
//            an EBSD map the slab cannot trace): nine probes over a canvas that holds the view at
//            every stage angle, and the canvas's plan for frames with an accessory
//            (figure_response.h).
//   None   — every other view (a plate, a wedge, a figure with ghost light and an accessory in
//            the slot, the parallel-light spot): the progressive renderer renders each setting
//            afresh.
#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <variant>

#include "core/microscope/scene.h"
#include "core/render/render_image.h"
#include "core/specimen/figure_response.h"
#include "core/specimen/forward_response.h"
#include "core/specimen/specimen_response.h"

namespace pmsim {

enum class ResponseKind { None, Traced, Figure, Flat };

ResponseKind response_kind(const Scene& scene);

// Whether one response rendered for `rendered` serves `next` as it is: both of one kind other than
// None, differing only in the instrument and exposure (same_specimen_response). A traced response
// serves a turned stage only with ResponseCoverage::Disc.
bool response_serves(const Scene& rendered, const Scene& next);

// A specimen's response, or the state of one being rendered.
class InstrumentResponse {
 public:
  InstrumentResponse(ResponseProgress traced, ResponseCoverage coverage);
  explicit InstrumentResponse(std::shared_ptr<const FigureResponse> figure);
  // A figure or flat view whose own render is still running (its probes come after): a status,
  // nothing to compose.
  static InstrumentResponse figure_rendering(RenderImage own);

  ResponseKind kind() const;
  // "field" | "disc" | "figure" | "flat": --stats' response.coverage.
  const char* coverage_name() const;
  // Nothing to compose yet: a traced response before its first pass, a figure before its probes.
  bool empty() const;
  bool preview() const;  // the traced response's coarse first pass
  // The convergence every composed frame carries, as a render's: passes, samples_per_pixel,
  // wavelengths, error_estimate, converged, stopped, time_ms, model_report (no pixels).
  RenderImage status() const;
  // The image at `instrument` (which the response must serve: response_serves).
  RenderImage compose(const InstrumentSettings& instrument) const;

 private:
  struct Traced {
    ResponseProgress progress;
    ResponseCoverage coverage;
  };
  explicit InstrumentResponse(RenderImage own) : state_(std::move(own)) {}
  std::variant<Traced, std::shared_ptr<const FigureResponse>, RenderImage> state_;
};

// Renders the response response_kind(scene) names (std::invalid_argument for None). `coverage`:
// a traced response's (Disc when the stage will turn; a figure always covers every angle).
// `progress` sees each state as it develops; `threads` bounds the worker threads (0: all cores),
// as ProgressiveRenderer::render's. nullopt when `cancel` stops it before a response is complete.
// `hold`: a traced response pauses between passes while it returns true (the app, while the stage
// is dragged: ResponseRenderOptions::hold); a figure's renders do not pause.
std::optional<InstrumentResponse> render_instrument_response(
    const Scene& scene, ResponseCoverage coverage,
    const std::function<void(const InstrumentResponse&)>& progress = nullptr, const std::atomic<bool>* cancel = nullptr,
    int threads = 0, const std::function<bool()>& hold = nullptr);

// One image of a microscope scene, from the source response_kind names for it: a traced specimen's
// response (Field coverage) composed at the scene's settings, else the progressive renderer (a
// single figure is rendered, not probed: its probes cost two to three renders). What pmsim-render, the
// app's export and the bench call for one image.
RenderImage render_microscope_scene(const Scene& scene, const std::function<void(const RenderImage&)>& progress = nullptr,
                                    const std::atomic<bool>* cancel = nullptr);

}  // namespace pmsim
