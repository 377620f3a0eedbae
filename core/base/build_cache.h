#pragma once
// The one cache type of core: things expensive to build (a thin section read and tiled, a slab of
// ~10⁶ triangles, a grain mount, a lens-ghost table, an EBSD map's section), kept between calls
// and keyed by everything they depend on. Two policies:
//  - Keep::Last — the specimen the app looks at: the app shows one field at a time, and a focus,
//    polarizer or stage-angle change must restart the image without rebuilding (seconds); another
//    key frees the old value before building, so two are never held (a slab can take a GB);
//  - Keep::All — small things read once per process (sections, tables), kept for its life.
// The build runs under the cache's lock, so that two callers with the same key build it once; a
// build that throws leaves the cache as it was (Keep::Last: empty). It runs isolated
// (tbb::this_task_arena::isolate): a build's own parallel loops (a rock's tiling, Embree's BVH)
// then never let the thread holding the lock take up an outer task that asks this cache again
// and waits on the lock it holds.
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include <tbb/task_arena.h>

namespace pmsim {

enum class Keep { Last, All };

template <class Key, class T, Keep policy = Keep::All>
class BuildCache {
 public:
  // The value of `key`, from `build()` (returning std::shared_ptr<const T> or <T>) the first time.
  template <class Build>
  std::shared_ptr<const T> get(const Key& key, Build build) {
    std::lock_guard<std::mutex> lock(mutex_);
    if constexpr (policy == Keep::Last) {
      if (last_ && last_key_ == key) return last_;
      last_.reset();
      std::shared_ptr<const T> v = isolated(build);
      last_key_ = key;
      last_ = v;
      return v;
    } else {
      if (const auto it = kept_.find(key); it != kept_.end()) return it->second;
      std::shared_ptr<const T> v = isolated(build);
      kept_.emplace(key, v);
      return v;
    }
  }

 private:
  template <class Build>
  static std::shared_ptr<const T> isolated(Build& build) {
    std::shared_ptr<const T> v;
    tbb::this_task_arena::isolate([&] { v = build(); });
    return v;
  }

  std::mutex mutex_;
  Key last_key_{};
  std::shared_ptr<const T> last_;
  std::map<Key, std::shared_ptr<const T>> kept_;
};

}  // namespace pmsim
