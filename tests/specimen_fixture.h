#pragma once
// One fragment in a liquid, seen in monochromatic plane light: the specimen tests' common setup,
// with the fragment's true outline (fragment_under at pixel centres) and bands along it.
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "core/crystal/crystal.h"
#include "core/materials/medium.h"
#include "core/specimen/plane_light_image.h"
#include "core/specimen/specimen_scene.h"

namespace specimen_test {

struct OneFragment {
  double n_fragment = 1.60;   // isotropic index (no dispersion)
  double n_liquid = 1.54;     // liquid n_D (no dispersion unless liquid_dispersion is set)
  double liquid_dispersion = 0.0;
  double size_um = 100.0;
  glm::dmat3 orientation{1.0};
  std::optional<pmsim::Crystal> crystal;  // replaces n_fragment
};

inline std::unique_ptr<pmsim::SpecimenScene> make_specimen(const OneFragment& f) {
  pmsim::FragmentShape shape;
  shape.size_um = f.size_um;
  shape.elongation = 1.0;
  shape.roughness = 0.0;
  shape.crystal_to_lab = f.orientation;
  const pmsim::Crystal c = f.crystal ? *f.crystal : pmsim::Crystal::isotropic_constant("test", f.n_fragment);
  return std::make_unique<pmsim::SpecimenScene>(std::vector<pmsim::FragmentShape>{shape}, c,
                                                pmsim::immersion_liquid(f.n_liquid, f.liquid_dispersion),
                                                pmsim::find_medium("N-BK7"), pmsim::find_medium("air"));
}

// 1 µm pixels over 160 µm: the 100 µm fragment and 30 µm of liquid around it.
inline pmsim::PlaneLightOptions mono_view(double focus_um, int spp = 64) {
  pmsim::PlaneLightOptions o;
  o.width = o.height = 160;
  o.um_per_px = 1.0;
  o.focus_um = focus_um;
  o.objective_na = 0.25;
  o.single_wavelength_nm = 589.26;
  o.spp = spp;
  return o;
}

// Signed distance (µm, + inside the fragment) of every pixel centre from the true outline.
inline std::vector<double> signed_distance(const pmsim::SpecimenScene& s, const pmsim::PlaneLightOptions& o) {
  const int w = o.width, h = o.height;
  std::vector<int> inside(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      inside[std::size_t(y) * w + x] =
          s.fragment_under((x + 0.5 - 0.5 * w) * o.um_per_px, (0.5 * h - (y + 0.5)) * o.um_per_px) >= 0;
  std::vector<std::pair<double, double>> edge;  // midpoints between unlike neighbours
  for (int y = 0; y + 1 < h; ++y)
    for (int x = 0; x + 1 < w; ++x) {
      const int a = inside[std::size_t(y) * w + x];
      if (a != inside[std::size_t(y) * w + x + 1]) edge.push_back({x + 1.0, y + 0.5});
      if (a != inside[std::size_t(y + 1) * w + x]) edge.push_back({x + 0.5, y + 1.0});
    }
  std::vector<double> d(std::size_t(w) * h, 1e9);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double m = 1e18;
      for (const auto& [ex, ey] : edge) m = std::min(m, (x + 0.5 - ex) * (x + 0.5 - ex) + (y + 0.5 - ey) * (y + 0.5 - ey));
      const double dist = std::sqrt(m) * o.um_per_px;
      d[std::size_t(y) * w + x] = inside[std::size_t(y) * w + x] ? dist : -dist;
    }
  return d;
}

// Mean relative intensity (Y) of the pixels whose signed distance lies in [lo, hi).
inline double band_mean(const pmsim::RenderImage& img, const std::vector<double>& d, double lo, double hi) {
  double s = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d[i] >= lo && d[i] < hi) {
      s += img.xyz[3 * i + 1];
      ++n;
    }
  return n ? s / n : std::nan("");
}

}  // namespace specimen_test
