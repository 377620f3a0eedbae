// BuildCache (core/base/build_cache.h): a key is built once however many callers ask for it at
// once; a build that throws leaves nothing behind; and, in the Keep::All cache, a lookup of one key
// does not wait while another key builds (the app's UI thread asks for the section it shows while a
// worker grows another rock). No timing is asserted: the tests order the threads by futures, with a
// generous timeout only so that a regression fails instead of hanging.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/base/build_cache.h"

namespace {

using pmsim::BuildCache;
using pmsim::Keep;

TEST(BuildCache, OneKeyIsBuiltOnceByConcurrentCallers) {
  BuildCache<int, std::string> cache;
  std::atomic<int> builds{0};
  std::vector<std::thread> callers;
  std::vector<std::shared_ptr<const std::string>> got(8);
  for (int t = 0; t < 8; ++t)
    callers.emplace_back([&, t] {
      got[t] = cache.get(7, [&] {
        ++builds;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));  // let the others arrive meanwhile
        return std::make_shared<const std::string>("seven");
      });
    });
  for (std::thread& c : callers) c.join();
  EXPECT_EQ(builds.load(), 1);
  for (const auto& g : got) EXPECT_EQ(g.get(), got[0].get());  // the one value, shared
}

TEST(BuildCache, AThrowingBuildLeavesNothingBehind) {
  BuildCache<int, std::string> all;
  EXPECT_THROW(all.get(1, []() -> std::shared_ptr<const std::string> { throw std::runtime_error("bad file"); }),
               std::runtime_error);
  EXPECT_EQ(*all.get(1, [] { return std::make_shared<const std::string>("built again"); }), "built again");
  BuildCache<int, std::string, Keep::Last> last;
  EXPECT_EQ(*last.get(1, [] { return std::make_shared<const std::string>("one"); }), "one");
  EXPECT_THROW(last.get(2, []() -> std::shared_ptr<const std::string> { throw std::runtime_error("bad"); }),
               std::runtime_error);
  int builds = 0;
  last.get(1, [&] {
    ++builds;
    return std::make_shared<const std::string>("one");
  });
  EXPECT_EQ(builds, 1);  // Keep::Last freed the old value before the failed build: it is rebuilt
}

TEST(BuildCache, AKeptKeyIsServedWhileAnotherKeyBuilds) {
  BuildCache<int, std::string> cache;
  cache.get(1, [] { return std::make_shared<const std::string>("grown"); });
  std::promise<void> started, release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> slow_built{false};
  std::thread slow([&] {
    cache.get(2, [&] {
      started.set_value();
      // Held until the main thread has read key 1 (or 30 s, so that a cache that serialises every
      // key fails the assertion below rather than hanging the suite).
      released.wait_for(std::chrono::seconds(30));
      slow_built = true;  // still inside the build: a serialising cache serves key 1 only after this
      return std::make_shared<const std::string>("slow");
    });
  });
  started.get_future().wait();
  EXPECT_EQ(*cache.get(1, [] { return std::make_shared<const std::string>("rebuilt"); }), "grown");
  EXPECT_FALSE(slow_built.load()) << "key 1 was served only after key 2's build had finished";
  release.set_value();
  slow.join();
  EXPECT_EQ(*cache.get(2, [] { return std::make_shared<const std::string>("rebuilt"); }), "slow");
}

// A build may ask the same cache for another key (a rock's section reading a mineral table kept
// in the same cache type): with one lock for every key it waited on itself.
TEST(BuildCache, ABuildMayAskForAnotherKey) {
  // On the heap and the thread detached: if the nested get deadlocks, the test fails after 30 s
  // and the blocked thread dies with the process instead of hanging it.
  auto* cache = new BuildCache<int, std::string>;
  auto result = std::make_shared<std::promise<std::string>>();
  std::future<std::string> got = result->get_future();
  std::thread([cache, result] {
    const auto v = cache->get(1, [cache] {
      const auto inner = cache->get(2, [] { return std::make_shared<const std::string>("inner"); });
      return std::make_shared<const std::string>("outer+" + *inner);
    });
    result->set_value(*v);
  }).detach();
  ASSERT_EQ(got.wait_for(std::chrono::seconds(30)), std::future_status::ready) << "the nested get deadlocked";
  EXPECT_EQ(got.get(), "outer+inner");
  delete cache;
}

}  // namespace
