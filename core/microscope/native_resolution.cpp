#include "core/microscope/native_resolution.h"

#include <algorithm>
#include <cmath>

#include "core/ebsd/read_orientation_map.h"
#include "core/microscope/map_section.h"

namespace pmsim {

Scene native_resolution_scene(const Scene& scene) {
  if (!scene.render.native || !scene.sample_in || scene.sample.type != SampleType::Section ||
      !is_orientation_map_path(scene.sample.section))
    return scene;
  const auto section = load_scene_section(scene);
  const MapSectionFacts* f = map_section_facts(*section);
  if (!f || f->columns < 1 || f->rows < 1) return scene;
  Scene s = scene;
  s.render.width = f->columns;
  s.render.height = std::max(1, static_cast<int>(std::lround(f->rows * f->step_y_um / f->step_x_um)));
  s.eyepiece.field_number_mm =
      f->step_x_um * 1e-3 * std::min(s.render.width, s.render.height) * s.objective.magnification;
  return s;
}

}  // namespace pmsim
