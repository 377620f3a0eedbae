#include "core/specimen/grain_mount_truth.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "core/microscope/view_geometry.h"
#include "core/specimen/becke_probe.h"
#include "core/specimen/probe_point.h"

namespace pmsim {

std::vector<std::uint16_t> fragment_label_image(const SpecimenScene& mount, const Scene& scene) {
  if (mount.fragment_count() > std::numeric_limits<std::uint16_t>::max() - 1u)
    throw std::invalid_argument("grain mount of " + std::to_string(mount.fragment_count()) +
                                " fragments: labels are 16-bit");
  const int w = scene.render.width, h = scene.render.height;
  std::vector<std::uint16_t> labels(std::size_t(w) * std::size_t(h), 0);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      // The pixel centre, where the renderer's map puts the pixel (probe_point.h).
      const ProbePoint p = probe_point(scene, (x + 0.5) / w, (y + 0.5) / h);
      const int f = mount.fragment_under(p.specimen_um.x, p.specimen_um.y);
      labels[std::size_t(y) * std::size_t(w) + std::size_t(x)] = std::uint16_t(f + 1);
    }
  });
  return labels;
}

std::vector<FragmentTruth> fragment_truths(const SpecimenScene& mount, const Scene& scene,
                                           const std::vector<std::uint16_t>& labels) {
  std::vector<long long> area(mount.fragment_count() + 1, 0);
  for (std::uint16_t l : labels)
    if (l < area.size()) ++area[l];
  // The polarizer's vibration in the stage frame is the same at every pixel (probe_point.h).
  const glm::dvec3 vibration = probe_point(scene, 0.5, 0.5).vibration;
  const std::string mineral = scene.sample.crystal ? "crystal" : scene.sample.mineral;
  std::vector<FragmentTruth> out;
  for (std::size_t k = 1; k < area.size(); ++k) {
    if (area[k] == 0) continue;
    FragmentTruth t;
    t.label = int(k);
    t.mineral = mineral;
    t.area_px = area[k];
    t.optic_axes = mount.orientation_of(kFirstFragment + int(k) - 1);
    const FragmentOptics f = fragment_optics(mount, int(k) - 1, vibration);
    t.n_polarizer = f.n_vibration;
    t.n_fast = f.n_fast;
    t.n_slow = f.n_slow;
    t.liquid_n_d = f.liquid_n;
    t.relief_vs_medium = f.relief == 0 ? "matched" : f.relief > 0 ? "higher" : "lower";
    out.push_back(std::move(t));
  }
  return out;
}

nlohmann::json grain_mount_report_json(const Scene& scene, const std::vector<FragmentTruth>& fragments,
                                       double liquid_n_d) {
  const auto column = [](const glm::dmat3& m, int c) { return nlohmann::json{m[c].x, m[c].y, m[c].z}; };
  nlohmann::json grains = nlohmann::json::array();
  for (const FragmentTruth& f : fragments)
    grains.push_back({{"id", f.label},
                      {"mineral", f.mineral},
                      {"area_px", f.area_px},
                      {"optic_axes", {{"X", column(f.optic_axes, 0)},
                                      {"Y", column(f.optic_axes, 1)},
                                      {"Z", column(f.optic_axes, 2)}}},
                      {"n_polarizer", f.n_polarizer},
                      {"n_fast", f.n_fast},
                      {"n_slow", f.n_slow},
                      {"relief_vs_medium", f.relief_vs_medium}});
  return {{"sample", "grains"},
          {"mineral", scene.sample.crystal ? "crystal" : scene.sample.mineral},
          {"liquid_n_d", liquid_n_d},
          {"stage_deg", scene.stage_deg},
          {"polarizer_deg", scene.polarizer_deg},
          {"mm_per_pixel", mm_per_pixel(scene, scene.render.width, scene.render.height)},
          {"index_wavelength_nm", kBeckeWavelengthNm},
          {"grains", std::move(grains)}};
}

}  // namespace pmsim
