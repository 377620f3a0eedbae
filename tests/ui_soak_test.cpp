// A soak of random control changes: widgets' scene keys, shortcut keys, drags on the field,
// probes and bad values, thousands of them with the renderer restarting under each. No crash,
// every frame drawn, memory flat, and the renderer still converges at the end.
// PMSIM_LONG_TESTS=1 runs ten times as many.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>

#include "ui/headless_driver.h"
#include "ui/script.h"

namespace pmsim::ui {
namespace {

double rss_mb() {
  std::ifstream statm("/proc/self/statm");
  long pages_total = 0, pages_resident = 0;
  statm >> pages_total >> pages_resident;
  return static_cast<double>(pages_resident) * sysconf(_SC_PAGESIZE) / (1024.0 * 1024.0);
}

std::string random_setting(std::mt19937& rng) {
  auto pick = [&](std::initializer_list<const char*> v) {
    return std::string(v.begin()[std::uniform_int_distribution<size_t>(0, v.size() - 1)(rng)]);
  };
  auto num = [&](double a, double b) {
    return std::to_string(std::uniform_real_distribution<double>(a, b)(rng));
  };
  switch (std::uniform_int_distribution<int>(0, 15)(rng)) {
    case 0:
      return "stage_deg=" + num(-720, 720);
    case 1:
      return "polarizer_deg=" + num(0, 360);
    case 2:
      return "analyzer_deg=" + num(0, 360);
    case 3:
      return "analyzer=" + pick({"in", "out"});
    case 4:
      return "mode=" + pick({"ortho", "cono"});
    case 5:
      return "bertrand=" + pick({"in", "out"});
    case 6:
      return "compensator=" + pick({"none", "gypsum", "mica", "quartz_wedge"});
    case 7:
      return "compensator_position=" + num(0, 1);
    case 8:
      return "objective.na=" + pick({"0.10", "0.25", "0.65", "0.85"});
    case 9:
      return "illuminant=" + pick({"D65", "A"});
    case 10:
      return "sample.mineral=" + pick({"quartz", "calcite", "muscovite", "biotite", "olivine", "gypsum",
                                       "augite", "plagioclase"});
    case 11:
      return "sample.thickness_um=" + num(1, 200);
    case 12:
      return "sample.optic_axis=[" + num(-1, 1) + "," + num(-1, 1) + "," + num(-1, 1) + "]";
    case 13:
      return "sample.type=" + pick({"plate", "wedge", "plate"});
    case 14:
      return "sample.present=" + pick({"true", "false", "true"});
    default:  // bad input: must raise the banner and change nothing
      return pick({"sample.thickness_um=-1", "objective.na=7", "sample.mineral=kryptonite", "mode=sideways",
                   "stage_deg=nan"});
  }
}

// Two changes per frame: a script may change several controls between frames, and it halves the
// software-GL drawing time of the in-CI run.
constexpr int kChangesPerFrame = 2;

void soak(int changes) {
  Scene s;
  s.render.width = s.render.height = 64;
  std::string log;
  auto d = HeadlessDriver::create(s, 1280, 800, log);
  ASSERT_TRUE(d) << log;
  std::mt19937 rng(20261122);
  const std::vector<int> keys = {'A', 'B', 'C', 'G', 'X', 'L', 'S', '1', '2', '3', '4'};
  const Layout& l = d->app().layout();

  // Warm up (fonts, first textures, worker threads) before the memory baseline.
  for (int i = 0; i < 100; ++i) d->frame();
  const double rss_start = rss_mb();
  const auto t0 = std::chrono::steady_clock::now();
  const auto frames_before = d->app().counters().frames;
  const auto uploads_before = d->app().counters().uploads;
  int frames = 0;
  for (int i = 0; i < changes; ++i) {
    const bool draw = (i + 1) % kChangesPerFrame == 0;
    const int kind = std::uniform_int_distribution<int>(0, 9)(rng);
    if (kind < 6) {
      d->app().set(random_setting(rng));
    } else if (kind < 8) {
      d->inject_key(keys[std::uniform_int_distribution<size_t>(0, keys.size() - 1)(rng)], false, false);
    } else {
      // Mouse on the field: press, move, release over the next frames.
      std::uniform_real_distribution<float> fx(l.field.x, l.field.x + l.field.w),
          fy(l.field.y, l.field.y + l.field.h);
      d->inject_mouse(fx(rng), fy(rng), kind == 9);
    }
    if (!draw) continue;
    ASSERT_TRUE(d->frame());
    ++frames;
  }
  d->release_mouse();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double rss_end = rss_mb();
  const auto& c = d->app().counters();
  std::printf(
      "[soak] %d changes, %d frames in %.1f s (%.1f fps), renderer images shown %llu, "
      "rejected %llu, RSS start %.1f MB end %.1f MB\n",
      changes, frames, seconds, frames / seconds, static_cast<unsigned long long>(c.uploads - uploads_before),
      static_cast<unsigned long long>(c.rejected), rss_start, rss_end);
  // Every frame was built and presented.
  EXPECT_EQ(c.frames - frames_before, static_cast<std::uint64_t>(frames));
  EXPECT_GE(d->frame_times().ms.size(), static_cast<size_t>(frames));
  EXPECT_GT(c.uploads - uploads_before, 0u) << "the field never updated";
  EXPECT_GT(c.rejected, 0u) << "the bad values were not refused";
  // Flat memory: the process's allocations are bounded (textures are reused, frame times are
  // capped, renderer buffers are per image size); 48 MB tolerates allocator fragmentation and
  // the mineral/section caches filling, not a leak per change.
  EXPECT_LT(rss_end - rss_start, 48.0);
  // The renderer is not wedged: a last clean scene still converges.
  ASSERT_TRUE(d->app().set("sample.present=true"));
  ASSERT_TRUE(d->app().set("mode=ortho"));
  EXPECT_TRUE(settle(*d, 120));
}

TEST(UiSoak, ThousandsOfRandomControlChangesDrawEveryFrameWithFlatMemory) {
  const bool long_run = std::getenv("PMSIM_LONG_TESTS") != nullptr;
  soak(long_run ? 30000 : 2000);
}

}  // namespace
}  // namespace pmsim::ui
