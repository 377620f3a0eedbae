#pragma once
// A thin section in three dimensions (issue 12): the part of a 2-D section map (SectionMap) around
// the field of view as a slab of solid grains, thickness_um thick, between films of mounting medium
// on the slide and under the cover glass (the SpecimenScene stack: slide, liquid layer = film +
// slab + film, cover glass). Section coordinates mm → specimen µm (x east, y north at stage 0°,
// origin at the section's centre), so render_plane_light with centre_um = 1000·stage and the stage
// angle shows the same section points as the orthoscopic section image, pixel for pixel.
//
// Geometry, watertight by construction (a "dual grid", as surface nets, Gibson 1998): the optical
// domain is sampled on a square grid of nodes (spacing h); each grid cell gets one vertex (its
// centre where its four nodes agree, else the mean of the midpoints of its edges whose labels
// differ). Each node owns the quad of its four cells' vertices: the top faces (z = slab top + a
// polishing roughness) and the bottom faces (z = slab bottom); every grid edge between unlike
// nodes gives a wall quad from its top edge to its bottom edge with the two media on its sides.
// Faces with the same medium on both sides are not made; the grid's outer ring is mounting medium,
// so the slab ends in walls at the window's edge.
//
// Inclined boundaries: the bottom vertices are the top vertices moved by a smooth reproducible
// field (a function of section position only) of RMS length thickness·tan(inclination), with
// wavelengths of 400–900 µm, so that boundaries lean by ~25° and the slab does not fold.
// Cleavage cracks (mounting medium) lean as their cleavage plane does (CleavageCracks::
// plane_normal), blended into the field over a distance that keeps the slope of the blend < 1
// and box-filtered where cracks of different planes meet (their leans cannot both be followed).
// Cracks are made at least one grid step wide. The top's boundary vertices get two smoothing
// steps (the bottom keeps the raw ones: a thin smoothed quad could turn over under the lean).
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>

#include "core/microscope/scene.h"
#include "core/microscope/section_map.h"
#include "core/specimen/specimen_scene.h"

namespace pmsim {

struct SectionSlabOptions {
  glm::dvec2 centre_mm{0.0};  // window centre (section coordinates)
  double half_width_mm = 0.5;  // the window is the square centre ± half_width
  double spacing_um = 2.0;     // grid spacing h
  double thickness_um = 30.0;  // the slab
  double film_um = 3.0;        // mounting medium under and over the slab
  double inclination_deg = 25.0;   // RMS lean of grain boundaries (0: vertical walls)
  double roughness_um = 0.15;      // RMS of the polishing relief of the top surface, 8–20 µm wavelengths (0: flat)
  std::uint64_t seed = 0x5eedu;
};

// At most this many grid nodes a side: ~1.4 M triangles for a window full of grains.
constexpr int kMaxSlabNodes = 600;

// Which slab medium each domain of `map` becomes: kFirstFragment + k for the k-th domain (in
// domain order) with a crystal, kSpecimenLiquid (the mounting medium) for the slide, the cracks,
// domains without a crystal and an opaque domain.
std::vector<int> section_slab_media(const SectionMap& map);
// What the slab's grid node at section point p_mm stands for: its domain (SectionMap::
// kMediumDomain on a crack, cracks widened to at least spacing_um), and the crack's grain and
// family (−1 off cracks). The slab's media are section_slab_media of these domains.
struct SlabNode {
  int domain = SectionMap::kSlideDomain;
  int crack_grain = -1, crack_family = -1;
};
SlabNode section_slab_node(const SectionMap& map, const glm::dvec2& p_mm, double spacing_um);

// Builds the slab. Domains 0 (beyond the section) and 1 (cracks) are the mounting medium
// `medium`; every other domain with a crystal is one medium (its crystal and indicatrix axes in
// the section frame); domains without a crystal are mounting medium.
std::unique_ptr<SpecimenScene> build_section_slab(const std::shared_ptr<const SectionMap>& map,
                                                  const IsotropicMedium& medium, const SectionSlabOptions& options);

// The mounting medium of a section scene: sample.medium, its n_D moved to sample.medium_index when set.
IsotropicMedium section_mounting_medium(const Scene& scene);
// The window around the field of view of `scene` (every stage angle; a margin for the light cone)
// and the grid spacing for its magnification (about a pixel, ≤ kMaxSlabNodes nodes a side).
SectionSlabOptions section_slab_options(const Scene& scene);
// The slab of a section scene, built once per (section, window, spacing, thickness, medium) and
// cached, so that a change of polarizer, focus or aperture reuses it.
std::shared_ptr<const SpecimenScene> section_slab(const Scene& scene);

}  // namespace pmsim
