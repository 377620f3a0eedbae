#pragma once
// The ground truth an exercise's reveal layer draws over the field once the student has checked
// (issue 23): which grain lies where, its mineral, its outline, its vibration directions, its
// cleavage traces and its indicatrix section, all at the scene's current stage angle and position
// (so the layer turns and moves with the stage). Everything comes from core: the label image the
// renderer's map gives (grain_labels.h, grain_mount_truth.h), the grain reports (grain_report.h)
// and the section's indicatrix (section_optics.h); for a crystal plate (a conoscopic figure, no
// grains) the figure's summary (figure_info.h).
//
// Positions are image fractions of the rendered field: x to the right, y down, (0, 0) the top left
// corner of the render.width × render.height image, (0.5, 0.5) the crosshair. Angles are image
// angles counter-clockwise from image +x in [0°, 180°), as GrainReport gives them.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/microscope/scene.h"

namespace pmsim {

// The grain-label image is computed at this many pixels across, whatever render.width: outlines
// stay sharp on a small or coarse render, and the cost stays small (65 536 lookups).
constexpr int kRevealResolution = 256;

struct RevealGrain {
  int label = 0;            // as pmsim-render --labels numbers it (a fragment: its label)
  std::string mineral;      // as the section file names it ("plagioclase:An24")
  long long area_px = 0;    // pixels of the label image (at kRevealResolution across)
  std::array<double, 2> centroid{0.5, 0.5};  // image fractions
  std::optional<double> slow_vibration_deg;  // n′γ; the fast one (n′α) is ⟂; empty: circular section
  std::vector<double> cleavage_traces_deg;
  // The indicatrix section normal to the microscope axis at 589.3 nm: its two radii.
  double n_slow = 0.0, n_fast = 0.0;
  std::string relief_vs_medium;  // grain mounts: "higher", "lower", "matched"
};

// A piece of a boundary between two labels (grains, or a grain and the medium), along pixel edges
// of the label image, in image fractions; collinear neighbours are merged.
struct RevealSegment {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct RevealGeometry {
  int width = 0, height = 0;           // of the label image
  std::vector<RevealGrain> grains;     // every grain with a pixel in the field, ascending label
  std::vector<RevealSegment> outlines;
  std::string figure;  // a crystal plate or a conoscopic view: what the figure is (no grains)
};

// The reveal layer's geometry of `scene` (a thin section or grain mount in orthoscopic view: grains
// and outlines; otherwise the figure's summary). Throws what loading the section throws.
RevealGeometry reveal_geometry(const Scene& scene, int resolution = kRevealResolution);

// Where a section point (mm, section coordinates) appears in the field, as image fractions (the
// inverse of section_point_from_pixel); orthoscopic view.
std::array<double, 2> image_fraction_of_section_point(const Scene& scene, double x_mm, double y_mm);

// The segments of the boundaries of a label image (w × h, top row first), merged along rows and
// columns, in image fractions.
std::vector<RevealSegment> label_outlines(const std::vector<std::uint16_t>& labels, int width, int height);

}  // namespace pmsim
