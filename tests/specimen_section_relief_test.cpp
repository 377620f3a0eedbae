// A thin section as a refracting 3-D slab (issue 12, core/specimen/section_slab.h): relief comes out
// of the traced light — no relief where every medium has the same index, a dark outline around a
// high-index grain, little around quartz in a medium of nearly its index, an outline contrast
// that follows |n − n_medium| — and the slab's geometry is a consistent partition of space.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include "core/crystal/crystal.h"
#include "core/materials/medium.h"
#include "core/microscope/section_map.h"
#include "core/microscope/view_geometry.h"
#include "core/render/progressive_renderer.h"
#include "core/specimen/grain_mount_render.h"
#include "core/specimen/plane_light_image.h"
#include "core/specimen/section_slab.h"
#include "core/specimen/traced_specimen.h"

namespace {

using pmsim::SectionMap;

constexpr double kGrainMm = 0.12;  // the square test grain: 120 µm a side

// A section of one grain: a kGrainMm square (the section's extent) of `crystal`; beyond it the
// field is mounting medium (domain 0), so the grain's outline is the square's edge.
std::shared_ptr<SectionMap> one_grain_section(const pmsim::Crystal* crystal) {
  auto m = std::make_shared<SectionMap>();
  m->name = "test";
  m->width_mm = m->height_mm = kGrainMm;
  pmsim::SectionGrain g;
  g.mineral = "test";
  g.crystal = crystal;
  g.semi_major_mm = g.semi_minor_mm = kGrainMm;
  g.metric_xx = g.metric_yy = 1.0 / (kGrainMm * kGrainMm);
  pmsim::SectionZone z;
  z.mineral = "test";
  z.crystal = crystal;
  g.zones.push_back(z);
  m->grains.push_back(g);
  m->finish();
  return m;
}

pmsim::SectionSlabOptions slab_options() {
  pmsim::SectionSlabOptions o;
  o.half_width_mm = 0.11;  // the 200 µm field and a margin
  o.spacing_um = 1.0;
  return o;
}

// 1 µm pixels over 200 µm at 589 nm, 10× objective (NA 0.25), diaphragm stopped down, in focus.
pmsim::PlaneLightOptions view(int spp = 16) {
  pmsim::PlaneLightOptions o;
  o.width = o.height = 200;
  o.um_per_px = 1.0;
  o.objective_na = 0.25;
  o.single_wavelength_nm = 589.26;
  o.spp = spp;
  return o;
}

// Distance (µm) of a pixel centre from the grain's true outline (the square's edge), + inside.
double signed_distance_um(int px, int py, const pmsim::PlaneLightOptions& o) {
  const double x = (px + 0.5 - 0.5 * o.width) * o.um_per_px, y = (0.5 * o.height - (py + 0.5)) * o.um_per_px;
  return 500.0 * kGrainMm - std::max(std::abs(x), std::abs(y));
}

struct Bands {
  double outline = 0.0, interior = 0.0, medium = 0.0;
};

// Mean Y in the band within 15 µm of the outline (a boundary leaning ~25° spans t·tan 25° = 14 µm
// of a 30 µm slab), the grain's interior 25 µm and more inside, the medium 25 µm and more outside.
Bands bands(const pmsim::RenderImage& img, const pmsim::PlaneLightOptions& o) {
  double s[3] = {0, 0, 0};
  int n[3] = {0, 0, 0};
  for (int py = 0; py < o.height; ++py)
    for (int px = 0; px < o.width; ++px) {
      const double d = signed_distance_um(px, py, o);
      const int k = std::abs(d) <= 15.0 ? 0 : d >= 25.0 ? 1 : d <= -25.0 ? 2 : -1;
      if (k < 0) continue;
      s[k] += img.xyz[3 * (std::size_t(py) * o.width + px) + 1];
      ++n[k];
    }
  return {s[0] / n[0], s[1] / n[1], s[2] / n[2]};
}

// Outline contrast: the light the band misses, relative to the mean of interior and medium.
double contrast(const Bands& b) { return 1.0 - b.outline / (0.5 * (b.interior + b.medium)); }

Bands render_bands(const pmsim::Crystal& c, const pmsim::IsotropicMedium& medium, int spp = 16) {
  const auto map = one_grain_section(&c);
  const auto slab = pmsim::build_section_slab(map, medium, slab_options());
  const auto o = view(spp);
  return bands(pmsim::render_plane_light(*slab, o), o);
}

}  // namespace

// (a) Every medium of the slab has n = 1.54 at every λ (grain, mounting medium; the slab's
// boundaries lean and its top is rough): no interface between them refracts or reflects, so every
// pixel sees the empty field's stack. What remains is the noise of the 0.03-NA cone's Fresnel
// transmission through the glass faces, < 1 % (the fragment test's matched-index bound).
TEST(SpecimenSectionRelief, MatchedIndicesGiveAUniformField) {
  const pmsim::Crystal c = pmsim::Crystal::isotropic_constant("matched", 1.54);
  const auto map = one_grain_section(&c);
  const auto slab =
      pmsim::build_section_slab(map, pmsim::IsotropicMedium(pmsim::Medium::constant("m", 1.54)), slab_options());
  const auto o = view(8);
  const auto img = pmsim::render_plane_light(*slab, o);
  double lo = 1e9, hi = -1e9, sum = 0.0;
  for (std::size_t i = 0; i < std::size_t(o.width) * o.height; ++i) {
    const double y = img.xyz[3 * i + 1];
    lo = std::min(lo, y);
    hi = std::max(hi, y);
    sum += y;
  }
  std::printf("matched slab: Y mean %.4f, min %.4f, max %.4f\n", sum / (o.width * o.height), lo, hi);
  EXPECT_NEAR(sum / (o.width * o.height), 1.0, 0.01);
  EXPECT_GT(lo, 0.99);
  EXPECT_LT(hi, 1.01);
}

// (b) Garnet (almandine, n ≈ 1.83) in a medium of 1.54: the light its leaning boundary bends out
// of the 0.25-NA objective leaves a dark outline. Quartz (1.544/1.553) in the same medium bends it
// by |Δn|/n ≈ 0.5 % of the lean: the outline nearly vanishes.
TEST(SpecimenSectionRelief, GarnetHasADarkOutlineQuartzNearlyNone) {
  const pmsim::IsotropicMedium medium(pmsim::Medium::constant("m", 1.54));
  const Bands garnet = render_bands(pmsim::find_mineral("almandine"), medium);
  const Bands quartz = render_bands(pmsim::find_mineral("quartz"), medium);
  std::printf("garnet: outline %.4f interior %.4f medium %.4f contrast %.4f\n", garnet.outline, garnet.interior,
              garnet.medium, contrast(garnet));
  std::printf("quartz: outline %.4f interior %.4f medium %.4f contrast %.4f\n", quartz.outline, quartz.interior,
              quartz.medium, contrast(quartz));
  // Dark outline: the band well below both sides (by a quarter at least; band-mean noise ≈ 0.005).
  EXPECT_LT(garnet.outline, 0.75 * garnet.interior);
  EXPECT_LT(garnet.outline, 0.75 * garnet.medium);
  // Quartz: a few per cent at most, and a tenth of garnet's at most.
  EXPECT_LT(std::abs(contrast(quartz)), 0.05);
  EXPECT_LT(std::abs(contrast(quartz)), 0.1 * contrast(garnet));
}

// (c) Watertight: every crystal region of the slab is a closed surface, no face is turned over,
// and a straight ray from
// above meets a consistent medium sequence: at each hit the side it comes from is the medium it
// is in, down to the air below the slide.
TEST(SpecimenSectionRelief, SlabIsWatertight) {
  // A window of the grown schist inside a garnet: its inclusion trails (dozens of closed quartz
  // regions 35 × 14 µm) and the grains round it.
  const auto map = pmsim::load_section("schist");
  pmsim::SectionSlabOptions so;
  so.half_width_mm = 0.15;
  so.spacing_um = 1.5;
  const auto in_inclusion = [&](const glm::dvec2& p) {
    const int d = map->domain_at(p);
    return d != pmsim::SectionMap::kMediumDomain && map->domain_part(d).inclusion >= 0;
  };
  // The window is found, not typed in, so a change of the recipe cannot leave it empty: on a 30 µm
  // grid (the trails' spacing is 60 µm) the 300 µm window holding the most inclusion points.
  const double step_mm = 0.03;
  const int nx = int(map->width_mm / step_mm), ny = int(map->height_mm / step_mm), r = 5;
  std::vector<int> inclusion_grid(std::size_t(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      inclusion_grid[std::size_t(j) * nx + i] = in_inclusion({(i + 0.5) * step_mm - 0.5 * map->width_mm,
                                                   (j + 0.5) * step_mm - 0.5 * map->height_mm});
  int best = -1;
  for (int j = r; j < ny - r; ++j)
    for (int i = r; i < nx - r; ++i) {
      int n = 0;
      for (int b = -r; b <= r; ++b)
        for (int a = -r; a <= r; ++a) n += inclusion_grid[std::size_t(j + b) * nx + i + a];
      if (n > best) {
        best = n;
        so.centre_mm = {(i + 0.5) * step_mm - 0.5 * map->width_mm, (j + 0.5) * step_mm - 0.5 * map->height_mm};
      }
    }
  int inclusion_points = 0;  // the window must hold inclusions, or it tests nothing new
  for (int k = 0; k < 10000; ++k)
    inclusion_points += in_inclusion(
        so.centre_mm + so.half_width_mm * glm::dvec2{(k % 100 + 0.5) / 50.0 - 1.0, (k / 100 + 0.5) / 50.0 - 1.0});
  EXPECT_GT(inclusion_points, 100);
  const auto slab = pmsim::build_section_slab(map, pmsim::IsotropicMedium(pmsim::find_medium("mounting")), so);
  std::printf("slab at (%.2f, %.2f) mm: %zu triangles, %d media, %d of 10000 points in inclusions\n",
              so.centre_mm.x, so.centre_mm.y, slab->triangle_count(), slab->medium_count(), inclusion_points);
  // Every crystal region is closed: its faces, oriented with the normal out of it, use each edge
  // as often in one direction as in the other (the mounting medium is the rest of the layer).
  std::map<std::tuple<int, unsigned, unsigned>, int> edges;
  const std::size_t slab_triangles = slab->triangle_count() - 8;  // the last 8: the glass faces
  for (std::size_t p = 0; p < slab_triangles; ++p) {
    const glm::uvec3 t = slab->triangle(p);
    for (int side = 0; side < 2; ++side) {
      const int region = side == 0 ? slab->back_of(p) : slab->front_of(p);  // normal points out of back
      if (region < pmsim::kFirstFragment) continue;
      for (int k = 0; k < 3; ++k) {
        unsigned a = t[k], b = t[(k + 1) % 3];
        if (side == 1) std::swap(a, b);
        edges[{region, std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
      }
    }
  }
  // No fold: the top and bottom faces (three vertices within 1 µm in z; a wall spans the slab's
  // 30 µm) all face up, as they were wound.
  int folded = 0;
  for (std::size_t p = 0; p < slab_triangles; ++p) {
    const glm::uvec3 t = slab->triangle(p);
    const glm::dvec3 a = slab->vertex(t.x), b = slab->vertex(t.y), c = slab->vertex(t.z);
    if (std::max({a.z, b.z, c.z}) - std::min({a.z, b.z, c.z}) > 1.0) continue;
    if (glm::cross(b - a, c - a).z < 0.0 && folded++ < 4)
      std::printf("turned-over face %zu at (%.2f %.2f %.2f), media %d/%d\n", p, a.x, a.y, a.z, slab->front_of(p),
                  slab->back_of(p));
  }
  EXPECT_EQ(folded, 0);
  int open_edges = 0;
  for (const auto& e : edges) open_edges += e.second != 0;
  std::printf("%zu region edges, %d open\n", edges.size(), open_edges);
  EXPECT_GT(edges.size(), 1000u);
  EXPECT_EQ(open_edges, 0);

  int bad = 0, rays = 0, crossings = 0;
  for (int k = 0; k < 4000; ++k) {
    const double u = (k % 63 + 0.37) / 63.0, v = (k / 63 + 0.61) / 64.0;
    const glm::dvec3 o{1000.0 * so.centre_mm.x + 250.0 * (u - 0.5), 1000.0 * so.centre_mm.y + 250.0 * (v - 0.5), 300.0};
    const double a = 0.37 * k, s = 0.3 * ((k * 7919) % 100) / 100.0;  // directions up to 17° off axis
    const glm::dvec3 d = glm::normalize(glm::dvec3(s * std::cos(a), s * std::sin(a), -1.0));
    int medium = pmsim::kSpecimenAir;
    glm::dvec3 at = o;
    pmsim::SpecimenHit hit;
    ++rays;
    for (int i = 0; i < 200 && slab->intersect(at, d, 0.0, hit); ++i) {
      const bool from_front = glm::dot(d, hit.normal) < 0.0;
      const int from = from_front ? hit.front : hit.back, to = from_front ? hit.back : hit.front;
      if (from != medium && bad++ < 6)
        std::printf("ray %d hit %d at (%.3f %.3f %.3f) n (%.3f %.3f %.3f) prim %u: from %d to %d, in %d, t %.5f\n", k, i,
                    hit.point.x, hit.point.y, hit.point.z, hit.normal.x, hit.normal.y, hit.normal.z, hit.prim, from, to,
                    medium, hit.t);
      medium = to;
      ++crossings;
      at = hit.point + (glm::dot(d, hit.normal) > 0.0 ? 1e-3 : -1e-3) * hit.normal;
    }
    if (medium != pmsim::kSpecimenAir) ++bad;  // out below the slide, in the air
  }
  std::printf("%d rays, %d crossings, %d inconsistent\n", rays, crossings, bad);
  EXPECT_EQ(bad, 0);
  EXPECT_GT(crossings, rays * 5);
}

// (d) sample.medium_index moves the mounting medium's n_D to the value set, and the outline of an
// isotropic n = 1.66 grain darkens as |n − n_medium| grows: 0.04, 0.08, 0.16.
TEST(SpecimenSectionRelief, MediumIndexSetsTheOutlineContrast) {
  const pmsim::Crystal c = pmsim::Crystal::isotropic_constant("n166", 1.66);
  double previous = -1.0;
  for (double nm : {1.62, 1.58, 1.50}) {
    pmsim::Scene scene;
    scene.sample.type = pmsim::SampleType::Section;
    scene.sample.medium_index = nm;
    const pmsim::IsotropicMedium medium = pmsim::section_mounting_medium(scene);
    EXPECT_NEAR(medium.n(589.26), nm, 1e-12);  // n_D is the value set, exactly up to rounding
    const double k = contrast(render_bands(c, medium, 32));
    std::printf("n 1.66 in medium %.2f: outline contrast %.4f\n", nm, k);
    // Each step at least doubles |Δn|: the contrast must grow by 20 % at least (noise ≈ 0.01).
    EXPECT_GT(k, previous < 0.0 ? 0.0 : 1.2 * previous) << "medium " << nm;
    previous = k;
  }
}

// (e) optics.relief = off keeps today's flat image (as do the conoscope and a compensator between
// the polars): such scenes are not traced, and the progressive renderer's pixels do not depend on
// the key. The analyzer in is traced too (tests/specimen_section_crossed_test.cpp).
TEST(SpecimenSectionRelief, ReliefOffGivesTheFlatImage) {
  pmsim::Scene scene;
  scene.sample.type = pmsim::SampleType::Section;
  scene.sample.section = "granite_hand_placed";
  scene.analyzer_in = false;
  scene.render.width = scene.render.height = 48;
  scene.render.spp = 4;
  EXPECT_TRUE(pmsim::is_traced_specimen(scene));
  pmsim::Scene off = scene;
  off.optics.relief = false;
  EXPECT_FALSE(pmsim::is_traced_specimen(off));
  pmsim::Scene crossed = scene;
  crossed.analyzer_in = true;
  EXPECT_TRUE(pmsim::is_traced_specimen(crossed));
  crossed.compensator = pmsim::Compensator::Gypsum;  // applied to the traced response (issue 21)
  EXPECT_TRUE(pmsim::is_traced_specimen(crossed));
  pmsim::Scene cono = scene;
  cono.mode = pmsim::ViewMode::Cono;
  cono.bertrand_in = true;
  EXPECT_FALSE(pmsim::is_traced_specimen(cono));
  const pmsim::RenderImage a = pmsim::ProgressiveRenderer::render(off, 0);
  const pmsim::RenderImage b = pmsim::ProgressiveRenderer::render(scene, 0);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  EXPECT_EQ(a.rgb, b.rgb);
}

// The traced image registers with the flat section image: with the stage moved and turned, the
// dark rim of a garnet grain lies where section_point_from_pixel (the flat image's mapping) puts
// the grain's boundary — and not where the opposite stage turn would put it.
TEST(SpecimenSectionRelief, TracedImageRegistersWithTheSectionImage) {
  const auto map = one_grain_section(&pmsim::find_mineral("almandine"));
  pmsim::Scene scene;
  scene.sample.type = pmsim::SampleType::Section;
  scene.analyzer_in = false;
  scene.objective.magnification = 100.0;  // 0.2 mm field over 200 px: 1 µm pixels
  scene.render.width = scene.render.height = 200;
  scene.render.single_wavelength_nm = 589.26;
  scene.render.spp = 8;
  scene.stage = {0.03, -0.02};
  scene.stage_deg = 30.0;
  pmsim::SectionSlabOptions so = pmsim::section_slab_options(scene);
  const auto slab = build_section_slab(map, pmsim::IsotropicMedium(pmsim::Medium::constant("m", 1.54)), so);
  const pmsim::RenderImage img = pmsim::render_plane_light(*slab, pmsim::plane_light_options(scene));
  // Mean Y within 6 µm of the boundary as the mapping of `s` places it.
  const auto rim = [&](const pmsim::Scene& s) {
    double sum = 0.0;
    int n = 0;
    for (int py = 0; py < 200; ++py)
      for (int px = 0; px < 200; ++px) {
        const glm::dvec2 p = pmsim::section_point_from_pixel(s, 200, 200, px + 0.5, py + 0.5);
        const double d = 500.0 * kGrainMm - 1000.0 * std::max(std::abs(p.x), std::abs(p.y));
        if (std::abs(d) > 6.0) continue;
        sum += img.xyz[3 * (std::size_t(py) * 200 + px) + 1];
        ++n;
      }
    return sum / n;
  };
  pmsim::Scene turned_wrong = scene;
  turned_wrong.stage_deg = -30.0;
  const double right = rim(scene), wrong = rim(turned_wrong);
  std::printf("rim Y where the section image puts the boundary %.4f, with the stage turned the other way %.4f\n",
              right, wrong);
  // The rim is dark (garnet's outline, contrast ≈ 0.3 over a 15 µm band, more within 6 µm); a
  // mapping 60° off puts most of its band on the bright interior or medium.
  EXPECT_LT(right, 0.8);
  EXPECT_LT(right, wrong - 0.1);
}

// The app does not rebuild the slab for a change of polarizer, focus or aperture: section_slab
// returns the cached one; a stage move (a new window) or another mounting medium builds anew.
TEST(SpecimenSectionRelief, SlabIsCachedAcrossViewChanges) {
  pmsim::Scene scene;
  scene.sample.type = pmsim::SampleType::Section;
  scene.sample.section = "granite_hand_placed";
  scene.analyzer_in = false;
  scene.render.width = scene.render.height = 32;
  const auto a = pmsim::section_slab(scene);
  pmsim::Scene view = scene;
  view.polarizer_deg = 40.0;
  view.focus_um = 7.0;
  view.condenser.aperture_na = 0.2;
  view.stage_deg = 75.0;  // the window holds the field at every stage angle
  EXPECT_EQ(pmsim::section_slab(view).get(), a.get());
  pmsim::Scene moved = scene;
  moved.stage.x_mm = 1.0;
  EXPECT_NE(pmsim::section_slab(moved).get(), a.get());
  pmsim::Scene liquid = scene;
  liquid.sample.medium_index = 1.60;
  EXPECT_NE(pmsim::section_slab(liquid).get(), a.get());
}
