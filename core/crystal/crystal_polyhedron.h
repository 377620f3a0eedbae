#pragma once
// A crystal's shape as a convex polyhedron bounded by face planes: {x : n_f·x ≤ h_f for every f},
// centred on its nucleus, in the section frame (mm). Grown crystals (core/texture) take this shape
// at every stage of growth, scaled about the nucleus: a crystal that grows at a constant linear
// rate keeps its faces parallel (the constant-habit growth of Marsh 1988's CSD theory), so the
// part of it reached by time t is {x : gauge(x) ≤ s(t)}.
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace pmsim {

struct MineralCrystallography;

// With no faces it is a ball of radius support_mm[0]: a grain that has no faces of its own, whose
// boundaries its neighbours alone set (the cells of a granoblastic foam, sphere_polyhedron).
struct CrystalPolyhedron {
  std::vector<glm::dvec3> normals;  // unit outward face normals, section frame
  std::vector<double> support_mm;   // distance of each face plane from the nucleus (> 0)
  double circumradius_mm = 0.0;     // the largest distance of a vertex from the nucleus
};

// The ball of diameter size_mm (gauge |x| / radius). Equal balls growing from simultaneous nuclei
// meet on the perpendicular bisector planes: the owners are the nuclei's Voronoi cells.
CrystalPolyhedron sphere_polyhedron(double size_mm);

// Minkowski gauge of the polyhedron: max_f n_f·x / h_f. 1 on the faces, < 1 inside, convex and
// positively homogeneous (gauge(kx) = k·gauge(x), k ≥ 0), so the crystal scaled by s is gauge ≤ s.
double gauge(const CrystalPolyhedron& p, const glm::dvec3& x);

// gauge(x) ≥ |x| / circumradius: the lower bound the section's lookup grid uses.
double circumradius_mm(const CrystalPolyhedron& p);

// Default true aspect ratios (length / width) of a habit when a file gives none: prisms of
// pyroxene and amphibole about 3 : 1, plates (micas) about 5 : 1 diameter / thickness (Deer, Howie
// & Zussman 2013, habit descriptions); 1 without a habit.
double default_habit_aspect(const MineralCrystallography* mc);

// The free-growth shape of a crystal of size_mm (its longest dimension) whose crystal frame has
// columns L in the section frame, from the habit in its mineral file:
// - a lath (elongation [uvw] and tabular (hkl), plagioclase): length size along [uvw], thickness
//   size/aspect across (hkl), width size/√aspect between, as the ellipsoid of section_map.h;
// - a prism ([uvw]): faces ∥ [uvw] from the prismatic cleavages that contain it (pyroxene and
//   amphibole {110}: their 87° and 124° basal outlines, Deer, Howie & Zussman 2013), else a square
//   prism; width size/aspect; ends ⟂ [uvw];
// - a plate ((hkl)): a pseudo-hexagonal plate of diameter size and thickness size/aspect (mica
//   books, Deer, Howie & Zussman 2013);
// - equant (no habit or no lattice): a rhombic dodecahedron {110} for cubic minerals (garnet's
//   form), else the three pinacoids truncated by the {110}, {101}, {011} planes.
// mc may be null (no crystallography): equant, oriented by L.
CrystalPolyhedron habit_polyhedron(const MineralCrystallography* mc, const glm::dmat3& L, double size_mm,
                                   double aspect);
// The same in two steps: the shape of size 1 in the crystal frame (L = identity), then placed:
// normals turned by L, supports and circumradius scaled by size. habit_polyhedron is exactly
// placed(habit_template(…), L, size), so a generator that places one template many times builds
// the crystals a section file's reader builds, bit for bit.
CrystalPolyhedron habit_template(const MineralCrystallography* mc, double aspect);
CrystalPolyhedron placed(const CrystalPolyhedron& unit, const glm::dmat3& L, double size_mm);

}  // namespace pmsim
