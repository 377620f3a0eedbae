#pragma once
// The geometry of a grain mount: mineral fragments lying on the slide in a layer of immersion
// liquid under the cover glass. Lengths in µm; lab frame of core/microscope/scene.h (x east, y
// north, z up toward the objective); z = 0 is the top of the slide.
//
// A fragment is a closed triangle mesh, star-shaped about its centre: an icosphere whose radius
// is modulated by a few random smooth lobes, flattened as fragments settle on their broad side
// (flat top and bottom, inclined edges), turned about z, then cut by the faces it broke along:
// cleavage planes (calcite, feldspar, pyroxene) or curved conchoidal fracture faces (quartz,
// garnet), which give its outline straight or curved edges meeting in sharp corners. Outward
// winding (counter-clockwise seen from outside), so cross(v1 − v0, v2 − v0) is the outward normal.
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace pmsim {

// A conchoidal fracture face: the shell-shaped surface a mineral without cleavage breaks along
// (quartz, garnet; C. Klein & B. Dutrow, Manual of Mineral Science, 23rd ed., 2007: fracture).
// It is the paraboloid n·q = d − κ·|q − (q·n)n|²/2 about the axis through the fragment's centre
// along n (q = p − centre): κ > 0 bulges outward (a convex shell), κ < 0 is hollowed (a concave
// one). The fragment keeps the side n·q below the surface.
struct FractureFace {
  glm::dvec3 normal{1.0, 0.0, 0.0};  // unit, lab frame
  double offset_fraction = 0.7;      // d: this × the unmodulated blob's half-extent along n
  double curvature = 0.0;            // κ × the blob's horizontal semi-axis (dimensionless)
};

struct FragmentShape {
  glm::dvec2 centre_um{0.0};      // position on the slide
  double size_um = 100.0;         // largest horizontal extent (diameter of the unmodulated blob)
  double height_ratio = 0.45;     // vertical semi-axis / horizontal semi-axis
  double elongation = 1.0;        // semi-axis along y' / along x' (≤ 1)
  double azimuth_rad = 0.0;       // turn about z of the fragment's long axis x'
  double roughness = 0.12;        // relative amplitude of the outline's lobes (0: a smooth oval)
  // Broad faces: the profile of a superellipsoid, |z|^k + ρ^k = 1 in the unit blob (ρ the
  // horizontal radius; k = 2 an ellipsoid; k = 8: flat top and bottom, slope ∝ ρ⁷, with
  // inclined, rounded edges, like a fragment lying on a fracture or cleavage face).
  double flatness = 8.0;
  std::uint64_t seed = 1;         // the lobes' phases and directions
  glm::dmat3 crystal_to_lab{1.0};  // columns: crystal X, Y, Z (indicatrix axes) in the lab frame
  // A cleavage fragment's other cleavage planes (unit normals, lab frame): the blob is cut to the
  // slab |(p − centre)·n| ≤ clip_fraction × its half-extent along n for each, so that its outline
  // runs along those cleavages' traces in straight (possibly inclined) faces.
  std::vector<glm::dvec3> clip_normals;
  double clip_fraction = 0.7;
  // A fragment of fracture's conchoidal faces (empty: the smooth lobed blob).
  std::vector<FractureFace> fracture_faces;
};

struct FragmentMesh {
  std::vector<glm::dvec3> vertices;        // µm, lab frame
  std::vector<glm::uvec3> triangles;       // outward winding
  double z_min_um = 0.0, z_max_um = 0.0;
};

// The mesh of one fragment resting `gap_um` above the slide (a liquid film under it).
// `subdivisions` of the icosahedron: 3 gives 1280 triangles, facets of ~4° of the blob.
FragmentMesh fragment_mesh(const FragmentShape& shape, double gap_um = 1.0, int subdivisions = 3);

struct ScatterOptions {
  double field_width_um = 2000.0, field_height_um = 2000.0;  // the area to fill, centred on 0
  double min_size_um = 30.0, max_size_um = 300.0;            // log-uniform sizes
  double coverage = 0.25;                                    // target area fraction
  // Fragments settle on their broad side: the vertical semi-axis is at most this, so that one
  // focus shows small and large fragments together in a liquid film of ~2× this thickness.
  double max_half_height_um = 40.0;
  // The mineral's good (perfect, very good, good) cleavage planes, unit normals in the indicatrix
  // frame (crystal X, Y, Z). Empty: fragments of fracture, uniformly random orientations. Else
  // cleavage fragments: each lies flat on one of them (drawn at random), turned at random about
  // the vertical, its outline cut along the others (FragmentShape::clip_normals).
  std::vector<glm::dvec3> cleavage_normals;
  std::uint64_t seed = 12;
};

// The orientation (crystal_to_lab) of a fragment lying on the cleavage of unit normal `n` (the
// indicatrix frame): n along +z (or −z if `flip`), then turned by `azimuth_rad` about z.
glm::dmat3 cleavage_orientation(const glm::dvec3& n, double azimuth_rad, bool flip);
// Fragments placed at random without overlap (rejection of overlapping bounding circles), random
// size, shape, azimuth and a uniformly random 3-D orientation of the crystal (Shoemake's
// quaternion method), or a cleavage fragment's (see cleavage_normals). A fragment of fracture
// (no cleavage) gets 5–8 steep conchoidal faces round its outline (conchoidal_faces). Reproducible
// from options.seed; the faces come from each fragment's own seed, so a mineral without cleavage
// places the same fragments, in the same orientations, as before either cut existed.
// The conchoidal faces of one fragment of fracture, drawn from `seed`: `count` steep faces (normal
// within 24° of horizontal) at stratified azimuths round the outline, cut at 0.6–0.9 of the
// blob's extent, each a shell of radius 1–4 semi-axes, convex or concave at random.
std::vector<FractureFace> conchoidal_faces(std::uint64_t seed);

std::vector<FragmentShape> scatter_fragments(const ScatterOptions& options);

}  // namespace pmsim
