#include "core/exercise/reveal_geometry.h"

#include <cmath>
#include <cstdint>

#include <glm/mat2x2.hpp>
#include <glm/matrix.hpp>

#include "core/base/units.h"
#include "core/crystal/crystal.h"
#include "core/crystal/section_optics.h"
#include "core/microscope/figure_info.h"
#include "core/microscope/grain_labels.h"
#include "core/microscope/grain_report.h"
#include "core/microscope/map_section.h"
#include "core/microscope/view_geometry.h"
#include "core/specimen/grain_mount_render.h"
#include "core/specimen/grain_mount_truth.h"

namespace pmsim {

namespace {

constexpr glm::dvec3 kAxis{0.0, 0.0, 1.0};

// The scene at the label image's size: the same field of view (it depends on the optics, not on
// the pixel count), `resolution` pixels across.
Scene at_resolution(const Scene& scene, int resolution) {
  Scene s = scene;
  s.render.width = resolution;
  s.render.height = std::max(1, static_cast<int>(std::lround(double(resolution) * scene.render.height /
                                                             std::max(1, scene.render.width))));
  return s;
}

// Pixel count and centroid (image fractions) of every label.
void add_centroids(const std::vector<std::uint16_t>& labels, int w, int h, std::vector<RevealGrain>& grains) {
  std::vector<double> n(65536, 0.0), sx(65536, 0.0), sy(65536, 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::uint16_t l = labels[std::size_t(y) * std::size_t(w) + std::size_t(x)];
      n[l] += 1, sx[l] += x + 0.5, sy[l] += y + 0.5;
    }
  for (RevealGrain& g : grains) {
    const std::size_t l = std::size_t(g.label);
    g.area_px = static_cast<long long>(n[l]);
    if (n[l] > 0) g.centroid = {sx[l] / n[l] / w, sy[l] / n[l] / h};
  }
}

// Cleavage cracks and the gaps of a grain's twin lamellae are mounting medium (label 0) inside a
// grain: a patch of medium of at most `max_pixels` whose every neighbour is one grain becomes that
// grain, so that the outlines are the grains' and not each crack's (a crack reaching the grain's
// edge stays: it touches the neighbour too).
void fill_enclosed_medium(std::vector<std::uint16_t>& labels, int w, int h, std::size_t max_pixels) {
  std::vector<char> seen(labels.size(), 0);
  std::vector<std::size_t> patch, stack;
  for (std::size_t start = 0; start < labels.size(); ++start) {
    if (labels[start] != 0 || seen[start]) continue;
    patch.clear();
    stack.assign(1, start);
    seen[start] = 1;
    int neighbour = -1;  // the one grain around the patch; -2: more than one, or the image edge
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      patch.push_back(i);
      const int x = int(i % std::size_t(w)), y = int(i / std::size_t(w));
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k) {
        if (nx[k] < 0 || ny[k] < 0 || nx[k] >= w || ny[k] >= h) {
          neighbour = -2;
          continue;
        }
        const std::size_t j = std::size_t(ny[k]) * std::size_t(w) + std::size_t(nx[k]);
        if (labels[j] == 0) {
          if (!seen[j]) seen[j] = 1, stack.push_back(j);
        } else if (neighbour == -1) {
          neighbour = labels[j];
        } else if (neighbour != labels[j]) {
          neighbour = -2;
        }
      }
    }
    if (neighbour > 0 && patch.size() <= max_pixels)
      for (std::size_t i : patch) labels[i] = std::uint16_t(neighbour);
  }
}

void section_grains(const Scene& s, RevealGeometry& out) {
  const std::shared_ptr<const SectionMap> section = load_scene_section(s);
  std::vector<std::uint16_t> labels = grain_label_image(s, *section);
  fill_enclosed_medium(labels, s.render.width, s.render.height,
                       std::size_t(s.render.width) * std::size_t(s.render.height) / 400);
  for (const GrainReport& r : report_grains(s, *section, labels)) {
    RevealGrain g;
    g.label = r.id;
    g.mineral = r.mineral;
    g.slow_vibration_deg = r.slow_vibration_deg;
    g.cleavage_traces_deg = r.cleavage_traces_deg;
    const SectionGrain& sg = section->grain_by_label(r.id);
    if (sg.crystal) {
      const SectionOptics o =
          section_optics(sg.orientation, sg.crystal->principal_indices(kGrainReportIndexWavelengthNm), kAxis);
      g.n_slow = o.n_slow, g.n_fast = o.n_fast;
    }
    out.grains.push_back(std::move(g));
  }
  add_centroids(labels, s.render.width, s.render.height, out.grains);
  out.outlines = label_outlines(labels, s.render.width, s.render.height);
}

void mount_grains(const Scene& s, RevealGeometry& out) {
  const std::shared_ptr<const SpecimenScene> mount = grain_mount_specimen_cached(s);
  const std::vector<std::uint16_t> labels = fragment_label_image(*mount, s);
  for (const FragmentTruth& f : fragment_truths(*mount, s, labels)) {
    RevealGrain g;
    g.label = f.label;
    g.mineral = f.mineral;
    g.n_slow = f.n_slow, g.n_fast = f.n_fast;
    g.relief_vs_medium = f.relief_vs_medium;
    // The fragment's optic axes are in the stage frame, as a section grain's orientation is in the
    // section frame: the image angle is the stage-frame angle + the stage angle.
    if (const Crystal* c = mount->crystal_of(kFirstFragment + f.label - 1)) {
      const SectionOptics o = section_optics(f.optic_axes, c->principal_indices(kGrainReportIndexWavelengthNm), kAxis);
      if (!o.circular) g.slow_vibration_deg = line_direction_deg(degrees(std::atan2(o.slow.y, o.slow.x)) + s.stage_deg);
    }
    out.grains.push_back(std::move(g));
  }
  add_centroids(labels, s.render.width, s.render.height, out.grains);
  out.outlines = label_outlines(labels, s.render.width, s.render.height);
}

}  // namespace

std::vector<RevealSegment> label_outlines(const std::vector<std::uint16_t>& labels, int w, int h) {
  std::vector<RevealSegment> out;
  auto at = [&](int x, int y) { return labels[std::size_t(y) * std::size_t(w) + std::size_t(x)]; };
  // Vertical edges between columns x − 1 and x, merged down each column.
  for (int x = 1; x < w; ++x)
    for (int y = 0; y < h;) {
      if (at(x - 1, y) == at(x, y)) {
        ++y;
        continue;
      }
      const int y0 = y;
      while (y < h && at(x - 1, y) != at(x, y)) ++y;
      out.push_back({double(x) / w, double(y0) / h, double(x) / w, double(y) / h});
    }
  // Horizontal edges between rows y − 1 and y, merged along each row.
  for (int y = 1; y < h; ++y)
    for (int x = 0; x < w;) {
      if (at(x, y - 1) == at(x, y)) {
        ++x;
        continue;
      }
      const int x0 = x;
      while (x < w && at(x, y - 1) != at(x, y)) ++x;
      out.push_back({double(x0) / w, double(y) / h, double(x) / w, double(y) / h});
    }
  return out;
}

std::array<double, 2> image_fraction_of_section_point(const Scene& scene, double x_mm, double y_mm) {
  // section_point_from_pixel is affine in the pixel position: invert it from three points.
  const int w = std::max(1, scene.render.width), h = std::max(1, scene.render.height);
  const glm::dvec2 o = section_point_from_pixel(scene, w, h, 0.0, 0.0);
  const glm::dvec2 ex = section_point_from_pixel(scene, w, h, double(w), 0.0) - o;
  const glm::dvec2 ey = section_point_from_pixel(scene, w, h, 0.0, double(h)) - o;
  const glm::dvec2 f = glm::inverse(glm::dmat2(ex, ey)) * (glm::dvec2(x_mm, y_mm) - o);
  return {f.x, f.y};
}

RevealGeometry reveal_geometry(const Scene& scene, int resolution) {
  RevealGeometry out;
  const bool ortho = scene.mode == ViewMode::Ortho && !scene.bertrand_in;
  const bool grains = scene.sample_in && (scene.sample.type == SampleType::Section || scene.sample.type == SampleType::Grains);
  if (!ortho || !grains) {
    out.figure = describe_figure(scene).summary;
    return out;
  }
  const Scene s = at_resolution(scene, resolution);
  out.width = s.render.width;
  out.height = s.render.height;
  if (s.sample.type == SampleType::Section)
    section_grains(s, out);
  else
    mount_grains(s, out);
  return out;
}

}  // namespace pmsim
