#pragma once
// The UI's side of the progressive renderer. ProgressiveRenderer::restart() stops the pass in
// flight and joins its worker, which can take a good part of a pass (tens of ms for a thin
// section); the UI thread must never wait for that. So scenes go to a small feeder thread that
// restarts the renderer with the newest one (older pending scenes are skipped: only the last
// position of a drag matters), and the UI thread only ever takes snapshots.
// A grain mount (sample.type = grains), and a thin section with optics.relief on (orthoscopic),
// are refracting 3-D specimens whose response the core renders (render_instrument_response;
// core/specimen/instrument_response.h's response_kind decides), not the ProgressiveRenderer: the feeder thread runs it itself,
// pass by pass, and a newer submission cancels it through its cancel flag. A section's slab is
// cached in core, so a focus or aperture change does not rebuild it.
// Traced specimens are rendered as a response (core/specimen/specimen_response.h) covering the
// disc the field sweeps: a submission that changes only the instrument (stage angle, polars,
// accessory, exposure: response_serves) neither cancels nor restarts anything; a composer
// thread composes the newest response at the newest settings (15 ms at 512² on 2 idle cores,
// more while the response is still being traced beside it) and snapshot() takes the newest
// composed image, so the UI thread never waits for a composition and every image of a stage drag
// shows its angle's colours at the response's convergence.
// A conoscopic figure (response_kind Figure) and a thin section's flat image (Flat) are
// rendered by the progressive renderer first; once that has
// converged, the feeder thread renders the view's nine probes (core/specimen/figure_response.h,
// 2–3 renders' work; a flat view's on a canvas that holds it at every stage angle) and from then
// on a submission that changes only the stage, the polars or the accessory is composed from them
// (an accessory's frames from the view's plan) by the composer
// thread, as a traced specimen's ("figure mode" below covers both). Any other change drops the
// response and restarts the renderer.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "core/render/progressive_renderer.h"
#include "core/specimen/instrument_response.h"

namespace pmsim::ui {

class RenderFeed {
 public:
  explicit RenderFeed(int renderer_threads = 0);
  ~RenderFeed();
  RenderFeed(const RenderFeed&) = delete;
  RenderFeed& operator=(const RenderFeed&) = delete;

  // Queues `scene` (tagged with the caller's `id`) for rendering; returns at once.
  void submit(const Scene& scene, std::uint64_t id);

  struct Failure {
    std::uint64_t id;
    std::string message;
  };
  // A scene the renderer refused (InputError from restart), reported once.
  std::optional<Failure> take_failure();

  // Newest image if it changed since `out` (as ProgressiveRenderer::snapshot). `current` tells
  // whether it belongs to the last scene submitted (no newer submission pending or in restart).
  bool snapshot(RenderImage& out, bool& current) const;
  // Blocks until the last submitted scene is being rendered and has converged, or timeout.
  bool wait(double timeout_s) const;

 private:
  void run();
  void compose_loop();  // the composer thread
  void render_grains(const Scene& scene);                            // on the feeder thread, unlocked
  void render_figure(const Scene& scene, std::uint64_t id);          // on the feeder thread, unlocked
  bool composing() const { return grains_mode_ || figure_mode_; }    // snapshots come from the composer

  // Worker threads of both renderers (the app's --threads; 0: all cores).
  const int threads_;
  ProgressiveRenderer renderer_;
  mutable std::mutex mu_;
  mutable std::condition_variable cv_;
  std::optional<std::pair<Scene, std::uint64_t>> pending_;
  bool busy_ = false;  // a restart is in progress
  bool quit_ = false;
  std::uint64_t submitted_id_ = 0;         // id of the newest submission
  std::uint64_t applied_id_ = 0;           // id of the scene the renderer is rendering
  std::uint64_t renderer_generation_ = 0;  // the renderer's generation for applied_id_
  std::optional<Failure> failure_;
  // The grain-mount path: its images carry generation kGrainGeneration | n, apart from the
  // renderer's own generations so that a snapshot never mistakes one for the other.
  static constexpr std::uint64_t kGrainGeneration = 1ull << 62;
  bool grains_mode_ = false;       // the applied scene is a grain mount
  bool grain_running_ = false;     // its render is in flight
  std::uint64_t grain_generation_ = 0;  // kGrainGeneration | n of the applied grain mount
  // The composer's source (core/specimen/instrument_response.h): the traced response so far, or
  // the figure's response once its probes are rendered; for source_scene_.
  std::optional<InstrumentResponse> source_;
  Scene source_scene_;
  std::uint64_t response_version_ = 0;     // bumps with every new response state
  InstrumentSettings instrument_;          // the newest submission's settings
  std::uint64_t instrument_version_ = 0;   // bumps with every instrument-only submission
  RenderImage composed_;                   // the response composed at instrument_
  // A conoscopic figure composed from its response (source_); its images carry
  // kGrainGeneration-tagged generations as the traced path's.
  bool figure_mode_ = false;
  // Bumps when the composer's source is replaced (a new scene applied, a figure's response ready):
  // a composition begun before is dropped, so no image of an earlier scene is shown after it.
  std::uint64_t source_epoch_ = 0;
  std::uint64_t composed_response_ = ~0ull, composed_instrument_ = ~0ull;
  std::atomic<bool> grain_cancel_{false};
  // Until this steady-clock time (ns) the response tracer holds (an instrument change was just
  // submitted: a drag gets the cores for composing and drawing).
  std::atomic<std::int64_t> hold_until_ns_{0};
  std::thread thread_;
  std::thread composer_;
};

}  // namespace pmsim::ui
