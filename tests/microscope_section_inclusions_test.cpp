// Inclusions in a grain (SectionGrain::InclusionSet): their area, their limit, their domains and
// the reader's refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>
#include <random>

#include <nlohmann/json.hpp>

#include "core/base/input_error.h"
#include "core/base/units.h"
#include "core/crystal/section_optics.h"
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

namespace {

// A quartz grain enclosing apatite needles 80 × 8 µm, each along its own crystal's c axis: one
// orientation per listed Euler triple (the first with c in the section, the last with c 87° from
// it, seen nearly end-on).
nlohmann::json quartz_with_needles(const nlohmann::json& inclusions_extra) {
  nlohmann::json in = {{"mineral", "apatite"},
                       {"size_mm", 0.08},
                       {"aspect", 10.0},
                       {"spacing_mm", 0.12},
                       {"trail_spacing_mm", 0.12},
                       {"fraction", 0.6},
                       {"habit", "needle"},
                       {"euler_deg", {{0, 90, 0}, {35, 90, 20}, {120, 60, 10}, {250, 30, 70}, {10, 3, 0}}}};
  if (!inclusions_extra.is_null()) in.update(inclusions_extra);
  return {{"type", "section"},
          {"size_mm", {1.4, 1.4}},
          {"grains",
           {{{"mineral", "quartz"},
             {"centre_mm", {0.0, 0.0}},
             {"size_mm", 1.2},
             {"euler_deg", {0.0, 0.0, 0.0}},
             {"inclusions", in}}}}};
}

}  // namespace

// Apatite is uniaxial negative (n_ε 1.630 < n_ω 1.634) and grows along c: in any section its
// e-ray vibrates in the plane of c and the wave normal, along c's projection, so a needle goes
// extinct parallel to its length and is length-fast (Nesse 2012, apatite). Each needle domain's
// optics are computed from its orientation and compared with the shape the section map draws:
// the second moments of every needle seen on a 1 µm grid.
TEST(SectionInclusions, ApatiteNeedlesLieAlongTheirCAxisAndAreLengthFastWithParallelExtinction) {
  const SectionMap m = section_from_json(quartz_with_needles(nlohmann::json::object()), "needles");
  const SectionGrain& g = m.grains[0];
  ASSERT_TRUE(g.inclusions);
  ASSERT_EQ(g.inclusions->needles.size(), 5u);
  const double step = 0.001;
  const int n = 700;  // a 0.7 mm window about the centre
  std::vector<int> dom(std::size_t(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) dom[std::size_t(j) * n + i] = m.domain_at({(i - n / 2) * step, (j - n / 2) * step});
  std::vector<char> seen(dom.size(), 0);
  int measured[5] = {0, 0, 0, 0, 0};
  double worst_deg = 0.0;
  for (std::size_t start = 0; start < dom.size(); ++start) {
    const int k = m.domain_part(dom[start]).inclusion;
    if (k < 0 || seen[start]) continue;
    // One needle: the 4-connected pixels of its domain.
    std::vector<std::size_t> stack{start}, pixels;
    seen[start] = 1;
    bool edge = false;
    while (!stack.empty()) {
      const std::size_t p = stack.back();
      stack.pop_back();
      pixels.push_back(p);
      const int i = int(p % n), j = int(p / n);
      edge = edge || i == 0 || j == 0 || i == n - 1 || j == n - 1;
      const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
      for (int e = 0; e < 4; ++e) {
        const int a = i + di[e], b = j + dj[e];
        if (a < 0 || b < 0 || a >= n || b >= n) continue;
        const std::size_t q = std::size_t(b) * n + a;
        if (!seen[q] && dom[q] == dom[start]) seen[q] = 1, stack.push_back(q);
      }
    }
    const SectionGrain::InclusionSet::Needle& nd = g.inclusions->needles[std::size_t(k)];
    // Needles touching the window's edge, or each other (two of one orientation), are not one
    // whole needle; nor is one seen end-on (its outline then a disc with no direction).
    if (edge || nd.length_mm < 3.0 * g.inclusions->width_mm || pixels.size() > 1.2 * 80 * 8) continue;
    double mx = 0, my = 0, sxx = 0, syy = 0, sxy = 0;
    for (const std::size_t p : pixels) mx += double(p % n), my += double(p / n);
    mx /= pixels.size(), my /= pixels.size();
    for (const std::size_t p : pixels) {
      const double x = double(p % n) - mx, y = double(p / n) - my;
      sxx += x * x, syy += y * y, sxy += x * y;
    }
    const double shape_deg = degrees(0.5 * std::atan2(2 * sxy, sxx - syy));
    const double axis_deg = degrees(std::atan2(nd.axis.y, nd.axis.x));
    double diff = std::fmod(std::abs(shape_deg - axis_deg), 180.0);
    diff = std::min(diff, 180.0 - diff);
    // A needle ≥ 24 × 8 µm on a 1 µm grid: its second-moment axis is its own to within a few
    // degrees (the grid's staircase); 5° bounds it.
    worst_deg = std::max(worst_deg, diff);
    // A prism seen side-on: a rectangle of its projected length by its width, on the 1 µm grid to
    // within half its perimeter in pixels (the staircase: ≤ 20 % of 640 px here).
    const double rect_px = nd.length_mm * g.inclusions->width_mm / (step * step);
    EXPECT_NEAR(double(pixels.size()), rect_px, (nd.length_mm + g.inclusions->width_mm) / step) << "orientation " << k;
    EXPECT_LT(diff, 5.0) << "orientation " << k << ": shape " << shape_deg << "°, c " << axis_deg << "°";
    ++measured[k];
  }
  for (int k = 0; k < 5; ++k) {
    const SectionGrain::InclusionSet::Needle& nd = g.inclusions->needles[std::size_t(k)];
    const int d = g.first_inclusion_domain() + k;
    const SectionOptics s = section_optics(m.orientation_of_domain(d), m.crystal_of_domain(d)->principal_indices(589.0),
                                           {0.0, 0.0, 1.0});
    const glm::dvec3 along{nd.axis, 0.0};
    std::printf("needle orientation %d: %.4f mm long, %d measured, fast ^ length %.2e deg\n", k, nd.length_mm,
                measured[k], std::acos(std::min(1.0, std::abs(glm::dot(s.fast, along)))) * 180.0 / M_PI);
    if (nd.length_mm < 1.5 * g.inclusions->width_mm) continue;  // end-on: a basal section
    // The e-ray's direction is c's projection, computed two ways (the lattice's [0001] through the
    // Euler rotation; the indicatrix's principal-axes section): equal to rounding (1e-9 rad).
    EXPECT_LT(std::abs(extinction_from(s, along).angle_deg), 1e-6) << "orientation " << k;
    EXPECT_EQ(sign_of_elongation(s, along), SignOfElongation::LengthFast) << "orientation " << k;
  }
  // c in the section (Φ = 90°): the full 80 µm; the near end-on one (Φ = 3°: 80·sin 3° = 4 µm) is
  // shown at its width (a small basal section).
  EXPECT_NEAR(g.inclusions->needles[0].length_mm, 0.08, 1e-12);
  EXPECT_NEAR(g.inclusions->needles[4].length_mm, g.inclusions->width_mm, 1e-12);
  std::printf("needle outlines within %.2f deg of their c axes\n", worst_deg);
  EXPECT_GT(measured[0] + measured[1] + measured[2], 10);
}

TEST(SectionInclusions, RefuseNeedlesThatCouldNotBeFoundOrHaveNoElongation) {
  const auto refused = [](const nlohmann::json& extra, const std::string& key) {
    try {
      (void)section_from_json(quartz_with_needles(extra), "bad needles");
      ADD_FAILURE() << "accepted: " << extra.dump();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  refused({{"habit", "spike"}}, "inclusions.habit");
  refused({{"mineral", "almandine"}}, "inclusions.habit");  // cubic: no elongation
  refused({{"trail_spacing_mm", 0.05}}, "inclusions.habit");  // longer than the trails are apart
}
