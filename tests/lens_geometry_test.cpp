// Lens geometry: JSON spec, thickness/ledge relation, validation, ray–surface intersection.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>
#include <random>

#include "core/base/input_error.h"
#include "core/lens/lens.h"

using namespace pmsim;
using json = nlohmann::json;

namespace {
json issue_example() {
  return json::parse(R"({"glass": "N-BK7", "center": [0,0,0], "axis": [0,0,1], "radius_mm": 4.25,
    "front": {"radius_mm": 8.0}, "back": {"radius_mm": -8.0}, "ledge_mm": 0.3, "medium": "air"})");
}
std::string key_of_error(const json& j) {
  try {
    LensGeometry g(lens_spec_from_json(j, "x.json"));
  } catch (const InputError& e) {
    return e.key;
  }
  return "<no error>";
}
}  // namespace

TEST(LensSpecJson, IssueExampleGivesVertexThicknessFromLedgeAndSags) {
  const LensSpec s = lens_spec_from_json(issue_example());
  const LensGeometry g(s);
  // Sag of R = 8 at r = 4.25: 8 − √(64 − 18.0625); thickness = ledge + 2·sag. Same formula in
  // another arrangement: agreement to rounding (1e-14 mm).
  const double sag = 8.0 - std::sqrt(64.0 - 4.25 * 4.25);
  EXPECT_NEAR(g.thickness_mm(), 0.3 + 2 * sag, 1e-14);
  EXPECT_NEAR(g.ledge_mm(), 0.3, 1e-15);
  EXPECT_NEAR(glm::length(g.front_vertex() - glm::dvec3(0, 0, -g.thickness_mm() / 2)), 0.0, 1e-15);
}

TEST(LensSpecJson, ThicknessAndLedgeMustAgree) {
  json j = issue_example();
  const double T = LensGeometry(lens_spec_from_json(j)).thickness_mm();
  j["thickness_mm"] = T;  // consistent to rounding (≪ 1e-9 mm)
  EXPECT_NO_THROW(LensGeometry(lens_spec_from_json(j)));
  j["thickness_mm"] = T + 2e-9;  // beyond the 1e-9 mm the contract allows
  EXPECT_EQ(key_of_error(j), "ledge_mm");
  j.erase("ledge_mm");
  EXPECT_NO_THROW(LensGeometry(lens_spec_from_json(j)));
}

TEST(LensSpecJson, BadInputNamesTheKey) {
  json j = issue_example();
  j["front"]["radius_mm"] = 4.0;  // |R| smaller than the aperture
  EXPECT_EQ(key_of_error(j), "front.radius_mm");
  j = issue_example();
  j["ledge_mm"] = -0.5;  // caps cross inside the aperture
  EXPECT_EQ(key_of_error(j), "ledge_mm");
  j = issue_example();
  j["radius_mm"] = "big";
  EXPECT_EQ(key_of_error(j), "radius_mm");
  j = issue_example();
  j["axis"] = {0, 0, 0};
  EXPECT_EQ(key_of_error(j), "axis");
  j = issue_example();
  j["thikness_mm"] = 1.0;
  EXPECT_EQ(key_of_error(j), "thikness_mm");
  j = issue_example();
  j.erase("ledge_mm");
  EXPECT_EQ(key_of_error(j), "ledge_mm");
  j = issue_example();
  j["back"] = {{"radius_mm", 5.0}};  // meniscus whose caps cross: thickness would be < 0
  j["front"] = {{"radius_mm", -5.0}};
  EXPECT_EQ(key_of_error(j), "ledge_mm");
  // Lengths beyond a kilometre (fuzz finding T1: a centre at 3e105 mm made the tracer's algebra
  // overflow into NaN) are refused with the key; a kilometre itself is accepted.
  j = issue_example();
  j["center"] = {0, -3e105, 0};
  EXPECT_EQ(key_of_error(j), "center[1]");
  j["center"] = {1e6, 0, 0};
  EXPECT_NO_THROW(LensGeometry(lens_spec_from_json(j)));
  j = issue_example();
  j["back"] = {{"radius_mm", -2e9}};
  EXPECT_EQ(key_of_error(j), "back.radius_mm");
  // Missing front object = plane.
  j = issue_example();
  j.erase("front");
  EXPECT_EQ(LensGeometry(lens_spec_from_json(j)).front_radius_mm(), 0.0);
}

TEST(LensIntersection, HitsLieOnTheSurfacesWithOutwardNormals) {
  // A tilted, displaced biconvex lens; random rays aimed at its bounding box.
  LensSpec s = lens_spec_from_json(issue_example());
  s.center = {1.0, -2.0, 0.5};
  s.axis = glm::normalize(glm::dvec3(1, 2, 3));
  const LensGeometry g(s);
  glm::dvec3 lo, hi;
  g.bounds(lo, hi);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n;
  std::uniform_real_distribution<double> u(0, 1);
  int hits = 0;
  for (int k = 0; k < 20000; ++k) {
    const glm::dvec3 target = lo + (hi - lo) * glm::dvec3(u(rng), u(rng), u(rng));
    const glm::dvec3 d = glm::normalize(glm::dvec3(n(rng), n(rng), n(rng)));
    const glm::dvec3 o = target - 30.0 * d;
    LensHit h;
    if (!g.intersect(o, d, 1e30, LensSurface::None, h)) continue;
    ++hits;
    // Inside the bounding box (1e-12 mm slack for rounding).
    ASSERT_TRUE(glm::all(glm::greaterThanEqual(h.point, lo - 1e-12)));
    ASSERT_TRUE(glm::all(glm::lessThanEqual(h.point, hi + 1e-12)));
    // From outside the first hit faces the ray: d·N < 0 (a convex solid).
    ASSERT_LT(glm::dot(d, h.normal), 0.0);
    ASSERT_NEAR(glm::length(h.normal), 1.0, 1e-14);
    const glm::dvec3 w = h.point - g.center();
    const double z = glm::dot(w, g.axis());
    const double r = glm::length(w - z * g.axis());
    ASSERT_LE(r, g.aperture_radius_mm() * (1 + 1e-12));
    if (h.surface == LensSurface::Front) {
      // On the sphere of radius 8 about front_vertex + 8·axis (1e-12 mm: rounding).
      ASSERT_NEAR(glm::length(h.point - (g.front_vertex() + 8.0 * g.axis())), 8.0, 1e-12);
    } else if (h.surface == LensSurface::Ledge) {
      ASSERT_NEAR(r, 4.25, 1e-12);
    }
    // Continue from the hit: the ray inside must find another surface ahead, never itself at t≈0.
    LensHit h2;
    ASSERT_TRUE(g.intersect(h.point, d, 1e30, h.surface, h2));
    ASSERT_GT(h2.t, 1e-9);
    ASSERT_GT(glm::dot(d, h2.normal), 0.0);  // leaving: outward normal along the ray
  }
  EXPECT_GT(hits, 5000);  // the box is well filled by the lens: most rays must hit
}

TEST(LensIntersection, RayAlongTheAxisHitsBothVerticesAndNeverTheLedge) {
  const LensGeometry g(lens_spec_from_json(issue_example()));
  LensHit h;
  ASSERT_TRUE(g.intersect({0, 0, -10}, {0, 0, 1}, 1e30, LensSurface::None, h));
  EXPECT_EQ(h.surface, LensSurface::Front);
  EXPECT_NEAR(h.point.z, -g.thickness_mm() / 2, 1e-14);
  ASSERT_TRUE(g.intersect(h.point, {0, 0, 1}, 1e30, LensSurface::Front, h));
  EXPECT_EQ(h.surface, LensSurface::Back);
  EXPECT_NEAR(h.t, g.thickness_mm(), 1e-14);
  // Miss: a ray parallel to the axis outside the aperture.
  EXPECT_FALSE(g.intersect({5, 0, -10}, {0, 0, 1}, 1e30, LensSurface::None, h));
}

TEST(LensAssets, ShippedLensFilesAreValidAndNameTheirSource) {
  int n = 0;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(PMSIM_SOURCE_DIR) + "/assets/lenses")) {
    if (e.path().extension() != ".json") continue;
    ++n;
    std::ifstream f(e.path());
    const json j = json::parse(f);
    EXPECT_TRUE(j.contains("source") && j["source"].is_string()) << e.path();
    // Parses, validates, and finds its glass and medium in the material library.
    EXPECT_NO_THROW(Lens(load_lens_spec(e.path().string()))) << e.path();
  }
  EXPECT_GE(n, 3);
  // The plano-convex N-SF11 lens: thin-lens estimate f = R/(n−1) with n_d = 1.78472; the thick-lens
  // effective focal length of a plano-convex lens is exactly R/(n−1), so 1e-3 mm covers the
  // catalogue-vs-Sellmeier n_d difference (≤ 1e-5 → 2.5e-4 mm).
  const Lens pc(load_lens_spec(std::string(PMSIM_SOURCE_DIR) + "/assets/lenses/planoconvex_nsf11.json"));
  const double nd = pc.media(587.5618).n_glass;
  EXPECT_NEAR(pc.geometry().front_radius_mm() / (nd - 1), 15.5 / 0.78472, 1e-3);
}
