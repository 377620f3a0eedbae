#include "ui/render_feed.h"

#include <chrono>

#include <tbb/task_arena.h>

#include "core/microscope/scene_check.h"

namespace pmsim::ui {

RenderFeed::RenderFeed(int renderer_threads)
    : threads_(renderer_threads),
      renderer_(renderer_threads),
      thread_([this] { run(); }),
      composer_([this] { compose_loop(); }) {}

RenderFeed::~RenderFeed() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    quit_ = true;
    grain_cancel_.store(true);
  }
  cv_.notify_all();
  thread_.join();
  composer_.join();
  renderer_.cancel();
}

void RenderFeed::submit(const Scene& scene, std::uint64_t id) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    // Only the instrument changed on a traced specimen or a figure: the response serves it as it is.
    if (composing() && !busy_ && !pending_ && applied_id_ == submitted_id_ && response_serves(source_scene_, scene)) {
      instrument_ = instrument_settings(scene);
      ++instrument_version_;
      grain_generation_ = kGrainGeneration | (grain_generation_ + 1);
      submitted_id_ = applied_id_ = id;
      // A drag submits every frame: the tracer waits until 150 ms after the last change.
      hold_until_ns_.store(
          std::chrono::duration_cast<std::chrono::nanoseconds>(
              (std::chrono::steady_clock::now() + std::chrono::milliseconds(150)).time_since_epoch())
              .count());
      cv_.notify_all();
      return;
    }
    pending_.emplace(scene, id);
    submitted_id_ = id;
  }
  // The render in flight is for a scene the user has just left: stop it now, from this thread,
  // so that its workers free the cores before the feed thread (which has to be scheduled first)
  // restarts. A restart that this catches half-way is superseded by the pending scene anyway.
  renderer_.interrupt();
  grain_cancel_.store(true);
  cv_.notify_all();
}

void RenderFeed::run() {
  std::unique_lock<std::mutex> lock(mu_);
  std::uint64_t restarts = 0;  // the renderer's generation counts successful restarts
  for (;;) {
    cv_.wait(lock, [&] { return quit_ || pending_.has_value(); });
    if (quit_) return;
    auto [scene, id] = std::move(*pending_);
    pending_.reset();
    busy_ = true;
    grain_cancel_.store(false);  // under the lock: a later submit() raises it again
    lock.unlock();
    // Grain mounts and sections with relief (plane light or between the polars): traced on this
    // thread, not by the progressive renderer (the slab is cached, so a polarizer or focus change
    // does not rebuild it).
    ResponseKind kind = ResponseKind::None;
    try {
      kind = response_kind(scene);
    } catch (const std::exception&) {
      // An unloadable section: the renderer's restart below reports it.
    }
    const bool grains = kind == ResponseKind::Traced;
    std::optional<Failure> failed;
    try {
      if (grains) {
        check_scene(scene);
        renderer_.cancel();  // the cores are the grain mount's now
      } else {
        renderer_.restart(scene);
      }
    } catch (const std::exception& e) {
      failed = Failure{id, e.what()};
    }
    lock.lock();
    busy_ = false;
    if (failed) {
      failure_ = failed;
    } else {
      applied_id_ = id;
      grains_mode_ = grains;
      figure_mode_ = false;
      source_.reset();
      ++source_epoch_;
      if (grains) {
        grain_generation_ = kGrainGeneration | (grain_generation_ + 1);
        grain_running_ = true;
        source_scene_ = scene;
        instrument_ = instrument_settings(scene);
        ++instrument_version_;
        ++response_version_;
      } else {
        renderer_generation_ = ++restarts;
      }
    }
    cv_.notify_all();
    if (!failed && grains) {
      lock.unlock();
      render_grains(scene);
      lock.lock();
      grain_running_ = false;
      cv_.notify_all();
    } else if (!failed && (kind == ResponseKind::Figure || kind == ResponseKind::Flat)) {
      lock.unlock();
      render_figure(scene, id);
      lock.lock();
    }
  }
}

void RenderFeed::render_figure(const Scene& scene, std::uint64_t id) {
  // The renderer's own render first: its first images come in milliseconds, and its converged
  // level is the probes' (a newer submission, which raises grain_cancel_, ends the wait).
  RenderImage own;
  for (;;) {
    if (grain_cancel_.load()) return;
    if (renderer_.wait(0.02)) break;
  }
  if (!renderer_.snapshot(own) || own.stopped.empty()) return;
  std::optional<FigureResponse> figure;
  try {
    tbb::task_arena arena(threads_ > 0 ? threads_ : static_cast<int>(tbb::task_arena::automatic));
    arena.execute([&] { figure = render_figure_probes(scene, own, threads_, &grain_cancel_); });
  } catch (const std::exception&) {
    return;  // the renderer rendered this scene: the figure stays the renderer's
  }
  std::lock_guard<std::mutex> lock(mu_);
  if (!figure || pending_ || busy_ || applied_id_ != id || submitted_id_ != id) return;
  source_.emplace(std::make_shared<const FigureResponse>(std::move(*figure)));
  source_scene_ = scene;
  figure_mode_ = true;
  // Until the first composition the renderer's image stays on screen (snapshot() reports nothing
  // new), not an image composed for an earlier scene.
  composed_ = RenderImage{};
  composed_response_ = composed_instrument_ = ~0ull;
  ++source_epoch_;
  instrument_ = instrument_settings(scene);
  ++instrument_version_;
  ++response_version_;
  grain_generation_ = kGrainGeneration | (grain_generation_ + 1);
  cv_.notify_all();
}

void RenderFeed::render_grains(const Scene& scene) {
  try {
    // In the app's --threads, as the progressive renderer (the traced response is otherwise free
    // to take every core); held while the stage is dragged, so that composing and drawing get the cores.
    render_instrument_response(
        scene, ResponseCoverage::Disc,
        [&](const InstrumentResponse& r) {
          std::lock_guard<std::mutex> lock(mu_);
          source_ = r;
          ++response_version_;
          cv_.notify_all();
        },
        &grain_cancel_, threads_,
        [this] {
          return std::chrono::steady_clock::now().time_since_epoch().count() <
                 std::chrono::steady_clock::duration(std::chrono::nanoseconds(hold_until_ns_.load())).count();
        });
  } catch (const std::exception& e) {
    // Passed the scene check but the mount could not be built (e.g. an unknown mineral name):
    // reported like a refused scene.
    std::lock_guard<std::mutex> lock(mu_);
    failure_ = Failure{applied_id_, e.what()};
  }
}

void RenderFeed::compose_loop() {
  std::unique_lock<std::mutex> lock(mu_);
  for (;;) {
    cv_.wait(lock, [&] {
      return quit_ || (composing() && source_ && !source_->empty() &&
                       (composed_response_ != response_version_ || composed_instrument_ != instrument_version_));
    });
    if (quit_) return;
    const InstrumentResponse source = *source_;  // shares the immutable response
    const InstrumentSettings instrument = instrument_;
    const std::uint64_t rv = response_version_, iv = instrument_version_, generation = grain_generation_,
                        epoch = source_epoch_;
    lock.unlock();
    RenderImage img = source.compose(instrument);
    img.generation = generation;
    lock.lock();
    if (epoch != source_epoch_) continue;  // composed from a response that has since been replaced
    composed_ = std::move(img);
    composed_response_ = rv;
    composed_instrument_ = iv;
    cv_.notify_all();
  }
}

std::optional<RenderFeed::Failure> RenderFeed::take_failure() {
  std::lock_guard<std::mutex> lock(mu_);
  auto f = failure_;
  failure_.reset();
  return f;
}

bool RenderFeed::snapshot(RenderImage& out, bool& current) const {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (composing()) {
      const bool changed =
          composed_.width > 0 && (out.generation != composed_.generation || out.passes != composed_.passes ||
                                  out.width != composed_.width || out.stopped != composed_.stopped);
      if (changed) out = composed_;
      current = !busy_ && !pending_ && applied_id_ == submitted_id_ && out.generation == grain_generation_;
      return changed;
    }
  }
  const bool changed = renderer_.snapshot(out);
  std::lock_guard<std::mutex> lock(mu_);
  current = !busy_ && !pending_ && applied_id_ == submitted_id_ && out.generation == renderer_generation_;
  return changed;
}

bool RenderFeed::wait(double timeout_s) const {
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                             std::chrono::duration<double>(std::min(timeout_s, 1e6)));
  {
    std::unique_lock<std::mutex> lock(mu_);
    if (!cv_.wait_until(lock, deadline, [&] { return quit_ || (!busy_ && !pending_); })) return false;
    if (figure_mode_) {
      // Composed from the figure's response: done when the newest settings are composed.
      if (!cv_.wait_until(lock, deadline, [&] {
            return quit_ || pending_ || !figure_mode_ ||
                   (composed_response_ == response_version_ && composed_instrument_ == instrument_version_);
          }))
        return false;
      if (figure_mode_ && !pending_) return true;
      // Otherwise a newer scene took over: wait for it below, as for any other.
    }
    if (grains_mode_) {
      if (!cv_.wait_until(lock, deadline, [&] { return quit_ || pending_ || !grain_running_; })) return false;
      // Rendered: stopped at the tolerance or at its cap (the image says which).
      const std::string stopped = source_ ? source_->status().stopped : std::string();
      return !pending_ && (stopped == "tolerance" || stopped == "cap");
    }
  }
  const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
  return left > 0 && renderer_.wait(left);
}

}  // namespace pmsim::ui
