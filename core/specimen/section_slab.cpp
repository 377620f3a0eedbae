#include "core/specimen/section_slab.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/base/units.h"
#include "core/microscope/map_section.h"
#include "core/microscope/view_geometry.h"
#include "core/specimen/last_built.h"
#include "core/specimen/specimen_random.h"
#include "core/spectrum/reference_wavelengths.h"

namespace pmsim {

namespace {

// A smooth random function of position with RMS 1: a sum of K plane waves of random direction,
// wavelength in [lo, hi] and phase (a Gaussian random field's spectral sampling, Shinozuka &
// Deodatis 1991); the same function for the same seed, whatever window samples it.
struct WaveField {
  static constexpr int K = 8;
  std::array<glm::dvec2, K> k;
  std::array<double, K> phase;
  WaveField(std::uint64_t seed, double lo_um, double hi_um) {
    SpecimenRandom rng(seed);
    for (int i = 0; i < K; ++i) {
      const double a = 2.0 * kPi * rng.uniform();
      const double lambda = lo_um + (hi_um - lo_um) * rng.uniform();
      k[i] = (2.0 * kPi / lambda) * glm::dvec2(std::cos(a), std::sin(a));
      phase[i] = 2.0 * kPi * rng.uniform();
    }
  }
  double operator()(const glm::dvec2& p_um) const {
    double s = 0.0;
    for (int i = 0; i < K; ++i) s += std::cos(glm::dot(k[i], p_um) + phase[i]);
    return s * std::sqrt(2.0 / K);
  }
};

double smoothstep01(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

}  // namespace

std::vector<int> section_slab_media(const SectionMap& m) {
  std::vector<int> medium_of_domain(std::size_t(m.domain_count()), kSpecimenLiquid);
  int next = kFirstFragment;
  for (int d = 2; d < m.domain_count(); ++d)
    if (m.crystal_of_domain(d) && !m.is_opaque(d)) medium_of_domain[std::size_t(d)] = next++;
  return medium_of_domain;
}

SlabNode section_slab_node(const SectionMap& m, const glm::dvec2& p_mm, double spacing_um) {
  SlabNode node;
  node.domain = m.domain_at(p_mm);
  if (node.domain == SectionMap::kSlideDomain) return node;
  // Cracks at least a grid step wide: a crack narrower than h would be hit by some nodes and
  // missed by others, a dashed line of pinholes.
  node.crack_family = m.crack_family_at(p_mm, node.crack_grain, 1e-3 * spacing_um);
  if (node.crack_family >= 0) node.domain = SectionMap::kMediumDomain;
  return node;
}

std::unique_ptr<SpecimenScene> build_section_slab(const std::shared_ptr<const SectionMap>& map,
                                                  const IsotropicMedium& medium, const SectionSlabOptions& o) {
  if (!map) throw std::invalid_argument("build_section_slab: no section");
  if (!(o.spacing_um > 0.0) || !(o.thickness_um > 0.0) || !(o.half_width_mm > 0.0) || !(o.film_um > 0.0))
    throw std::invalid_argument("build_section_slab: spacing, thickness, window and film must be positive");
  const SectionMap& m = *map;

  // Media: one per crystal domain, in domain order.
  const std::vector<int> medium_of_domain = section_slab_media(m);
  std::vector<SpecimenMedium> media;
  for (int d = 2; d < m.domain_count(); ++d)
    if (medium_of_domain[std::size_t(d)] != kSpecimenLiquid)
      media.push_back({std::nullopt, std::shared_ptr<const Crystal>(map, m.crystal_of_domain(d)),
                       m.orientation_of_domain(d)});

  // The node lattice: global (node positions are multiples of h), so that the same section point
  // gets the same node wherever the window lies.
  const double h = o.spacing_um;
  const int half_n = std::min(kMaxSlabNodes / 2, int(std::ceil(1000.0 * o.half_width_mm / h)));
  const int N = 2 * half_n + 1;
  const glm::dvec2 origin_um = glm::round(1000.0 * o.centre_mm / h) * h - double(half_n) * h;
  const auto node_pos = [&](int i, int j) { return origin_um + glm::dvec2(i * h, j * h); };

  std::vector<int> label(std::size_t(N) * N, kSpecimenLiquid);
  std::vector<glm::dvec2> crack_shift(std::size_t(N) * N, glm::dvec2(0.0));
  std::vector<char> is_crack(std::size_t(N) * N, 0);
  const double t = o.thickness_um;
  tbb::parallel_for(tbb::blocked_range<int>(1, N - 1), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j < rows.end(); ++j)
      for (int i = 1; i < N - 1; ++i) {
        const SlabNode node = section_slab_node(m, 1e-3 * node_pos(i, j), h);
        const std::size_t n = std::size_t(j) * N + i;
        label[n] = medium_of_domain[std::size_t(node.domain)];
        const int f = node.crack_family, g = node.crack_grain;
        if (f < 0) continue;
        // The cleavage plane through the crack's trace on the top face reaches the bottom face
        // shifted along its horizontal normal by t·n_z/|n_h| (n·Δx = 0 over a drop of t).
        const glm::dvec3 pn = m.grains[std::size_t(g)].cracks[std::size_t(f)].plane_normal;
        const glm::dvec2 nh(pn.x, pn.y);
        const double len = glm::length(nh);
        if (len < 1e-6) continue;
        is_crack[n] = 1;
        crack_shift[n] = (t * pn.z / (len * len)) * nh;
      }
  });
  // The outer ring stays mounting medium: the slab closes in walls inside the window.

  // Cell vertices (surface nets).
  const int C = N - 1;
  const auto L = [&](int i, int j) { return label[std::size_t(j) * N + i]; };
  std::vector<glm::dvec2> cell_xy(std::size_t(C) * C);
  std::vector<float> dist(std::size_t(C) * C, std::numeric_limits<float>::infinity());
  std::vector<glm::dvec2> src_shift(std::size_t(C) * C, glm::dvec2(0.0));
  for (int cj = 0; cj < C; ++cj)
    for (int ci = 0; ci < C; ++ci) {
      const int a = L(ci, cj), b = L(ci + 1, cj), c = L(ci + 1, cj + 1), d = L(ci, cj + 1);
      glm::dvec2 sum(0.0);
      int k = 0;
      const auto edge = [&](int la, int lb, glm::dvec2 mid) {
        if (la != lb) {
          sum += mid;
          ++k;
        }
      };
      edge(a, b, {0.5, 0.0});
      edge(b, c, {1.0, 0.5});
      edge(c, d, {0.5, 1.0});
      edge(d, a, {0.0, 0.5});
      const glm::dvec2 local = k > 0 ? sum / double(k) : glm::dvec2(0.5);
      const std::size_t cell = std::size_t(cj) * C + ci;
      cell_xy[cell] = node_pos(ci, cj) + h * local;
      glm::dvec2 s(0.0);
      int nc = 0;
      for (const std::array<int, 2>& q : {std::array<int, 2>{ci, cj}, {ci + 1, cj}, {ci + 1, cj + 1}, {ci, cj + 1}}) {
        const std::size_t n = std::size_t(q[1]) * N + q[0];
        if (is_crack[n]) {
          s += crack_shift[n];
          ++nc;
        }
      }
      if (nc > 0) {
        dist[cell] = 0.0f;
        src_shift[cell] = s / double(nc);
      }
    }
  // Two smoothing steps of the top's boundary vertices (surface nets' relaxation): each moves to
  // the mean of itself and its boundary neighbours, kept inside its own cell. A boundary along a
  // grid diagonal or a crack nearly along the grid is then a straight edge, not a staircase. The
  // bottom keeps the unsmoothed vertices: a smoothed quad can be thin enough for the lean's
  // gradient to turn it over (measured: 20 of 80 000 bottom faces of a schist window).
  const std::vector<glm::dvec2> cell_xy_raw = cell_xy;
  {
    std::vector<char> boundary(std::size_t(C) * C, 0);
    for (int cj = 0; cj < C; ++cj)
      for (int ci = 0; ci < C; ++ci) {
        const int a = L(ci, cj);
        boundary[std::size_t(cj) * C + ci] = L(ci + 1, cj) != a || L(ci + 1, cj + 1) != a || L(ci, cj + 1) != a;
      }
    std::vector<glm::dvec2> next = cell_xy;
    for (int step = 0; step < 2; ++step) {
      for (int cj = 1; cj + 1 < C; ++cj)
        for (int ci = 1; ci + 1 < C; ++ci) {
          const std::size_t c = std::size_t(cj) * C + ci;
          if (!boundary[c]) continue;
          glm::dvec2 sum = cell_xy[c];
          int k = 1;
          for (const std::size_t nb : {c - 1, c + 1, c - std::size_t(C), c + std::size_t(C)})
            if (boundary[nb]) {
              sum += cell_xy[nb];
              ++k;
            }
          const glm::dvec2 lo = node_pos(ci, cj) + 0.05 * h, hi = node_pos(ci + 1, cj + 1) - 0.05 * h;
          next[c] = glm::clamp(sum / double(k), lo, hi);
        }
      cell_xy.swap(next);
      next = cell_xy;
    }
  }
  // Distance to the nearest crack cell with that crack's shift carried along (two-pass chamfer
  // distance transform, Borgefors 1986).
  {
    const float dx = float(h), dd = float(h * std::sqrt(2.0));
    const auto relax = [&](int ci, int cj, int ni, int nj, float w) {
      if (ni < 0 || nj < 0 || ni >= C || nj >= C) return;
      const std::size_t a = std::size_t(cj) * C + ci, b = std::size_t(nj) * C + ni;
      if (dist[b] + w < dist[a]) {
        dist[a] = dist[b] + w;
        src_shift[a] = src_shift[b];
      }
    };
    for (int cj = 0; cj < C; ++cj)
      for (int ci = 0; ci < C; ++ci) {
        relax(ci, cj, ci - 1, cj, dx);
        relax(ci, cj, ci, cj - 1, dx);
        relax(ci, cj, ci - 1, cj - 1, dd);
        relax(ci, cj, ci + 1, cj - 1, dd);
      }
    for (int cj = C - 1; cj >= 0; --cj)
      for (int ci = C - 1; ci >= 0; --ci) {
        relax(ci, cj, ci + 1, cj, dx);
        relax(ci, cj, ci, cj + 1, dx);
        relax(ci, cj, ci + 1, cj + 1, dd);
        relax(ci, cj, ci - 1, cj + 1, dd);
      }
  }

  // Vertices: top (index cell) and bottom (C² + cell).
  const WaveField fx(o.seed * 4 + 1, 400.0, 900.0), fy(o.seed * 4 + 2, 400.0, 900.0);
  // Polishing relief of 8–20 µm wavelength: RMS slope ≈ 2π·0.15/14 ≈ 0.07 rad, which a surface
  // between media 0.3 apart in n (garnet in epoxy) turns into deviations of ~0.02 rad, the size of
  // a stopped-down condenser's cone: shagreen, while quartz (Δn ≈ 0.01) stays smooth.
  const WaveField rough(o.seed * 4 + 3, 8.0, 20.0);
  // RMS |shift| = t·tan(inclination): each component's RMS is that over √2.
  const double amp = t * std::tan(radians(o.inclination_deg)) / std::sqrt(2.0);
  const double z_bottom = o.film_um, z_top = o.film_um + t;
  const std::size_t cells = std::size_t(C) * C;
  std::vector<glm::dvec2> field(cells), crack(cells, glm::dvec2(0.0));
  tbb::parallel_for(tbb::blocked_range<int>(0, C), [&](const tbb::blocked_range<int>& rows) {
    for (int cj = rows.begin(); cj < rows.end(); ++cj)
      for (int ci = 0; ci < C; ++ci) {
        const std::size_t cell = std::size_t(cj) * C + ci;
        const glm::dvec2 p = cell_xy[cell];
        field[cell] = amp > 0.0 ? amp * glm::dvec2(fx(p), fy(p)) : glm::dvec2(0.0);
        if (std::isfinite(dist[cell])) {
          // Near a crack its own lean: 1 on the crack, fading over R ≥ 2.5·|Δ| (slope ≤ 0.6).
          const glm::dvec2 delta = src_shift[cell] - field[cell];
          const double R = 2.5 * glm::length(delta) + 2.0 * h;
          crack[cell] = (1.0 - smoothstep01(double(dist[cell]) / R)) * delta;
        }
      }
  });
  // Where cracks of two families (or of two grains) meet, their leans differ by up to 2·t·tan 30°
  // over one cell: two box filters of radius 25 µm turn that jump into a ramp of slope < 0.7 (the
  // slab must not fold; the crossing planes cannot both be followed to the bottom there), at the
  // cost of ~20 % of a crack's lean.
  {
    const int r = std::max(1, int(std::ceil(25.0 / h)));
    std::vector<glm::dvec2> tmp(cells);
    const auto box = [&](std::vector<glm::dvec2>& in, std::vector<glm::dvec2>& out, bool along_x) {
      tbb::parallel_for(tbb::blocked_range<int>(0, C), [&](const tbb::blocked_range<int>& lines) {
        for (int l = lines.begin(); l < lines.end(); ++l) {
          const auto at = [&](int k) -> std::size_t {
            k = std::clamp(k, 0, C - 1);
            return along_x ? std::size_t(l) * C + k : std::size_t(k) * C + l;
          };
          glm::dvec2 sum(0.0);
          for (int k = -r; k <= r; ++k) sum += in[at(k)];
          for (int k = 0; k < C; ++k) {
            out[at(k)] = sum / double(2 * r + 1);
            sum += in[at(k + r + 1)] - in[at(k - r)];
          }
        }
      });
    };
    for (int pass = 0; pass < 2; ++pass) {
      box(crack, tmp, true);
      box(tmp, crack, false);
    }
  }
  SpecimenMesh mesh;
  mesh.vertices.resize(2 * cells);
  tbb::parallel_for(tbb::blocked_range<int>(0, C), [&](const tbb::blocked_range<int>& rows) {
    for (int cj = rows.begin(); cj < rows.end(); ++cj)
      for (int ci = 0; ci < C; ++ci) {
        const std::size_t cell = std::size_t(cj) * C + ci;
        const glm::dvec2 p = cell_xy[cell];
        const double zr = o.roughness_um > 0.0 ? o.roughness_um * rough(p) : 0.0;
        mesh.vertices[cell] = {p, z_top + zr};
        mesh.vertices[cells + cell] = {cell_xy_raw[cell] + field[cell] + crack[cell], z_bottom};
      }
  });

  const auto top = [&](int ci, int cj) { return unsigned(std::size_t(cj) * C + ci); };
  const auto bot = [&](int ci, int cj) { return unsigned(std::size_t(C) * C + std::size_t(cj) * C + ci); };
  const auto tri = [&](unsigned a, unsigned b, unsigned c, int front, int back) {
    mesh.triangles.push_back({a, b, c});
    mesh.front.push_back(front);
    mesh.back.push_back(back);
  };
  // A face quad (counter-clockwise from above) split along the diagonal that leaves both
  // triangles facing up: a quad of surface-net vertices may be concave at one corner.
  const auto quad_face = [&](unsigned a, unsigned b, unsigned c, unsigned d, int front, int back) {
    const auto up = [&](unsigned p, unsigned q, unsigned r) {
      const glm::dvec3 u = mesh.vertices[q] - mesh.vertices[p], v = mesh.vertices[r] - mesh.vertices[p];
      return u.x * v.y - u.y * v.x > 0.0;
    };
    if (up(a, b, c) && up(a, c, d)) {
      tri(a, b, c, front, back);
      tri(a, c, d, front, back);
    } else {
      tri(a, b, d, front, back);
      tri(b, c, d, front, back);
    }
  };
  for (int j = 1; j < N - 1; ++j)
    for (int i = 1; i < N - 1; ++i) {
      const int a = L(i, j);
      // Top and bottom faces of the node's quad (counter-clockwise from above: normal +z).
      if (a != kSpecimenLiquid) {
        quad_face(top(i - 1, j - 1), top(i, j - 1), top(i, j), top(i - 1, j), kSpecimenLiquid, a);
        quad_face(bot(i - 1, j - 1), bot(i, j - 1), bot(i, j), bot(i - 1, j), a, kSpecimenLiquid);
      }
    }
  // Walls. Edge (i, j)–(i+1, j) lies between cells (i, j−1) and (i, j); the quad's normal points
  // to −x, toward node (i, j). Edge (i, j)–(i, j+1) between cells (i−1, j) and (i, j); normal +y,
  // toward node (i, j+1).
  for (int j = 1; j < N - 1; ++j)
    for (int i = 0; i < N - 1; ++i) {
      const int a = L(i, j), b = L(i + 1, j);
      if (a == b) continue;
      tri(top(i, j - 1), top(i, j), bot(i, j), a, b);
      tri(top(i, j - 1), bot(i, j), bot(i, j - 1), a, b);
    }
  for (int j = 0; j < N - 1; ++j)
    for (int i = 1; i < N - 1; ++i) {
      const int a = L(i, j), b = L(i, j + 1);
      if (a == b) continue;
      tri(top(i - 1, j), top(i, j), bot(i, j), b, a);
      tri(top(i - 1, j), bot(i, j), bot(i - 1, j), b, a);
    }

  SpecimenLayers layers;
  layers.liquid_um = t + 2.0 * o.film_um;
  return std::make_unique<SpecimenScene>(std::move(media), std::move(mesh), Crystal{}, medium,
                                         find_medium("N-BK7"), find_medium("air"), layers);
}

IsotropicMedium section_mounting_medium(const Scene& scene) {
  const Medium& m = find_medium(scene.sample.medium);
  const double offset = scene.sample.medium_index ? *scene.sample.medium_index - m.n(kLiquidDNm) : 0.0;
  return IsotropicMedium(m, offset);
}

SectionSlabOptions section_slab_options(const Scene& scene) {
  SectionSlabOptions o;
  const int w = scene.render.width, hh = scene.render.height;
  const double mmpp = mm_per_pixel(scene, w, hh);
  o.centre_mm = {scene.stage.x_mm, scene.stage.y_mm};
  // The image turned to any stage angle lies within its half-diagonal; 40 µm more hold the light
  // cone of NA ≤ 0.95 through the slab and the films at moderate defocus.
  o.half_width_mm = 0.5 * mmpp * std::sqrt(double(w) * w + double(hh) * hh) + 0.04;
  const double pixel_um = 1000.0 * mmpp;
  o.spacing_um = std::max({pixel_um, 0.5, 2000.0 * o.half_width_mm / (kMaxSlabNodes - 1)});
  o.thickness_um = scene.sample.thickness_um;
  return o;
}

std::shared_ptr<const SpecimenScene> section_slab(const Scene& scene) {
  const SectionSlabOptions o = section_slab_options(scene);
  const IsotropicMedium medium = section_mounting_medium(scene);
  std::ostringstream key;
  key.precision(17);
  key << scene.sample.section << '|' << o.centre_mm.x << ',' << o.centre_mm.y << '|' << o.half_width_mm << '|'
      << o.spacing_um << '|' << o.thickness_um << '|' << scene.sample.medium << '|'
      << scene.sample.medium_index.value_or(0.0) << '|' << scene.sample.orientation_seed.value_or(-1);
  // One slab kept: the app looks at one field at a time; a stage move rebuilds.
  static LastBuilt<SpecimenScene> cache;
  return cache.get(key.str(), [&] { return build_section_slab(load_scene_section(scene), medium, o); });
}

}  // namespace pmsim
