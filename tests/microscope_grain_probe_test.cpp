// The grain under an image point is the grain the label image shows there, and its report is the
// one pmsim-render --grains writes.
#include <gtest/gtest.h>

#include "core/microscope/grain_labels.h"
#include "core/microscope/grain_probe.h"
#include "core/microscope/section_map.h"

namespace pmsim {
namespace {

Scene granite_scene() {
  Scene s;
  s.sample.type = SampleType::Section;
  s.sample.section = "granite_hand_placed";
  s.render.width = 64;
  s.render.height = 48;
  s.stage_deg = 30.0;
  s.stage.x_mm = 0.3;
  s.stage.y_mm = -0.2;
  return s;
}

TEST(GrainProbe, AgreesWithTheLabelImageAtEveryPixelCentre) {
  const Scene s = granite_scene();
  const auto map = load_section(s.sample.section);
  const std::vector<std::uint16_t> labels = grain_label_image(s, *map);
  int grains_seen = 0;
  for (int y = 0; y < s.render.height; y += 3)
    for (int x = 0; x < s.render.width; x += 3) {
      const auto g = grain_at_image_point(s, (x + 0.5) / s.render.width, (y + 0.5) / s.render.height);
      const int want = labels[static_cast<std::size_t>(y) * s.render.width + x];
      ASSERT_EQ(g ? g->id : 0, want) << x << "," << y;
      if (g) {
        ++grains_seen;
        EXPECT_EQ(g->mineral, map->grain_by_label(want).mineral);
      }
    }
  EXPECT_GT(grains_seen, 0);
}

TEST(GrainProbe, NothingOutsideAnOrthoscopicSection) {
  Scene s = granite_scene();
  s.mode = ViewMode::Cono;
  s.bertrand_in = true;
  EXPECT_FALSE(grain_at_image_point(s, 0.5, 0.5));
  Scene plate;
  EXPECT_FALSE(grain_at_image_point(plate, 0.5, 0.5));
}

}  // namespace
}  // namespace pmsim
