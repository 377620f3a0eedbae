// Inclusions in a grain (SectionGrain::InclusionSet): their area, their limit, their domains and
// the reader's refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <nlohmann/json.hpp>

#include "core/base/input_error.h"
#include "core/microscope/section_map.h"

using namespace pmsim;

namespace {

nlohmann::json garnet_with_inclusions(double size_mm, double spacing_mm) {
  return {{"type", "section"},
          {"size_mm", {3.0, 3.0}},
          {"grains",
           {{{"mineral", "almandine"},
             {"centre_mm", {0.0, 0.0}},
             {"size_mm", 2.0},
             {"euler_deg", {0.0, 0.0, 0.0}},
             {"inclusions",
              {{"mineral", "quartz"},
               {"size_mm", size_mm},
               {"aspect", 2.0},
               {"spacing_mm", spacing_mm},
               {"trail_spacing_mm", 0.08},
               {"fraction", 0.5},
               {"within", 0.8},
               {"euler_deg", {{0, 0, 0}, {30, 60, 90}, {200, 10, 40}}}}}}}}};
}

}  // namespace

TEST(SectionInclusions, CoverTheirExpectedShareInsideTheirLimitAndNothingOutside) {
  const SectionMap m = section_from_json(garnet_with_inclusions(0.04, 0.1), "inclusions");
  ASSERT_EQ(m.grains.size(), 1u);
  const SectionGrain& g = m.grains[0];
  ASSERT_TRUE(g.inclusions);
  EXPECT_EQ(m.domain_count(), g.first_inclusion_domain() + 3);
  const double R = g.semi_major_mm;  // an equant garnet: a disc of radius R, s = r/R
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  long inner = 0, inner_hits = 0, ring = 0, ring_hits = 0;
  for (int i = 0; i < 400000; ++i) {
    const glm::dvec2 p{R * u(rng), R * u(rng)};
    const double r = std::hypot(p.x, p.y) / R;
    const int d = m.domain_at(p);
    const bool hit = m.domain_part(d).inclusion >= 0;
    if (hit) {
      EXPECT_EQ(m.mineral_of_domain(d), "quartz");
      EXPECT_EQ(m.grain_label(d), 1);
      EXPECT_LT(m.domain_part(d).inclusion, 3);
    }
    if (r < 0.7) {
      ++inner;
      inner_hits += hit;
    } else if (r > 0.82 && r < 0.95) {
      ++ring;
      ring_hits += hit;
    }
  }
  // Each 0.1 × 0.08 mm cell holds an ellipse of 0.04 × 0.02 mm with probability 0.5: a share of
  // 0.5·(π/4)·0.04·0.02/0.008 = 0.0393. About 190 cells lie within 0.7 R: the occupied count is
  // binomial with a relative standard deviation of √(0.5/(0.5·190)) ≈ 7 %; 25 % is 3.5 σ.
  const double expected = 0.5 * 0.25 * M_PI * 0.04 * 0.02 / (0.1 * 0.08);
  EXPECT_NEAR(static_cast<double>(inner_hits) / inner, expected, 0.25 * expected);
  // Beyond `within` (0.8 of the way to the rim) the garnet is clear.
  EXPECT_GT(ring, 10000);
  EXPECT_EQ(ring_hits, 0);
}

TEST(SectionInclusions, RefuseInclusionsLargerThanTheirSpacing) {
  try {
    (void)section_from_json(garnet_with_inclusions(0.2, 0.1), "bad.json");
    FAIL() << "an inclusion longer than its site spacing was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("spacing_mm"), std::string::npos) << e.what();
  }
}

namespace {

// A biotite flake (cleavage in the section's plane rotated to stand upright: euler Φ 90°) with
// zircon inclusions 30 × 15 µm, each in a pleochroic halo reaching `radius_mm` from its centre.
nlohmann::json biotite_with_haloes(const nlohmann::json& halo, const std::string& host = "biotite") {
  return {{"type", "section"},
          {"size_mm", {1.2, 1.2}},
          {"grains",
           {{{"mineral", host},
             {"centre_mm", {0.0, 0.0}},
             {"size_mm", 1.0},
             {"euler_deg", {0.0, 90.0, 0.0}},
             {"inclusions",
              {{"mineral", "zircon"},
               {"size_mm", 0.03},
               {"aspect", 2.0},
               {"spacing_mm", 0.2},
               {"trail_spacing_mm", 0.16},
               {"fraction", 0.5},
               {"euler_deg", {{0, 0, 0}, {40, 70, 10}}},
               {"halo", halo}}}}}}};
}

}  // namespace

// Every point of a halo lies within its radius of an inclusion's centre, so within radius + the
// inclusion's half-length (15 µm) of some zircon point; every point of the host outside the haloes
// lies beyond the radius from every centre, so farther than radius − 15 µm from every zircon point
// (a 2 µm grid: ± one grid step more). The halo is the host in its own orientation, its mineral
// biotite, its absorption 4 times the host's at every wavelength and vibration.
TEST(SectionInclusions, PleochroicHaloesRingTheirInclusionsAndDarkenTheHost) {
  const double radius = 0.05;
  const SectionMap m = section_from_json(biotite_with_haloes({{"radius_mm", radius}, {"darkening", 4.0}}), "haloes");
  const SectionGrain& g = m.grains[0];
  ASSERT_TRUE(g.has_halo());
  EXPECT_EQ(m.domain_count(), g.first_halo_domain() + g.crystal_domain_count());
  std::vector<glm::dvec2> zircon, halo, host;
  const double step = 0.002;
  for (double y = -0.3; y <= 0.3; y += step)
    for (double x = -0.3; x <= 0.3; x += step) {
      const int d = m.domain_at({x, y});
      const DomainPart part = m.domain_part(d);
      if (part.grain != 0) continue;  // a cleavage crack
      (part.inclusion >= 0 ? zircon : part.halo ? halo : host).push_back({x, y});
      if (part.halo) {
        ASSERT_EQ(m.mineral_of_domain(d), "biotite");
        const int host_d = d - (g.first_halo_domain() - g.first_domain);
        EXPECT_EQ(m.orientation_of_domain(d), m.orientation_of_domain(host_d));
        for (const double nm : {420.0, 550.0, 680.0}) {
          const glm::dvec3 dark = m.crystal_of_domain(d)->principal_absorption_per_um(nm);
          const glm::dvec3 plain = m.crystal_of_domain(host_d)->principal_absorption_per_um(nm);
          for (int k = 0; k < 3; ++k) EXPECT_NEAR(dark[k], 4.0 * plain[k], 1e-12 * plain[k]) << nm << " nm, axis " << k;
        }
      }
    }
  ASSERT_GT(zircon.size(), 50u);
  ASSERT_GT(halo.size(), 20 * zircon.size() / 2);  // a halo's disc is 21× its zircon's area
  const auto nearest_zircon = [&](const glm::dvec2& p) {
    double best = 1e9;
    for (const glm::dvec2& z : zircon) best = std::min(best, glm::length(p - z));
    return best;
  };
  // A halo point near the window's edge may ring a zircon beyond it: those within the reach of
  // the edge are left out.
  const auto inside = [](const glm::dvec2& p) { return std::max(std::abs(p.x), std::abs(p.y)) < 0.3 - 0.07; };
  double halo_far = 0.0, host_near = 1e9;
  for (const glm::dvec2& p : halo)
    if (inside(p)) halo_far = std::max(halo_far, nearest_zircon(p));
  for (std::size_t i = 0; i < host.size(); i += 7) host_near = std::min(host_near, nearest_zircon(host[i]));
  std::printf("halo points reach %.4f mm from a zircon point, host points come within %.4f mm (radius %.3f)\n",
              halo_far, host_near, radius);
  EXPECT_LE(halo_far, radius + 0.015 + step);
  EXPECT_GE(host_near, radius - 0.015 - step);
}

// A halo darkens an absorbing host; quartz absorbs nothing, so its halo would not show: refused,
// as is a halo beyond the inclusions' spacing (the lookup searches the next cell only) or one
// inside its own inclusion.
TEST(SectionInclusions, RefuseHaloesThatCouldNotShowOrReachTooFar) {
  const auto refused = [](const nlohmann::json& section, const std::string& key) {
    try {
      (void)section_from_json(section, "bad halo");
      ADD_FAILURE() << "accepted: " << key;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  refused(biotite_with_haloes({{"radius_mm", 0.05}, {"darkening", 4.0}}, "quartz"), "inclusions.halo");
  refused(biotite_with_haloes({{"radius_mm", 0.3}, {"darkening", 4.0}}), "halo.radius_mm");
  refused(biotite_with_haloes({{"radius_mm", 0.01}, {"darkening", 4.0}}), "halo.radius_mm");
  refused(biotite_with_haloes({{"radius_mm", 0.05}, {"darkening", 0.5}}), "halo.darkening");
}
