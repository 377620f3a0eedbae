#pragma once
// The optical domains of a scene's specimen: the regions of one crystal, orientation and thickness
// that the evaluation treats as one plate — the plate or wedge on the stage, every zone and twin
// individual of a thin section's grains with its slide and mounting medium (section_map.h), or
// the empty stage (one domain without a crystal).
#include <memory>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>

#include "core/crystal/crystal.h"
#include "core/microscope/scene.h"
#include "core/microscope/section_map.h"

namespace pmsim {

struct OpticalDomain {
  const Crystal* crystal = nullptr;  // nullptr: nothing on the stage (or an isotropic layer)
  glm::dmat3 crystal_to_lab{1.0};    // stage rotation applied
  double thickness_um = 0.0;
  std::string mineral;
  bool opaque = false;  // passes no light (an EBSD map's non-indexed points with sample.nonindexed=black)
};

struct OpticalDomains {
  std::vector<OpticalDomain> domains;
  std::shared_ptr<Crystal> custom_crystal;    // sample.crystal, owned here (a domain points to it)
  std::shared_ptr<const SectionMap> section;  // the grain map of a thin section on the stage; else null

  bool opaque(int domain) const { return domains[domain].opaque; }

  // The domain a sample-frame point shows: 0 but on a thin section.
  int domain_at_sample(const glm::dvec2& sample_point) const {
    return section ? section->domain_at(sample_point) : 0;
  }
};

// Throws InputError for an unknown mineral or a bad section file (as the scene check reports).
OpticalDomains optical_domains(const Scene& scene);

}  // namespace pmsim
