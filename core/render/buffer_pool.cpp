#include "core/render/buffer_pool.h"

namespace pmsim {

std::vector<float> BufferPool::take(std::size_t n) {
  std::vector<float> v;
  {
    std::lock_guard<std::mutex> lock(mu_);
    for (auto it = spare_.begin(); it != spare_.end(); ++it)
      if (it->size() == n) {
        v = std::move(*it);
        spare_.erase(it);
        break;
      }
  }
  v.resize(n);  // no-op for a recycled buffer of that size
  return v;
}

void BufferPool::give(std::vector<float>&& v) {
  if (v.empty()) return;
  std::lock_guard<std::mutex> lock(mu_);
  if (spare_.size() < 6) spare_.push_back(std::move(v));
}

RenderImage image_with_buffers(BufferPool* pool, int w, int h) {
  RenderImage img;
  img.width = w;
  img.height = h;
  const std::size_t n = static_cast<std::size_t>(w) * h * 3;
  img.rgb = pool ? pool->take(n) : std::vector<float>(n);
  img.xyz = pool ? pool->take(n) : std::vector<float>(n);
  return img;
}

}  // namespace pmsim
