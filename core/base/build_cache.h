#pragma once
// The one cache type of core: things expensive to build (a thin section read and tiled, a slab of
// ~10⁶ triangles, a grain mount, a lens-ghost table, an EBSD map's section), kept between calls
// and keyed by everything they depend on. Two policies:
//  - Keep::Last — the specimen the app looks at: the app shows one field at a time, and a focus,
//    polarizer or stage-angle change must restart the image without rebuilding (seconds); another
//    key frees the old value before building, so two are never held (a slab can take a GB);
//  - Keep::All — small things read once per process (sections, tables), kept for its life.
// Two callers with the same key build it once: Keep::Last builds under the cache's one lock (one
// value at a time, by design); Keep::All under the key's own lock, so that a lookup of one key
// never waits while another key builds (the app asks for the section it shows on its UI thread
// while a worker grows another rock). A build that throws leaves the cache as it was
// (Keep::Last: empty). It runs isolated (tbb::this_task_arena::isolate): a build's own parallel
// loops (a rock's tiling, Embree's BVH) then never let the thread holding a lock take up an outer
// task that asks this cache again and waits on the lock it holds.
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
    if constexpr (policy == Keep::Last) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (last_ && last_key_ == key) return last_;
      last_.reset();
      std::shared_ptr<const T> v = isolated(build);
      last_key_ = key;
      last_ = v;
      return v;
    } else {
      std::shared_ptr<Slot> slot;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        std::shared_ptr<Slot>& s = kept_[key];
        if (!s) s = std::make_shared<Slot>();
        slot = s;
      }
      std::lock_guard<std::mutex> lock(slot->mutex);
      if (!slot->value) {
        try {
          slot->value = isolated(build);
        } catch (...) {
          std::lock_guard<std::mutex> map_lock(mutex_);
          if (const auto it = kept_.find(key); it != kept_.end() && it->second == slot) kept_.erase(it);
          throw;
        }
      }
      return slot->value;
    }
  }

 private:
  struct Slot {  // one key's value, built under its own lock
    std::mutex mutex;
    std::shared_ptr<const T> value;
  };

  template <class Build>
  static std::shared_ptr<const T> isolated(Build& build) {
    std::shared_ptr<const T> v;
    tbb::this_task_arena::isolate([&] { v = build(); });
    return v;
  }

  std::mutex mutex_;
  Key last_key_{};
  std::shared_ptr<const T> last_;
  std::map<Key, std::shared_ptr<Slot>> kept_;
};

}  // namespace pmsim
