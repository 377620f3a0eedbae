#include "core/ebsd/example_map.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include "core/crystal/euler_angles.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/ebsd/ebsd_frames.h"

namespace pmsim {

namespace {

// splitmix64 (Steele et al. 2014) to [0, 1): a stream per (seed, object, draw).
double u01(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull ^ (a + 0x632BE59BD9B4E019ull) * 0xBF58476D1CE4E5B9ull ^
                    (b + 0x2545F4914F6CDD1Dull) * 0x94D049BB133111EBull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

glm::dquat uniform_rotation(std::uint64_t seed, std::uint64_t id) {  // Shoemake's method
  const double u1 = u01(seed, id, 0), u2 = u01(seed, id, 1), u3 = u01(seed, id, 2);
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  return {a * std::sin(2 * M_PI * u2), a * std::cos(2 * M_PI * u2), b * std::sin(2 * M_PI * u3),
          b * std::cos(2 * M_PI * u3)};
}

glm::dvec3 random_axis(std::uint64_t seed, std::uint64_t id) {
  const double z = 2 * u01(seed, id, 5) - 1, t = 2 * M_PI * u01(seed, id, 6), r = std::sqrt(1 - z * z);
  return {r * std::cos(t), r * std::sin(t), z};
}

// Jittered seeds on a square lattice of `cell_um`, looked up through their lattice cell.
struct Seeds {
  double cell_um;
  int nx, ny;
  std::vector<glm::dvec2> p;
  Seeds(double width_um, double height_um, double cell, std::uint64_t seed, std::uint64_t stream)
      : cell_um(cell), nx(static_cast<int>(std::ceil(width_um / cell)) + 1), ny(static_cast<int>(std::ceil(height_um / cell)) + 1) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::uint64_t id = stream * 100000000ull + static_cast<std::uint64_t>(j) * nx + i;
        p.push_back({(i + 0.1 + 0.8 * u01(seed, id, 3)) * cell, (j + 0.1 + 0.8 * u01(seed, id, 4)) * cell});
      }
  }
  // Nearest and second-nearest seed distances; returns the nearest's index.
  int nearest(const glm::dvec2& q, double* d1, double* d2) const {
    const int ci = static_cast<int>(q.x / cell_um), cj = static_cast<int>(q.y / cell_um);
    int best = 0;
    double b1 = 1e300, b2 = 1e300;
    for (int j = std::max(0, cj - 2); j <= std::min(ny - 1, cj + 2); ++j)
      for (int i = std::max(0, ci - 2); i <= std::min(nx - 1, ci + 2); ++i) {
        const int k = j * nx + i;
        const double d = glm::length(q - p[k]);
        if (d < b1) {
          b2 = b1;
          b1 = d;
          best = k;
        } else if (d < b2) {
          b2 = d;
        }
      }
    if (d1) *d1 = b1;
    if (d2) *d2 = b2;
    return best;
  }
};

glm::dmat3 half_turn(const glm::dvec3& u) {
  glm::dmat3 r(0.0);
  for (int c = 0; c < 3; ++c)
    for (int rr = 0; rr < 3; ++rr) r[c][rr] = 2.0 * u[c] * u[rr] - (c == rr ? 1.0 : 0.0);
  return r;
}

}  // namespace

OrientationMap example_quartzite_map(int columns, int rows, double step_um, double grain_um, std::uint64_t seed) {
  OrientationMap m;
  m.vendor = EbsdVendor::OxfordChannel5;
  m.grid = MapGrid::Square;
  m.columns_odd = m.columns_even = columns;
  m.rows = rows;
  m.step_x_um = m.step_y_um = step_um;
  // Cells: Deer, Howie & Zussman (2013) — quartz a 4.913, c 5.405 Å; calcite a 4.990, c 17.062 Å;
  // almandine a 11.53 Å.
  m.phases = {EbsdPhase{1, "Quartz", "SiO2", UnitCell{4.913, 4.913, 5.405, 90, 90, 120}, CrystalSystem::Trigonal,
                        "-3m", "7", 154},
              EbsdPhase{2, "Calcite", "CaCO3", UnitCell{4.990, 4.990, 17.062, 90, 90, 120}, CrystalSystem::Trigonal,
                        "-3m", "7", 167},
              EbsdPhase{3, "Garnet", "Fe3Al2Si3O12", UnitCell{11.53, 11.53, 11.53, 90, 90, 90}, CrystalSystem::Cubic,
                        "m-3m", "11", 230}};
  m.allocate_points();
  const double W = (columns - 1) * step_um, H = (rows - 1) * step_um;
  const Seeds grains(W + step_um, H + step_um, grain_um, seed, 1), subgrains(W + step_um, H + step_um, grain_um / 3, seed, 2);
  // The e-twin: half-turn about the (01-12) normal, in pmsim's crystal frame of calcite's cell.
  const UnitCell calcite_cell = m.phases[1].cell;
  const glm::dvec3 e_normal = glm::normalize(plane_normal(calcite_cell, parse_miller_plane("(01-12)")));
  const glm::dmat3 twin = half_turn(e_normal);
  std::vector<glm::dmat3> vendor_frame;
  for (const EbsdPhase& ph : m.phases) vendor_frame.push_back(vendor_crystal_frame(m.vendor, ph.system, ph.cell));
  const glm::dmat3 S = vendor_specimen_frame(m.vendor);
  for (std::size_t i = 0; i < m.size(); ++i) {
    const glm::dvec2 q{m.x_um(i), m.y_um(i)};
    double d1, d2;
    const int gk = grains.nearest(q, &d1, &d2);
    const std::uint64_t g = static_cast<std::uint64_t>(gk);
    const double kind = u01(seed, g, 7);
    const int phase = kind < 0.85 ? 1 : kind < 0.95 ? 2 : 3;
    if ((d2 - d1 < 0.6 * step_um && u01(seed, i, 8) < 0.5) || u01(seed, i, 9) < 0.01) continue;  // non-indexed
    glm::dmat3 c = glm::mat3_cast(uniform_rotation(seed, g));  // pmsim crystal → section
    const glm::dvec2 centre = grains.p[gk];
    if (phase == 1) {
      // Subgrain: 2–5° about a random axis; bending: 1°/100 µm about an in-plane axis.
      const std::uint64_t sg = static_cast<std::uint64_t>(subgrains.nearest(q, nullptr, nullptr)) + 7777777ull;
      const double sub_deg = 2.0 + 3.0 * u01(seed, sg, 10);
      const glm::dmat3 sub = glm::mat3_cast(glm::angleAxis(sub_deg * M_PI / 180.0, random_axis(seed, sg)));
      const double bend_dir = 2 * M_PI * u01(seed, g, 11);
      const glm::dvec2 along{std::cos(bend_dir), std::sin(bend_dir)};
      const double bend_rad = 1.0 * glm::dot(q - centre, along) / 100.0 * M_PI / 180.0;
      const glm::dmat3 bend =
          glm::mat3_cast(glm::angleAxis(bend_rad, glm::dvec3(-along.y, along.x, 0.0)));
      c = bend * sub * c;
    } else if (phase == 2) {
      // Lamellae 20 µm wide on the trace of (01-12) in the map (normal projected to the section).
      const glm::dvec3 n = c * e_normal;
      const glm::dvec2 nt = glm::length(glm::dvec2(n.x, n.y)) > 1e-6 ? glm::normalize(glm::dvec2(n.x, n.y)) : glm::dvec2(1, 0);
      if (static_cast<long>(std::floor(glm::dot(q - centre, nt) / 20.0)) % 2 != 0) c = c * twin;
    }
    // Noise 0.1° about a random axis.
    c = glm::mat3_cast(glm::angleAxis(0.1 * M_PI / 180.0 * u01(seed, i, 12), random_axis(seed, i + 99999999ull))) * c;
    // Back to the vendor's Bunge angles: crystal_to_section = S · gᵀ · Rᵀ, so gᵀ = Sᵀ · C · R.
    const EulerBunge e = bunge_from_crystal_to_sample(glm::transpose(S) * c * vendor_frame[phase - 1]);
    m.phase[i] = static_cast<std::uint8_t>(phase);
    m.phi1_rad[i] = static_cast<float>(e.phi1_rad);
    m.Phi_rad[i] = static_cast<float>(e.Phi_rad);
    m.phi2_rad[i] = static_cast<float>(e.phi2_rad);
  }
  m.points_in_file = m.size();
  return m;
}

}  // namespace pmsim
