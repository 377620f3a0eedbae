#include "core/specimen/instrument_response.h"

#include <stdexcept>

#include <tbb/task_arena.h>

#include "core/render/progressive_renderer.h"
#include "core/specimen/traced_specimen.h"

namespace pmsim {

ResponseKind response_kind(const Scene& scene) {
  if (is_traced_specimen(scene)) return ResponseKind::Traced;
  if (figure_response_applies(scene)) return ResponseKind::Figure;
  if (flat_response_applies(scene)) return ResponseKind::Flat;
  return ResponseKind::None;
}

bool response_serves(const Scene& rendered, const Scene& next) {
  // The specimens compared first: response_kind may load (grow) a section, and a scene with another
  // section or seed must not be grown here (the app asks this on its UI thread at every change).
  if (!same_specimen_response(rendered, next)) return false;
  const ResponseKind k = response_kind(rendered);
  return k != ResponseKind::None && response_kind(next) == k;
}

InstrumentResponse::InstrumentResponse(ResponseProgress traced, ResponseCoverage coverage)
    : state_(Traced{std::move(traced), coverage}) {}

InstrumentResponse::InstrumentResponse(std::shared_ptr<const FigureResponse> figure) : state_(std::move(figure)) {
  if (!std::get<1>(state_)) throw std::invalid_argument("InstrumentResponse: no figure response");
}

InstrumentResponse InstrumentResponse::figure_rendering(RenderImage own) {
  own.rgb.clear();
  own.xyz.clear();
  return InstrumentResponse(std::move(own));
}

ResponseKind InstrumentResponse::kind() const {
  if (std::holds_alternative<Traced>(state_)) return ResponseKind::Traced;
  const auto* f = std::get_if<std::shared_ptr<const FigureResponse>>(&state_);
  return f && (*f)->flat ? ResponseKind::Flat : ResponseKind::Figure;
}

const char* InstrumentResponse::coverage_name() const {
  if (const Traced* t = std::get_if<Traced>(&state_)) return t->coverage == ResponseCoverage::Disc ? "disc" : "field";
  return kind() == ResponseKind::Flat ? "flat" : "figure";
}

bool InstrumentResponse::empty() const {
  if (const Traced* t = std::get_if<Traced>(&state_)) return !t->progress.response;
  return !std::holds_alternative<std::shared_ptr<const FigureResponse>>(state_);
}

bool InstrumentResponse::preview() const {
  const Traced* t = std::get_if<Traced>(&state_);
  return t && t->progress.preview;
}

RenderImage InstrumentResponse::status() const {
  if (const Traced* t = std::get_if<Traced>(&state_)) {
    RenderImage s;
    if (const SpecimenResponse* r = t->progress.response.get()) {
      s.passes = r->passes;
      s.samples_per_pixel = r->samples_per_pixel;
      s.time_ms = r->time_ms;
      s.model_report = r->model_report;
    }
    s.error_estimate = t->progress.error_estimate;
    s.converged = t->progress.converged;
    s.stopped = t->progress.stopped;
    return s;
  }
  if (const auto* f = std::get_if<std::shared_ptr<const FigureResponse>>(&state_)) {
    RenderImage s = (*f)->progress;
    s.wavelengths = (*f)->wavelengths;
    s.time_ms = (*f)->time_ms;
    return s;
  }
  return std::get<RenderImage>(state_);
}

RenderImage InstrumentResponse::compose(const InstrumentSettings& instrument) const {
  if (const Traced* t = std::get_if<Traced>(&state_)) return compose_progress(t->progress, instrument);
  if (const auto* f = std::get_if<std::shared_ptr<const FigureResponse>>(&state_))
    return compose_figure(**f, instrument);
  throw std::logic_error("InstrumentResponse::compose: the figure's probes are not rendered yet");
}

namespace {

std::optional<InstrumentResponse> render_figure(const Scene& scene,
                                                const std::function<void(const InstrumentResponse&)>& progress,
                                                const std::atomic<bool>* cancel, int threads) {
  std::optional<FigureResponse> figure = render_figure_response(
      scene, threads,
      progress ? [&](const RenderImage& own) { progress(InstrumentResponse::figure_rendering(own)); }
               : std::function<void(const RenderImage&)>(),
      cancel);
  if (!figure) return std::nullopt;
  InstrumentResponse r(std::make_shared<const FigureResponse>(std::move(*figure)));
  if (progress) progress(r);
  return r;
}

std::optional<InstrumentResponse> render_traced(const Scene& scene, ResponseCoverage coverage,
                                                const std::function<void(const InstrumentResponse&)>& progress,
                                                const std::atomic<bool>* cancel, int threads,
                                                const std::function<bool()>& hold) {
  ResponseProgress last;
  // The response's passes run in TBB loops: an arena bounds them as the renderer's thread count does.
  tbb::task_arena arena(threads > 0 ? threads : static_cast<int>(tbb::task_arena::automatic));
  arena.execute([&] {
    last = render_traced_response(
        scene, coverage,
        progress ? [&](const ResponseProgress& p) { progress(InstrumentResponse(p, coverage)); }
                 : std::function<void(const ResponseProgress&)>(),
        cancel, hold);
  });
  if (!last.response || last.stopped == "cancelled") return std::nullopt;
  return InstrumentResponse(std::move(last), coverage);
}

}  // namespace

std::optional<InstrumentResponse> render_instrument_response(
    const Scene& scene, ResponseCoverage coverage, const std::function<void(const InstrumentResponse&)>& progress,
    const std::atomic<bool>* cancel, int threads, const std::function<bool()>& hold) {
  switch (response_kind(scene)) {
    case ResponseKind::Traced: return render_traced(scene, coverage, progress, cancel, threads, hold);
    case ResponseKind::Figure:
    case ResponseKind::Flat: return render_figure(scene, progress, cancel, threads);
    case ResponseKind::None: break;
  }
  throw std::invalid_argument("render_instrument_response: the scene's view has no response (each setting is rendered)");
}

RenderImage render_microscope_scene(const Scene& scene, const std::function<void(const RenderImage&)>& progress,
                                    const std::atomic<bool>* cancel) {
  if (response_kind(scene) == ResponseKind::Traced) return render_traced_specimen(scene, progress, cancel);
  (void)cancel;  // the progressive renderer's static render runs to its stop
  return ProgressiveRenderer::render(scene, 0, progress ? progress : [](const RenderImage&) {});
}

}  // namespace pmsim
