#pragma once
// A thin section as a map of grains (assets/sections/*.json). Each grain owns the points of the
// field nearest to its seed under its own anisotropic metric (an elongated Voronoi cell, so that
// plagioclase laths look like laths); a twinned grain alternates lamellae of two orientations
// related by a 180° rotation about the twin axis (albite law: the normal of the (010) composition
// plane, whose trace is the lamella direction). Field coordinates: x east, y north, the shorter
// image side spans −1…1; seeds may lie outside so that a turned stage still shows grains.
#include <memory>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>

#include "core/crystal/crystal.h"

namespace pmsim {

struct SectionGrain {
  std::string mineral;
  const Crystal* crystal = nullptr;
  glm::dmat3 orientation{1.0};  // columns: crystal X, Y, Z in the sample frame
  glm::dvec2 seed{0.0};
  double elongation = 1.0;      // cell length / width
  double elongation_rad = 0.0;  // direction of the long side
  double weight = 1.0;          // larger: bigger cell
  bool twinned = false;
  std::string twin_law;              // "albite", … (empty when untwinned)
  double twin_trace_rad = 0.0;       // direction of the lamella traces
  double twin_width = 0.05;          // lamella width (field units)
  glm::dmat3 twin_orientation{1.0};  // orientation of the odd lamellae
  // Derived once at load (the map lookup runs per sub-pixel).
  double cos_elong = 1.0, sin_elong = 0.0;
  glm::dvec2 twin_normal{0.0, 1.0};
};

class SectionMap {
 public:
  std::string name, source, path;
  double thickness_um = 30.0;
  std::vector<SectionGrain> grains;
  // The section's extent (centred on the origin, mm); beyond it the field shows the slide.
  double width_mm = 4.0, height_mm = 4.0;

  // Ground-truth label of a domain: 0 for the mounting medium or the slide, k ≥ 1 for grain k
  // (grains[k − 1]: file order, so the same k in every render of the same section).
  int grain_label(int domain) const { return domain / 2 + 1; }
  const SectionGrain& grain_by_label(int k) const { return grains[k - 1]; }

  // Optical domain under a sample-frame point: 2·grain + (1 for an odd twin lamella).
  int domain_at(const glm::dvec2& p) const;
  int domain_count() const { return 2 * static_cast<int>(grains.size()); }
  const SectionGrain& grain_of_domain(int d) const { return grains[d / 2]; }
  const glm::dmat3& orientation_of_domain(int d) const {
    const SectionGrain& g = grains[d / 2];
    return (d & 1) ? g.twin_orientation : g.orientation;
  }
  // Builds the lookup grid domain_at uses (load_section calls it; a map whose grains changed
  // since falls back to testing every grain). Same results as the exhaustive search.
  void build_index();

 private:
  int nearest_grain(const glm::dvec2& p) const;
  // Grid over [−kIndexHalf, kIndexHalf]² with, per cell, the grains that can be nearest there.
  static constexpr int kIndexCells = 64;
  static constexpr double kIndexHalf = 2.0;
  std::vector<int> cell_start_, cell_grains_;
  std::size_t indexed_grains_ = 0;
};

// Loads (once, cached by resolved path) a section file; throws InputError naming file, key and
// value on bad content or an unknown mineral.
std::shared_ptr<const SectionMap> load_section(const std::string& name_or_path);

}  // namespace pmsim
