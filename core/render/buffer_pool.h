#pragma once
#include <cstddef>
#include <mutex>
#include <vector>

#include "core/render/render_image.h"

namespace pmsim {

// Image buffers handed back by the images a renderer replaces, for the next ones. A 512² image is
// two 3 MB buffers; fresh ones cost ~3 ms of page faults and zero-filling on these machines,
// which was half of a preview (a restart on every slider step makes a preview every frame).
class BufferPool {
 public:
  // A buffer of exactly n floats, contents unspecified (every element is written by the caller).
  std::vector<float> take(std::size_t n);
  // Keeps a buffer for a later take (up to six; an empty one is dropped). Thread-safe.
  void give(std::vector<float>&& v);

 private:
  std::mutex mu_;
  std::vector<std::vector<float>> spare_;
};

// An image of w×h pixels whose rgb and xyz buffers (w·h·3 floats each, contents unspecified) come
// from the pool when there is one.
RenderImage image_with_buffers(BufferPool* pool, int w, int h);

}  // namespace pmsim
