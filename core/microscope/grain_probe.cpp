#include "core/microscope/grain_probe.h"

#include "core/microscope/map_section.h"
#include "core/microscope/section_map.h"
#include "core/microscope/view_geometry.h"

namespace pmsim {

std::optional<GrainReport> grain_at_image_point(const Scene& scene, double x_frac, double y_frac) {
  if (!scene.sample_in || scene.sample.type != SampleType::Section || scene.mode != ViewMode::Ortho ||
      scene.bertrand_in)
    return std::nullopt;
  const auto map = load_scene_section(scene);
  const int w = scene.render.width, h = scene.render.height;
  const glm::dvec2 p = section_point_from_pixel(scene, w, h, x_frac * w, y_frac * h);
  const int label = map->grain_label(map->domain_at(p));
  if (label < 1) return std::nullopt;
  return report_grain(scene, *map, label);
}

}  // namespace pmsim
