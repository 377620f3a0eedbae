#include "ui/render_feed.h"

#include <chrono>

namespace pmsim::ui {

RenderFeed::RenderFeed(int renderer_threads) : renderer_(renderer_threads), thread_([this] { run(); }) {}

RenderFeed::~RenderFeed() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    quit_ = true;
  }
  cv_.notify_all();
  thread_.join();
  renderer_.cancel();
}

void RenderFeed::submit(const Scene& scene, std::uint64_t id) {
  {
    std::lock_guard<std::mutex> lock(mu_);
    pending_.emplace(scene, id);
    submitted_id_ = id;
  }
  // The render in flight is for a scene the user has just left: stop it now, from this thread,
  // so that its workers free the cores before the feed thread (which has to be scheduled first)
  // restarts. A restart that this catches half-way is superseded by the pending scene anyway.
  renderer_.interrupt();
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
    lock.unlock();
    std::optional<Failure> failed;
    try {
      renderer_.restart(scene);
    } catch (const std::exception& e) {
      failed = Failure{id, e.what()};
    }
    lock.lock();
    busy_ = false;
    if (failed) {
      failure_ = failed;
    } else {
      ++restarts;
      applied_id_ = id;
      renderer_generation_ = restarts;
    }
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
  }
  const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
  return left > 0 && renderer_.wait(left);
}

}  // namespace pmsim::ui
