// Myrmekite (core/texture/myrmekite.h, issue 22's intergrowths): a bulb's shape, its quartz rods'
// share, and the boundary search that places bulbs.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "core/base/input_error.h"
#include "core/texture/myrmekite.h"
#include "core/texture/rock_recipe.h"

namespace pmsim {
namespace {

// A bulb is half an ellipse on the K-feldspar side of its root: the root itself and the point
// depth_mm out along `out` are in it (to 1e-12 mm, the rounding of the two dot products), the
// point as far behind the root is not, nor one just beyond the front or the flank.
TEST(Myrmekite, BulbIsHalfAnEllipseOnTheHostSide) {
  MyrmekiteBulb b;
  b.root_mm = {1.0, -2.0};
  b.out = glm::normalize(glm::dvec2(3.0, 4.0));
  b.depth_mm = 0.15;
  b.half_width_mm = 0.1;
  const glm::dvec2 across{-b.out.y, b.out.x};
  EXPECT_TRUE(in_bulb(b, b.root_mm));
  EXPECT_TRUE(in_bulb(b, b.root_mm + (b.depth_mm - 1e-12) * b.out));
  EXPECT_FALSE(in_bulb(b, b.root_mm + (b.depth_mm + 1e-9) * b.out));
  EXPECT_FALSE(in_bulb(b, b.root_mm - 0.5 * b.depth_mm * b.out));
  EXPECT_TRUE(in_bulb(b, b.root_mm + (b.half_width_mm - 1e-12) * across));
  EXPECT_FALSE(in_bulb(b, b.root_mm + (b.half_width_mm + 1e-9) * across));
}

// The rods take width/spacing of the arc at every depth, so of the bulb's area: counted on a
// 0.5 µm grid over a bulb 0.15 mm deep and 0.3 mm wide with rods 4 µm wide every 20 µm, 0.2.
// Tolerance 0.01: the bulb holds ~10 rods across, and its elliptic outline cuts the outermost
// ones where their phase puts them (measured 0.1975–0.2015 over eight hashes, 1.4·10⁵ points each).
// The rods are also thin: no run across them at mid-depth is much wider than a rod.
TEST(Myrmekite, RodsTakeTheirWidthOverSpacingOfTheBulb) {
  for (std::uint64_t hash : {1ull, 2ull, 77ull, 12345ull}) {
    MyrmekiteBulb b;
    b.out = {0.0, 1.0};
    b.depth_mm = 0.15;
    b.half_width_mm = 0.15;
    b.hash = hash;
    const Vermicules v{0.004, 0.02};
    long in = 0, rod = 0;
    const double h = 0.0005;
    for (double y = 0.5 * h; y < b.depth_mm; y += h)
      for (double x = -b.half_width_mm; x < b.half_width_mm; x += h) {
        if (!in_bulb(b, {x, y})) continue;
        ++in;
        rod += in_vermicule(b, v, {x, y});
      }
    ASSERT_GT(in, 50000);
    EXPECT_NEAR(double(rod) / double(in), 0.2, 0.01) << "hash " << hash;
    // Runs across the bulb at mid-depth: a rod's run is about its width, more where it wriggles
    // across the line at a slant (measured 4.6–4.8 µm for 4 µm rods); allow 8 µm, against the
    // 20 µm from one rod to the next, which a merged pair would exceed.
    double run = 0.0, widest = 0.0;
    int runs = 0;
    for (double x = -0.1; x < 0.1; x += 1e-4) {
      if (in_vermicule(b, v, {x, 0.075})) {
        run += 1e-4;
        widest = std::max(widest, run);
      } else if (run > 0.0) {
        ++runs;
        run = 0.0;
      }
    }
    EXPECT_LE(widest, 2.0 * v.width_mm) << "hash " << hash;
    EXPECT_GE(runs, 7) << "hash " << hash;  // 0.2 mm of arc at mid-depth: about ten rods
  }
}

// The boundary search finds where a disc of radius 0.7 ends along any ray from inside it, to the
// tolerance asked (1 µm: the bisection's stop), and reports no exit for a ray that stays inside.
TEST(Myrmekite, RayExitFindsTheBoundaryToTheTolerance) {
  const auto disc = [](const glm::dvec2& p) { return glm::length(p - glm::dvec2(0.2, 0.1)) < 0.7; };
  for (double a = 0.0; a < 6.28; a += 0.37) {
    const glm::dvec2 dir{std::cos(a), std::sin(a)};
    const glm::dvec2 from{0.2, 0.1};
    const auto t = ray_exit_mm(disc, from, dir, 2.0, 0.02, 0.001);
    ASSERT_TRUE(t.has_value());
    EXPECT_NEAR(*t, 0.7, 0.001);
  }
  EXPECT_FALSE(ray_exit_mm(disc, {0.2, 0.1}, {1.0, 0.0}, 0.5, 0.02, 0.001).has_value());
  // A ray starting outside enters first, then leaves: the far side.
  const auto t = ray_exit_mm(disc, {-1.0, 0.1}, {1.0, 0.0}, 3.0, 0.02, 0.001);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 1.9, 0.001);
}

// A recipe whose myrmekite has no host phase in the rock is refused naming the key and value.
TEST(Myrmekite, RecipeWithoutItsHostPhaseIsRefused) {
  const std::filesystem::path f = std::filesystem::temp_directory_path() / "pmsim_myrmekite_recipe.json";
  {
    std::ofstream o(f);
    o << R"({"type": "rock", "name": "t", "size_mm": [4, 3], "thickness_um": 30, "source": "test",
      "phases": [
        {"name": "plagioclase", "mineral": "plagioclase:An30", "mode_percent": 60, "csd": {"slope_per_mm": -1, "min_mm": 0.5, "max_mm": 2},
         "myrmekite": {"host": "orthoclase", "depth_mm": 0.1, "bulb_mm": 0.2, "quartz": {"width_mm": 0.004, "spacing_mm": 0.02}}},
        {"name": "quartz", "mineral": "quartz", "mode_percent": 40, "csd": {"slope_per_mm": -1, "min_mm": 0.5, "max_mm": 2}}]})";
  }
  try {
    (void)read_rock_recipe(f.string());
    FAIL() << "accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("phases[0].myrmekite.host"), std::string::npos) << what;
    EXPECT_NE(what.find("orthoclase"), std::string::npos) << what;
  }
  std::filesystem::remove(f);
}

}  // namespace
}  // namespace pmsim
