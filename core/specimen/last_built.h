#pragma once
// The one specimen kept between renders (a grain mount, a section slab): the app looks at one
// field at a time, and a focus, polarizer or stage-angle change must restart the image without
// rebuilding ~10⁶ triangles (seconds). Keyed by what the geometry depends on; another key frees
// the old one before building (two are never held by the cache), under the lock, so that two
// callers with the same key build it once.
#include <memory>
#include <mutex>
#include <string>

namespace pmsim {

template <class T>
class LastBuilt {
 public:
  template <class Build>
  std::shared_ptr<const T> get(const std::string& key, Build build) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!last_ || key_ != key) {
      last_.reset();
      last_ = build();
      key_ = key;
    }
    return last_;
  }

 private:
  std::mutex mutex_;
  std::string key_;
  std::shared_ptr<const T> last_;
};

}  // namespace pmsim
