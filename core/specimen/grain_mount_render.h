#pragma once
// A microscope scene with sample.type = grains rendered in plane-polarized light (analyzer out) or
// between polars (analyzer in, at analyzer_deg: interference colours): fragments of
// sample.mineral (or sample.crystal) scattered over the slide in the liquid of n_D
// sample.medium_index, seen through the scene's objective at focus_um with the condenser's
// aperture diaphragm condenser.aperture_na (core/specimen/plane_light_image.h).
#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/microscope/scene.h"
#include "core/render/render_image.h"
#include "core/specimen/plane_light_image.h"
#include "core/specimen/specimen_scene.h"

namespace pmsim {

// n_D of the liquid when sample.medium_index is not set: that of the usual mounting media.
constexpr double kDefaultGrainMountIndex = 1.54;

// The good (perfect, very good, good) cleavages of a library mineral as unit normals in its
// indicatrix frame (what ScatterOptions::cleavage_normals takes); empty without lattice data.
std::vector<glm::dvec3> good_cleavage_normals(const std::string& mineral);
// The mount on the slide: a fixed 4 mm × 4 mm spread of fragments (the same slide whatever the
// mineral or liquid; the stage moves and turns it), in the liquid the scene names.
std::unique_ptr<SpecimenScene> grain_mount_specimen(const Scene& scene);
// The view: field of view, stage, focus, apertures, polarizer, analyzer, illuminant and samples of `scene`
// (render.spp; 0: 64 samples a pixel).
PlaneLightOptions plane_light_options(const Scene& scene);
// The mount a grain-mount scene traces (render_traced_response): the last one built is kept, by
// mineral and liquid; a crystal given by its indices is rebuilt every time.
std::shared_ptr<const SpecimenScene> grain_mount_specimen_cached(const Scene& scene);

}  // namespace pmsim
