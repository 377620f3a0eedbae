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

#include "core/base/build_cache.h"
#include "core/base/units.h"
#include "core/microscope/map_section.h"
#include "core/microscope/view_geometry.h"
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
  if (node.crack_family >= 0) node.domain = m.crack_domain(node.crack_grain);  // open, or a vein
  return node;
}

namespace {

// The node lattice: global (node positions are multiples of h), so that the same section point
// gets the same node wherever the window lies. N nodes a side, C = N − 1 cells.
struct SlabLattice {
  double h = 0.0;
  int N = 0, C = 0;
  glm::dvec2 origin_um{0.0};
  SlabLattice(const SectionSlabOptions& o) : h(o.spacing_um) {
    const int half_n = std::min(kMaxSlabNodes / 2, int(std::ceil(1000.0 * o.half_width_mm / h)));
    N = 2 * half_n + 1;
    C = N - 1;
    origin_um = glm::round(1000.0 * o.centre_mm / h) * h - double(half_n) * h;
  }
  glm::dvec2 node_pos(int i, int j) const { return origin_um + glm::dvec2(i * h, j * h); }
  std::size_t node(int i, int j) const { return std::size_t(j) * std::size_t(N) + std::size_t(i); }
  std::size_t cell(int ci, int cj) const { return std::size_t(cj) * std::size_t(C) + std::size_t(ci); }
  std::size_t cells() const { return std::size_t(C) * std::size_t(C); }
};

// Phase 1. One medium per crystal domain, in domain order.
std::vector<SpecimenMedium> slab_media(const std::shared_ptr<const SectionMap>& map,
                                       const std::vector<int>& medium_of_domain) {
  const SectionMap& m = *map;
  std::vector<SpecimenMedium> media;
  for (int d = 2; d < m.domain_count(); ++d)
    if (medium_of_domain[std::size_t(d)] != kSpecimenLiquid)
      media.push_back({std::nullopt, std::shared_ptr<const Crystal>(map, m.crystal_of_domain(d)),
                       m.orientation_of_domain(d)});
  return media;
}

// Phase 2. Each node's medium, and on a crack node the shift its cleavage plane takes down to
// the bottom face.
struct NodeLabels {
  std::vector<int> label;
  std::vector<glm::dvec2> crack_shift;
  std::vector<char> is_crack;
  int at(const SlabLattice& g, int i, int j) const { return label[g.node(i, j)]; }
};

NodeLabels label_nodes(const SectionMap& m, const SlabLattice& g, const std::vector<int>& medium_of_domain,
                       double t) {
  const std::size_t nodes = std::size_t(g.N) * std::size_t(g.N);
  NodeLabels n{std::vector<int>(nodes, kSpecimenLiquid), std::vector<glm::dvec2>(nodes, glm::dvec2(0.0)),
               std::vector<char>(nodes, 0)};
  const int N = g.N;
  tbb::parallel_for(tbb::blocked_range<int>(1, N - 1), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j < rows.end(); ++j)
      for (int i = 1; i < N - 1; ++i) {
        const SlabNode node = section_slab_node(m, 1e-3 * g.node_pos(i, j), g.h);
        const std::size_t k = g.node(i, j);
        n.label[k] = medium_of_domain[std::size_t(node.domain)];
        const int f = node.crack_family, gr = node.crack_grain;
        if (f < 0) continue;
        // The cleavage plane through the crack's trace on the top face reaches the bottom face
        // shifted along its horizontal normal by t·n_z/|n_h| (n·Δx = 0 over a drop of t).
        const glm::dvec3 pn = m.grains[std::size_t(gr)].cracks[std::size_t(f)].plane_normal;
        const glm::dvec2 nh(pn.x, pn.y);
        const double len = glm::length(nh);
        if (len < 1e-6) continue;
        n.is_crack[k] = 1;
        n.crack_shift[k] = (t * pn.z / (len * len)) * nh;
      }
  });
  // The outer ring stays mounting medium: the slab closes in walls inside the window.
  return n;
}

// Phase 3. Cell vertices (surface nets): the mean of the cell's edge midpoints where the label
// changes; crack cells get distance 0 and the mean shift of their crack nodes.
struct SurfaceNet {
  std::vector<glm::dvec2> cell_xy;
  std::vector<float> dist;           // to the nearest crack cell (µm), ∞ where none
  std::vector<glm::dvec2> src_shift;  // that crack's shift
};

SurfaceNet place_cell_vertices(const SlabLattice& g, const NodeLabels& n) {
  const int C = g.C;
  SurfaceNet s{std::vector<glm::dvec2>(g.cells()), std::vector<float>(g.cells(), std::numeric_limits<float>::infinity()),
               std::vector<glm::dvec2>(g.cells(), glm::dvec2(0.0))};
  for (int cj = 0; cj < C; ++cj)
    for (int ci = 0; ci < C; ++ci) {
      const int a = n.at(g, ci, cj), b = n.at(g, ci + 1, cj), c = n.at(g, ci + 1, cj + 1), d = n.at(g, ci, cj + 1);
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
      const std::size_t cell = g.cell(ci, cj);
      s.cell_xy[cell] = g.node_pos(ci, cj) + g.h * local;
      glm::dvec2 shift(0.0);
      int nc = 0;
      for (const std::array<int, 2>& q : {std::array<int, 2>{ci, cj}, {ci + 1, cj}, {ci + 1, cj + 1}, {ci, cj + 1}}) {
        const std::size_t k2 = g.node(q[0], q[1]);
        if (n.is_crack[k2]) {
          shift += n.crack_shift[k2];
          ++nc;
        }
      }
      if (nc > 0) {
        s.dist[cell] = 0.0f;
        s.src_shift[cell] = shift / double(nc);
      }
    }
  return s;
}

// Phase 4. Two smoothing steps of the top's boundary vertices (surface nets' relaxation): each
// moves to the mean of itself and its boundary neighbours, kept inside its own cell. A boundary
// along a grid diagonal or a crack nearly along the grid is then a straight edge, not a staircase.
void relax_boundary_vertices(const SlabLattice& g, const NodeLabels& n, std::vector<glm::dvec2>& cell_xy) {
  const int C = g.C;
  std::vector<char> boundary(g.cells(), 0);
  for (int cj = 0; cj < C; ++cj)
    for (int ci = 0; ci < C; ++ci) {
      const int a = n.at(g, ci, cj);
      boundary[g.cell(ci, cj)] = n.at(g, ci + 1, cj) != a || n.at(g, ci + 1, cj + 1) != a || n.at(g, ci, cj + 1) != a;
    }
  std::vector<glm::dvec2> next = cell_xy;
  for (int step = 0; step < 2; ++step) {
    for (int cj = 1; cj + 1 < C; ++cj)
      for (int ci = 1; ci + 1 < C; ++ci) {
        const std::size_t c = g.cell(ci, cj);
        if (!boundary[c]) continue;
        glm::dvec2 sum = cell_xy[c];
        int k = 1;
        for (const std::size_t nb : {c - 1, c + 1, c - std::size_t(C), c + std::size_t(C)})
          if (boundary[nb]) {
            sum += cell_xy[nb];
            ++k;
          }
        const glm::dvec2 lo = g.node_pos(ci, cj) + 0.05 * g.h, hi = g.node_pos(ci + 1, cj + 1) - 0.05 * g.h;
        next[c] = glm::clamp(sum / double(k), lo, hi);
      }
    cell_xy.swap(next);
    next = cell_xy;
  }
}

// Phase 5. Distance to the nearest crack cell with that crack's shift carried along (two-pass
// chamfer distance transform, Borgefors 1986).
void spread_crack_shifts(const SlabLattice& g, SurfaceNet& s) {
  const int C = g.C;
  const float dx = float(g.h), dd = float(g.h * std::sqrt(2.0));
  const auto relax = [&](int ci, int cj, int ni, int nj, float w) {
    if (ni < 0 || nj < 0 || ni >= C || nj >= C) return;
    const std::size_t a = g.cell(ci, cj), b = g.cell(ni, nj);
    if (s.dist[b] + w < s.dist[a]) {
      s.dist[a] = s.dist[b] + w;
      s.src_shift[a] = s.src_shift[b];
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

// Phase 6. The bottom face's horizontal lean under each cell: the grain walls' random
// inclination (`field`) and, near a crack, the crack's own lean (`crack`): 1 on the crack, fading
// over R ≥ 2.5·|Δ| (slope ≤ 0.6).
struct BottomLean {
  std::vector<glm::dvec2> field, crack;
};

BottomLean bottom_lean(const SlabLattice& g, const SurfaceNet& s, const SectionSlabOptions& o) {
  const WaveField fx(o.seed * 4 + 1, 400.0, 900.0), fy(o.seed * 4 + 2, 400.0, 900.0);
  // RMS |shift| = t·tan(inclination): each component's RMS is that over √2.
  const double amp = o.thickness_um * std::tan(radians(o.inclination_deg)) / std::sqrt(2.0);
  BottomLean b{std::vector<glm::dvec2>(g.cells()), std::vector<glm::dvec2>(g.cells(), glm::dvec2(0.0))};
  tbb::parallel_for(tbb::blocked_range<int>(0, g.C), [&](const tbb::blocked_range<int>& rows) {
    for (int cj = rows.begin(); cj < rows.end(); ++cj)
      for (int ci = 0; ci < g.C; ++ci) {
        const std::size_t cell = g.cell(ci, cj);
        const glm::dvec2 p = s.cell_xy[cell];
        b.field[cell] = amp > 0.0 ? amp * glm::dvec2(fx(p), fy(p)) : glm::dvec2(0.0);
        if (std::isfinite(s.dist[cell])) {
          const glm::dvec2 delta = s.src_shift[cell] - b.field[cell];
          const double R = 2.5 * glm::length(delta) + 2.0 * g.h;
          b.crack[cell] = (1.0 - smoothstep01(double(s.dist[cell]) / R)) * delta;
        }
      }
  });
  return b;
}

// Phase 7. Where cracks of two families (or of two grains) meet, their leans differ by up to
// 2·t·tan 30° over one cell: two box filters of radius 25 µm turn that jump into a ramp of slope
// < 0.7 (the slab must not fold; the crossing planes cannot both be followed to the bottom
// there), at the cost of ~20 % of a crack's lean.
void smooth_crack_lean(const SlabLattice& g, std::vector<glm::dvec2>& crack) {
  const int C = g.C;
  const int r = std::max(1, int(std::ceil(25.0 / g.h)));
  std::vector<glm::dvec2> tmp(g.cells());
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

// Phase 8. The vertices: top (index cell) at the smoothed vertex, raised by the polishing
// relief; bottom (C² + cell) at the unsmoothed vertex, leaned.
void slab_vertices(const SlabLattice& g, const std::vector<glm::dvec2>& top_xy, const std::vector<glm::dvec2>& bottom_xy,
                   const BottomLean& lean, const SectionSlabOptions& o, SpecimenMesh& mesh) {
  // Polishing relief of 8–20 µm wavelength: RMS slope ≈ 2π·0.15/14 ≈ 0.07 rad, which a surface
  // between media 0.3 apart in n (garnet in epoxy) turns into deviations of ~0.02 rad, the size of
  // a stopped-down condenser's cone: shagreen, while quartz (Δn ≈ 0.01) stays smooth.
  const WaveField rough(o.seed * 4 + 3, 8.0, 20.0);
  const double z_bottom = o.film_um, z_top = o.film_um + o.thickness_um;
  const std::size_t cells = g.cells();
  mesh.vertices.resize(2 * cells);
  tbb::parallel_for(tbb::blocked_range<int>(0, g.C), [&](const tbb::blocked_range<int>& rows) {
    for (int cj = rows.begin(); cj < rows.end(); ++cj)
      for (int ci = 0; ci < g.C; ++ci) {
        const std::size_t cell = g.cell(ci, cj);
        const glm::dvec2 p = top_xy[cell];
        const double zr = o.roughness_um > 0.0 ? o.roughness_um * rough(p) : 0.0;
        mesh.vertices[cell] = {p, z_top + zr};
        mesh.vertices[cells + cell] = {bottom_xy[cell] + lean.field[cell] + lean.crack[cell], z_bottom};
      }
  });
}

// Phase 9. The faces: each solid node's top and bottom quad, and a wall wherever two nodes'
// media differ.
void slab_faces(const SlabLattice& g, const NodeLabels& n, SpecimenMesh& mesh) {
  const int N = g.N, C = g.C;
  const auto L = [&](int i, int j) { return n.at(g, i, j); };
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
}

}  // namespace

std::unique_ptr<SpecimenScene> build_section_slab(const std::shared_ptr<const SectionMap>& map,
                                                  const IsotropicMedium& medium, const SectionSlabOptions& o) {
  if (!map) throw std::invalid_argument("build_section_slab: no section");
  if (!(o.spacing_um > 0.0) || !(o.thickness_um > 0.0) || !(o.half_width_mm > 0.0) || !(o.film_um > 0.0))
    throw std::invalid_argument("build_section_slab: spacing, thickness, window and film must be positive");
  const std::vector<int> medium_of_domain = section_slab_media(*map);
  std::vector<SpecimenMedium> media = slab_media(map, medium_of_domain);
  const SlabLattice g(o);
  const NodeLabels labels = label_nodes(*map, g, medium_of_domain, o.thickness_um);
  SurfaceNet net = place_cell_vertices(g, labels);
  // The bottom keeps the unsmoothed vertices: a smoothed quad can be thin enough for the lean's
  // gradient to turn it over (measured: 20 of 80 000 bottom faces of a schist window).
  const std::vector<glm::dvec2> cell_xy_raw = net.cell_xy;
  relax_boundary_vertices(g, labels, net.cell_xy);
  spread_crack_shifts(g, net);
  BottomLean lean = bottom_lean(g, net, o);
  smooth_crack_lean(g, lean.crack);
  SpecimenMesh mesh;
  slab_vertices(g, net.cell_xy, cell_xy_raw, lean, o, mesh);
  slab_faces(g, labels, mesh);
  SpecimenLayers layers;
  layers.liquid_um = o.thickness_um + 2.0 * o.film_um;
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
      << scene.sample.medium_index.value_or(0.0) << '|' << scene.sample.orientation_seed.value_or(-1) << '|' << scene.sample.seed.value_or(-1);
  // One slab kept: the app looks at one field at a time; a stage move rebuilds.
  static BuildCache<std::string, SpecimenScene, Keep::Last> cache;
  return cache.get(key.str(), [&] { return build_section_slab(load_scene_section(scene), medium, o); });
}

}  // namespace pmsim
