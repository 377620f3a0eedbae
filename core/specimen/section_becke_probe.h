#pragma once
// What the Becke line does at one point of a thin section (the teaching panel's probe for
// sample.type = section): the nearest boundary between two media of the section slab
// (core/specimen/section_slab.h) — grain against grain (another mineral, or the same one in
// another orientation, zone or twin individual), or grain against the mounting medium at a
// cleavage crack or the section's edge — the medium on each side, the index each offers to light
// vibrating along the polarizer at the D line, and the side the bright Becke line moves into on
// focusing up: the side of the higher index (Nesse 2012, Introduction to Optical Mineralogy, §4
// "Becke line").
//
// Everything comes from what the slab tracer is given: the media are the slab's (section_slab_
// media of section_slab_node, cracks widened to the slab's grid spacing for this view), the
// crystals and orientations the section map's, the mounting medium section_mounting_medium(scene)
// (sample.medium_index moves its n_D), and n' is vibration_index, what SpecimenScene::index
// answers for the slab's media. The image point maps to the section as the traced image's pixels
// do (probe_point).
//
// The boundary is located on the section plane, where the slab's top face follows the map's
// boundaries (to within the slab's grid spacing); the slab's walls lean (~25°), so at the slab's
// mid-plane the boundary can lie up to t/2·tan 25° ≈ 7 µm of a 30 µm slab to either side.
#include <string>

#include <glm/vec2.hpp>

#include "core/microscope/scene.h"
#include "core/microscope/section_map.h"

namespace pmsim {

// One side of the boundary.
struct SectionBeckeSide {
  int domain = SectionMap::kSlideDomain;  // the section map's optical domain (kMediumDomain on a crack)
  int grain = 0;                          // SectionMap::grain_label: 0 for the mounting medium, else k ≥ 1
  std::string mineral;                    // the domain's mineral; empty for the mounting medium
  // Which part of the grain (a boundary inside one grain is between zones or twin individuals):
  // zone index of zone_count (inner to outer), twin individual 0 or 1 (−1: untwinned grain).
  int zone = 0, zone_count = 1, twin = -1;
  double n = 0.0;  // n' along the polarizer at kBeckeWavelengthNm (n_D of the medium)
  bool is_medium() const { return grain == 0; }
};

enum class BeckeMovesInto { Matched, Here, There };

struct SectionBeckeProbe {
  glm::dvec2 point_um{0.0};     // the probed section point (section coordinates × 1000)
  double radius_um = 0.0;       // how far the boundary was looked for
  SectionBeckeSide here;        // the medium under the point
  bool found = false;           // a boundary within radius_um
  SectionBeckeSide there;       // the medium beyond the nearest boundary (when found)
  double distance_um = 0.0;     // from the point to that boundary, in the section plane
  glm::dvec2 boundary_um{0.0};  // the nearest boundary point
  // Focusing up (focus +), the line moves into the side of higher n'; Matched within kBeckeMatch.
  BeckeMovesInto moves_into = BeckeMovesInto::Matched;
};

// The default search radius: a tenth of the field of view (at least 10 µm), the neighbourhood of
// the cursor a student reads as "here" at any magnification — 220 µm at 10×, 22 µm at 100×.
double section_becke_radius_um(const Scene& scene);

// `x`, `y`: fractions of the image from its top left (as the app's probe); the view (stage,
// field, polarizer, mounting medium) is `scene`'s, the section `map` (load_scene_section(scene)).
// radius_um ≤ 0: section_becke_radius_um(scene).
SectionBeckeProbe probe_section_becke_line(const SectionMap& map, const Scene& scene, double x, double y,
                                           double radius_um = 0.0);
// The same for the scene's own section (loaded once, cached).
SectionBeckeProbe probe_section_becke_line(const Scene& scene, double x, double y);

// What one side is called in the panel: "quartz (grain 4)", "plagioclase:An20 (grain 31, twin
// individual 2)", "garnet (grain 2, zone 1 of 3)" or "mounting medium".
std::string section_becke_side_name(const SectionBeckeSide& side);
// One or two sentences for the teaching panel: the boundary, its two sides and what the student
// sees when focusing up and down there.
std::string describe_section_becke_line(const SectionBeckeProbe& probe);

}  // namespace pmsim
