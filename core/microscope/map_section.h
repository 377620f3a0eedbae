#pragma once
// An EBSD orientation map (.ctf, .ang: core/ebsd/) as a thin section (issue 13).
//
// Section coordinates (mm): the origin at the map's centre, x along the map's x, y against the
// map's y (north up: the first row at the top), scaled by the step size
// (core/ebsd/ebsd_frames.h section_position_mm). Each point owns its step rectangle
// (DomainRaster); beyond them the slide.
//
// Phases become library minerals by name (core/ebsd/phase_names.h; sample.phases maps them
// explicitly): "none" shows the mounting medium, "isotropic" an isotropic grain. Non-indexed
// points show the mounting medium or, with sample.nonindexed=black, nothing.
//
// What is evaluated: the map's grains (reconstructed by misorientation, core/ebsd/
// grain_reconstruction.h) are the section's grains, and each grain's orientation clusters its
// zones, one optical domain each. Every point keeps its own orientation to within the cluster
// tolerance kClusterToleranceDeg, chosen from the errors it allows:
//   extinction: a domain turned δ from a point's true orientation leaks sin²(2δ) of the grain's
//     brightest intensity at the point's extinction position; δ = 0.5° leaks 3·10⁻⁴, under
//     1 L* unit (L* = 903.3·Y below Y = 0.0089, CIE 15:2004), below the render's 0.5 ΔE2000
//     tolerance for all but the brightest grains (about 0.3 L*);
//   retardation: Γ = t·Δn′ changes by at most t·(nₘₐₓ − nₘᵢₙ)·δ when the section tilts the
//     indicatrix by δ (dΔn′/dθ ≤ Δn), 1 % of the highest retardation at δ = 0.5° (0.3 nm of a
//     quartz grain's 270 nm);
//   and 0.5° is the angular precision of EBSD orientations themselves (Humphreys 2001, J. Mater.
//     Sci. 36, 3833–3854: relative misorientations to about 0.5°), so finer clusters would
//     resolve the measurement's noise, not the rock.
// Optically isotropic phases (cubic minerals, "isotropic") are one domain per grain whatever the
// orientations.
#include <map>
#include <memory>
#include <string>

#include "core/ebsd/grain_reconstruction.h"
#include "core/ebsd/orientation_map.h"
#include "core/microscope/scene.h"
#include "core/microscope/section_map.h"

namespace pmsim {

constexpr double kClusterToleranceDeg = 0.5;
constexpr double kGrainBoundaryDeg = 10.0;  // MTEX calcGrains' default (grain_reconstruction.h)

// What a map section holds, for reports and native-resolution rendering.
struct MapSectionFacts {
  std::size_t points = 0, indexed = 0;
  std::size_t grains = 0, clusters = 0, domains = 0;
  int columns = 0, rows = 0;  // columns: of the widest row
  double step_x_um = 0.0, step_y_um = 0.0;
  std::string vendor;
  std::vector<std::string> warnings;  // the reader's (truncated file, …)
};

// Builds the section. `phases`: sample.phases; `file`: what error messages name for phase
// mapping (the scene, or the map when no scene). Throws InputError (key sample.phases) for a
// phase of the map's points that maps to no mineral.
SectionMap section_from_orientation_map(const OrientationMap& map, const std::map<std::string, std::string>& phases,
                                        NonIndexed nonindexed, const std::string& file,
                                        MapSectionFacts* facts = nullptr);

// Reads and builds once per (path, phases, nonindexed); throws InputError for a bad map file or
// phase mapping.
std::shared_ptr<const SectionMap> load_map_section(const std::string& path,
                                                   const std::map<std::string, std::string>& phases,
                                                   NonIndexed nonindexed);
// The facts of a map section load_map_section built (null for any other section).
const MapSectionFacts* map_section_facts(const SectionMap& section);
// What an EBSD map became, for a model report: "EBSD map: N points (M indexed), G grains
// (boundaries > 10°), C orientation clusters (within 0.5°): D optical domains" — the same words
// whichever renderer (flat or traced slab) shows the map.
std::string map_section_summary(const MapSectionFacts& facts);

// The section a scene's sample.section names: an EBSD map (by its .ctf/.ang extension) or a
// thin-section file (load_section).
std::shared_ptr<const SectionMap> load_scene_section(const Scene& scene);

}  // namespace pmsim
