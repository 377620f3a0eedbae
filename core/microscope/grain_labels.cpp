#include "core/microscope/grain_labels.h"

#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "core/microscope/view_geometry.h"

namespace pmsim {

std::vector<std::uint16_t> grain_label_image(const Scene& scene, const SectionMap& section) {
  if (section.grains.size() > 65535)
    throw std::invalid_argument("section '" + section.name + "' has " +
                                std::to_string(section.grains.size()) +
                                " grains: labels of more than 65535 do not fit a 16-bit image");
  const int W = scene.render.width, H = scene.render.height;
  std::vector<std::uint16_t> labels(static_cast<std::size_t>(W) * H, 0);
  const FieldToSection to_section(scene);
  const auto label_at = [&](const glm::dvec2& p) {
    return static_cast<std::uint16_t>(section.grain_label(section.domain_at(p)));
  };
  if (scene.bertrand_in) {
    // As pixel_view's conoscopic figure (lit where bfp_direction is) and parallel-light spot
    // (within kParallelBeamSinTheta / NA of the centre).
    const std::uint16_t k = label_at(to_section({0.0, 0.0}));
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const glm::dvec2 f = field_from_pixel(W, H, x + 0.5, y + 0.5);
        const double rho = std::hypot(f.x, f.y);
        const bool lit = scene.mode == ViewMode::Cono ? bfp_lit(scene, rho)
                                                      : rho <= kParallelBeamSinTheta / scene.objective.na;
        if (lit) labels[static_cast<std::size_t>(y) * W + x] = k;
      }
    return labels;
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, H, 8), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y)
      for (int x = 0; x < W; ++x)
        labels[static_cast<std::size_t>(y) * W + x] =
            label_at(to_section(field_from_pixel(W, H, x + 0.5, y + 0.5)));
  });
  return labels;
}

std::vector<long long> label_counts(const std::vector<std::uint16_t>& labels, const SectionMap& section) {
  std::vector<long long> n(section.grains.size() + 1, 0);
  for (const std::uint16_t k : labels)
    if (k < n.size()) ++n[k];
  return n;
}

}  // namespace pmsim
