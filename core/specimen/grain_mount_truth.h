#pragma once
// Ground truth of a grain-mount image, as pmsim-render --labels / --grains give it for thin
// sections (core/microscope/grain_labels.h): the fragment under every pixel centre, and for each
// fragment in the image what a student measures on it — its mineral, its optical orientation,
// the index n′ it offers to light vibrating along the polarizer and its relief against the
// liquid (the Becke-line test), and its two vibration indices for vertical light. The numbers come
// from the SpecimenScene the renderer traces (grain_mount_specimen), through the probe's map of
// image to specimen (core/specimen/probe_point.h).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <nlohmann/json.hpp>

#include "core/microscope/scene.h"
#include "core/specimen/specimen_scene.h"

namespace pmsim {

// render.width × render.height labels, top row first: 0 over liquid, k ≥ 1 for fragment k − 1
// of the mount (the same k in every render of the same mount). Orthoscopic view only; throws
// std::invalid_argument for a mount of more than 65535 fragments.
std::vector<std::uint16_t> fragment_label_image(const SpecimenScene& mount, const Scene& scene);

struct FragmentTruth {
  int label = 0;               // as in the label image
  std::string mineral;         // sample.mineral, or "crystal" for sample.crystal
  long long area_px = 0;       // pixels labelled with it
  glm::dmat3 optic_axes{1.0};  // columns: indicatrix X (n_α), Y (n_β), Z (n_γ) in the stage frame
  double n_polarizer = 0.0;    // n′ along the polarizer at 589.26 nm (the radius of the indicatrix)
  double n_fast = 0.0, n_slow = 0.0;  // the two vibrations of vertical light, 589.26 nm
  double liquid_n_d = 0.0;
  // The Becke line: "higher" (n′ > n_D, the line moves into the fragment on focusing up),
  // "lower", or "matched" (|n′ − n_D| < kBeckeMatch).
  std::string relief_vs_medium;
};

// Every fragment with at least one pixel in `labels`, by label.
std::vector<FragmentTruth> fragment_truths(const SpecimenScene& mount, const Scene& scene,
                                           const std::vector<std::uint16_t>& labels);

// pmsim-render --grains for sample.type=grains:
//   {"sample": "grains", "mineral", "liquid_n_d", "stage_deg", "polarizer_deg", "mm_per_pixel",
//    "index_wavelength_nm": 589.26,
//    "grains": [{"id", "mineral", "area_px", "optic_axes": {"X": [x, y, z], "Y": …, "Z": …},
//                "n_polarizer", "n_fast", "n_slow", "relief_vs_medium"}, …]}
// Directions are unit vectors in the stage frame (x right, y up, z toward the objective at stage
// angle 0; core/base/conventions.h).
nlohmann::json grain_mount_report_json(const Scene& scene, const std::vector<FragmentTruth>& fragments,
                                       double liquid_n_d);

}  // namespace pmsim
