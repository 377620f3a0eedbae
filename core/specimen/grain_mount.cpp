#include "core/specimen/grain_mount.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/base/units.h"
#include "core/specimen/specimen_random.h"

namespace pmsim {

namespace {

// Unit icosphere: the icosahedron with each triangle split in four `subdivisions` times, new
// vertices pushed onto the sphere; outward winding.
void icosphere(int subdivisions, std::vector<glm::dvec3>& v, std::vector<glm::uvec3>& f) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
       {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : v) p = glm::normalize(p);
  f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
       {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
       {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<unsigned, unsigned>, unsigned> mid;
    auto midpoint = [&](unsigned a, unsigned b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(glm::normalize(v[a] + v[b]));
      const unsigned id = unsigned(v.size() - 1);
      mid.emplace(key, id);
      return id;
    };
    std::vector<glm::uvec3> g;
    g.reserve(f.size() * 4);
    for (const glm::uvec3& tri : f) {
      const unsigned a = midpoint(tri.x, tri.y), b = midpoint(tri.y, tri.z), c = midpoint(tri.z, tri.x);
      g.push_back({tri.x, a, c});
      g.push_back({tri.y, b, a});
      g.push_back({tri.z, c, b});
      g.push_back({a, b, c});
    }
    f = std::move(g);
  }
}

// A uniformly random rotation (K. Shoemake, "Uniform random rotations", Graphics Gems III, 1992).
glm::dmat3 random_rotation(SpecimenRandom& rng) {
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const glm::dquat q(a * std::sin(2 * kPi * u2), a * std::cos(2 * kPi * u2), b * std::sin(2 * kPi * u3),
                     b * std::cos(2 * kPi * u3));  // (w, x, y, z)
  return glm::mat3_cast(glm::normalize(q));
}

// Half-extent along the lab direction n of the unmodulated blob (the ellipsoid of semi-axes
// `scale` turned by azimuth_rad about z): its support function |S·Rᵀn|.
double blob_half_extent(const glm::dvec3& n, double azimuth_rad, const glm::dvec3& scale) {
  const double c = std::cos(azimuth_rad), s = std::sin(azimuth_rad);
  const glm::dvec3 nl{c * n.x + s * n.y, -s * n.x + c * n.y, n.z};  // fragment frame
  return glm::length(nl * scale);
}

// Pulls each vertex (relative to the centre, lab frame) outside a conchoidal face in along its ray
// onto the face: q = t·u on n·q = d − κ·t²(1 − (u·n)²)/2, the smaller positive root
// t = 2d / (b + √(b² + 4ad)) with b = u·n, a = κ(1 − b²)/2 (the stable form: no cancellation
// for a → 0, where it is the plane's d/b). No real root, or none ahead: the ray never leaves.
void cut_conchoidal(const FractureFace& face, const FragmentShape& shape, const glm::dvec3& scale,
                    std::vector<glm::dvec3>& vertices) {
  const glm::dvec3& n = face.normal;
  const double d = face.offset_fraction * blob_half_extent(n, shape.azimuth_rad, scale);
  const double semi = scale.x, r_max = semi * (1.0 + shape.roughness);
  double kappa = face.curvature / semi;
  if (kappa < 0.0) {
    // A concave face has rays that just graze it, where the cut would jump to nothing: its
    // tangent ray meets it at t = 2d/b* with b*² = q/(1 + q), q = 2|κ|d. Keep that beyond the
    // blob (≥ 1.05 r_max), so the jump is never in the outline: q ≤ 1/(A − 1), A = (1.05 r_max/2d)².
    const double big_a = std::pow(1.05 * r_max / (2.0 * d), 2.0);
    if (big_a > 1.0) kappa = -std::min(-kappa, 1.0 / (big_a - 1.0) / (2.0 * d));
  }
  for (glm::dvec3& p : vertices) {
    const double len = glm::length(p);
    if (len <= 0.0) continue;
    const double b = glm::dot(p, n) / len;
    const double a = 0.5 * kappa * std::max(0.0, 1.0 - b * b);
    const double disc = b * b + 4.0 * a * d;
    if (disc < 0.0) continue;
    const double denom = b + std::sqrt(disc);
    if (denom <= 0.0) continue;
    const double t = 2.0 * d / denom;
    if (len > t) p *= t / len;
  }
}

}  // namespace

std::vector<FractureFace> conchoidal_faces(std::uint64_t seed) {
  SpecimenRandom rng(seed ^ 0xc0c401da1ull);
  const int count = 5 + std::min(3, int(4.0 * rng.uniform()));
  const double phi0 = 2.0 * kPi * rng.uniform();
  std::vector<FractureFace> faces;
  faces.reserve(std::size_t(count));
  for (int k = 0; k < count; ++k) {
    const double phi = phi0 + 2.0 * kPi * (k + 0.7 * (rng.uniform() - 0.5)) / count;
    const double elevation = radians(24.0) * (2.0 * rng.uniform() - 1.0);
    FractureFace f;
    f.normal = {std::cos(elevation) * std::cos(phi), std::cos(elevation) * std::sin(phi), std::sin(elevation)};
    f.offset_fraction = 0.6 + 0.3 * rng.uniform();
    const double radius = 1.0 + 3.0 * rng.uniform();  // semi-axes
    f.curvature = (rng.uniform() < 0.5 ? 1.0 : -1.0) / radius;
    faces.push_back(f);
  }
  return faces;
}

glm::dmat3 cleavage_orientation(const glm::dvec3& n_in, double azimuth_rad, bool flip) {
  // An orthonormal frame (e1, e2, n) in crystal coordinates; the rotation takes it to the lab's
  // (x, y, ±z), then turns about z. Its transpose maps lab to crystal, so crystal_to_lab = Rz·Fᵀ
  // with F's rows e1, e2, n: crystal_to_lab · n = ±z exactly (to rounding).
  const glm::dvec3 n = glm::normalize(flip ? -n_in : n_in);
  const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 e1 = glm::normalize(glm::cross(helper, n));
  const glm::dvec3 e2 = glm::cross(n, e1);
  // Columns of crystal_to_lab are the images of crystal X, Y, Z: row i of F is e1, e2, n, so the
  // image of crystal axis j is (e1[j], e2[j], n[j]) before the turn.
  glm::dmat3 to_lab;
  for (int j = 0; j < 3; ++j) to_lab[j] = glm::dvec3(e1[j], e2[j], n[j]);
  const double c = std::cos(azimuth_rad), s = std::sin(azimuth_rad);
  const glm::dmat3 rz(glm::dvec3(c, s, 0), glm::dvec3(-s, c, 0), glm::dvec3(0, 0, 1));
  return rz * to_lab;
}

FragmentMesh fragment_mesh(const FragmentShape& shape, double gap_um, int subdivisions) {
  FragmentMesh m;
  std::vector<glm::dvec3> unit;
  icosphere(subdivisions, unit, m.triangles);
  // Horizontal modulation r(u) = 1 + roughness·Σ_k w_k·cos(f_k·(u·d_k) + φ_k): smooth lobes of
  // random direction and angular frequency, normalized so that |r − 1| ≤ roughness. The blob
  // stays star-shaped, a closed, non-self-intersecting mesh, for roughness < 1.
  constexpr int kLobes = 5;
  SpecimenRandom rng(shape.seed);
  glm::dvec3 dir[kLobes];
  double freq[kLobes], phase[kLobes], weight[kLobes], wsum = 0.0;
  for (int k = 0; k < kLobes; ++k) {
    const double z = 2.0 * rng.uniform() - 1.0, phi = 2.0 * kPi * rng.uniform();
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    dir[k] = {r * std::cos(phi), r * std::sin(phi), z};
    freq[k] = 1.5 + 2.0 * rng.uniform();
    phase[k] = 2.0 * kPi * rng.uniform();
    weight[k] = 0.5 + rng.uniform();
    wsum += weight[k];
  }
  const double semi = 0.5 * shape.size_um;
  const glm::dvec3 scale{semi, semi * shape.elongation, semi * shape.height_ratio};
  const double c = std::cos(shape.azimuth_rad), s = std::sin(shape.azimuth_rad);
  m.vertices.reserve(unit.size());
  for (const glm::dvec3& u : unit) {
    double r = 0.0;
    for (int k = 0; k < kLobes; ++k) r += weight[k] * std::cos(freq[k] * glm::dot(u, dir[k]) + phase[k]);
    r = 1.0 + shape.roughness * r / wsum;
    // Keep the sphere's horizontal radius ρ and set |z| = (1 − ρ^k)^(1/k) (superellipsoid profile).
    const double rho = std::min(1.0, std::hypot(u.x, u.y));
    const double zk = std::pow(std::max(0.0, 1.0 - std::pow(rho, shape.flatness)), 1.0 / shape.flatness);
    const glm::dvec3 flat{u.x, u.y, std::copysign(zk, u.z)};
    // The lobes move the outline only (x, y): the broad faces stay flat, as fracture and cleavage
    // faces of a fragment are, and the irregularity is in its outline and inclined edges.
    const glm::dvec3 p = glm::dvec3(r * flat.x, r * flat.y, flat.z) * scale;
    m.vertices.push_back({c * p.x - s * p.y, s * p.x + c * p.y, p.z});
  }
  // Cleavage faces: each vertex outside a slab is pulled in along its ray from the centre onto
  // the slab's face. The blob stays star-shaped about the centre (inside every slab), and a
  // triangle whose corners all land on one face lies in that plane: a flat cleavage face.
  for (const glm::dvec3& n_lab : shape.clip_normals) {
    const double d = shape.clip_fraction * blob_half_extent(n_lab, shape.azimuth_rad, scale);
    for (glm::dvec3& p : m.vertices) {
      const double a = glm::dot(p, n_lab);
      if (std::abs(a) > d) p *= d / std::abs(a);
    }
  }
  for (const FractureFace& face : shape.fracture_faces) cut_conchoidal(face, shape, scale, m.vertices);
  double zmin = 1e300, zmax = -1e300;
  for (const auto& p : m.vertices) zmin = std::min(zmin, p.z), zmax = std::max(zmax, p.z);
  for (auto& p : m.vertices) p += glm::dvec3(shape.centre_um, gap_um - zmin);
  m.z_min_um = gap_um;
  m.z_max_um = gap_um + (zmax - zmin);
  return m;
}

std::vector<FragmentShape> scatter_fragments(const ScatterOptions& o) {
  SpecimenRandom rng(o.seed);
  std::vector<FragmentShape> out;
  const double area = o.field_width_um * o.field_height_um;
  double covered = 0.0;
  // Bounded attempts: a full field stops the loop even if the coverage is not reached.
  for (int attempt = 0; attempt < 4000 && covered < o.coverage * area; ++attempt) {
    FragmentShape f;
    f.size_um = o.min_size_um * std::pow(o.max_size_um / o.min_size_um, rng.uniform());
    f.elongation = 0.55 + 0.45 * rng.uniform();
    f.height_ratio = std::min(0.3 + 0.25 * rng.uniform(), o.max_half_height_um / (0.5 * f.size_um));
    f.azimuth_rad = kPi * rng.uniform();
    f.roughness = 0.08 + 0.12 * rng.uniform();
    f.seed = splitmix64(o.seed ^ (0x5bd1e995ull * std::uint64_t(attempt + 1)));
    f.centre_um = {(rng.uniform() - 0.5) * o.field_width_um, (rng.uniform() - 0.5) * o.field_height_um};
    if (o.cleavage_normals.empty()) {
      f.crystal_to_lab = random_rotation(rng);
      f.fracture_faces = conchoidal_faces(f.seed);
    } else {
      // Three draws, as random_rotation takes: the turn about z, which cleavage, which side up.
      const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
      const std::size_t k = std::min(o.cleavage_normals.size() - 1, std::size_t(u2 * o.cleavage_normals.size()));
      f.crystal_to_lab = cleavage_orientation(o.cleavage_normals[k], 2.0 * kPi * u1, u3 < 0.5);
      for (std::size_t j = 0; j < o.cleavage_normals.size(); ++j) {
        if (j == k) continue;
        const glm::dvec3 n = glm::normalize(f.crystal_to_lab * o.cleavage_normals[j]);
        // A cleavage (nearly) parallel to the one it lies on adds no outline.
        if (std::abs(n.z) < 0.95) f.clip_normals.push_back(n);
      }
    }
    // Bounding circle of the modulated blob: radius ≤ (1 + roughness)·size/2; keep 2 µm of liquid.
    const double rad = 0.5 * f.size_um * (1.0 + f.roughness);
    bool free = true;
    for (const FragmentShape& g : out) {
      const double rg = 0.5 * g.size_um * (1.0 + g.roughness);
      if (glm::length(f.centre_um - g.centre_um) < rad + rg + 2.0) {
        free = false;
        break;
      }
    }
    if (!free) continue;
    out.push_back(f);
    covered += kPi * 0.25 * f.size_um * f.size_um * f.elongation;
  }
  return out;
}

}  // namespace pmsim
