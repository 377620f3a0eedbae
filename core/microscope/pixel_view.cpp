#include "core/microscope/pixel_view.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/parallel_for.h>

#include "core/base/units.h"
#include "core/microscope/view_geometry.h"

namespace pmsim {

namespace {

bool cancelled(const std::atomic<bool>* cancel) { return cancel && *cancel; }

int samples_per_side(int spp) { return std::max(1, static_cast<int>(std::ceil(std::sqrt(spp)))); }

// The refs of one pixel while it is being sampled: a unit met twice adds to its weight.
struct RefBuilder {
  std::vector<PixelRef> tmp;
  void add(int unit, float w) {
    for (PixelRef& r : tmp)
      if (r.unit == unit) {
        r.weight += w;
        return;
      }
    tmp.push_back({unit, w});
  }
};

// The units of the image plane (and of the parallel-light spot, which gathers the field's light):
// one per domain, or one per thickness step of a wedge, and which of them a field point shows.
// Created up front so that the per-pixel passes are read-only and run in parallel.
class FieldUnits {
 public:
  FieldUnits(const Scene& scene, const OpticalDomains& domains)
      : scene_(scene),
        domains_(domains),
        is_wedge_(scene.sample_in && scene.sample.type == SampleType::Wedge),
        wedge_steps_(scene.mode == ViewMode::Cono ? 256
                                                  : 2 * std::max(scene.render.width, scene.render.height)),
        to_sample_(scene.stage_deg),
        to_section_(scene) {}

  std::vector<EvalUnit> units() const {
    std::vector<EvalUnit> out;
    const int n = is_wedge_ ? wedge_steps_ : static_cast<int>(domains_.domains.size());
    for (int i = 0; i < n; ++i) {
      EvalUnit u;
      u.domain = is_wedge_ ? 0 : i;
      u.cone = scene_.mode == ViewMode::Cono;
      u.thickness_um = is_wedge_ ? scene_.sample.thickness_um * i / (wedge_steps_ - 1.0)
                                 : domains_.domains[i].thickness_um;
      out.push_back(u);
    }
    return out;
  }

  // Adds the units field point f (weight w) shows: its domain (a thin section's at the section
  // point in mm), or the two thickness steps of a wedge around it, linearly weighted. Plates and
  // wedges fill the field whatever the magnification.
  void add_field_point(RefBuilder& rb, const glm::dvec2& f, float w) const {
    if (is_wedge_) {
      const glm::dvec2 p = to_sample_(f);
      const double pos = wedge_thickness_um(scene_, p) / scene_.sample.thickness_um * (wedge_steps_ - 1);
      const int i0 = std::min(static_cast<int>(pos), wedge_steps_ - 2);
      const float frac = static_cast<float>(pos - i0);
      rb.add(i0, w * (1 - frac));
      rb.add(i0 + 1, w * frac);
    } else {
      const int d = domains_.domain_at_sample(to_section_(f));
      if (!domains_.opaque(d)) rb.add(d, w);  // an opaque point adds no light: the pixel darkens by its share
    }
  }

 private:
  const Scene& scene_;
  const OpticalDomains& domains_;
  bool is_wedge_;
  int wedge_steps_;
  StageToSample to_sample_;
  FieldToSection to_section_;
};

}  // namespace

std::vector<glm::dvec3> cone_directions(int n, double s_max) {
  std::vector<glm::dvec3> d;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double r = s_max * std::sqrt((i + 0.5) / n), a = i * golden;
    d.push_back({r * std::cos(a), r * std::sin(a), std::sqrt(std::max(0.0, 1.0 - r * r))});
  }
  return d;
}

std::optional<PixelView> conoscopic_figure_view(const Scene& scene, const OpticalDomains& domains,
                                                const std::atomic<bool>* cancel) {
  const int W = scene.render.width, H = scene.render.height;
  PixelView view;
  view.kind = ViewKind::ConoscopicFigure;
  view.pixel_offset.assign(static_cast<std::size_t>(W) * H + 1, 0);
  // The figure of the grain under the crosshair (a section's point at stage.x_mm, stage.y_mm), or
  // of the wedge's thickness at the field centre.
  const int dom = domains.domain_at_sample(FieldToSection(scene)({0.0, 0.0}));
  const bool is_wedge = scene.sample_in && scene.sample.type == SampleType::Wedge;
  const double d = is_wedge ? wedge_thickness_um(scene, sample_from_field({0.0, 0.0}, scene.stage_deg))
                            : domains.domains[dom].thickness_um;
  // Directions per pixel in parallel (rows), then numbered in order.
  std::vector<glm::dvec3> k_px(static_cast<std::size_t>(W) * H);
  std::vector<char> lit_px(k_px.size());
  tbb::parallel_for(tbb::blocked_range<int>(0, H, 16), [&](const tbb::blocked_range<int>& r) {
    if (cancelled(cancel)) return;
    for (int y = r.begin(); y != r.end(); ++y)
      for (int x = 0; x < W; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * W + x;
        lit_px[i] = bfp_direction(scene, field_from_pixel(W, H, x + 0.5, y + 0.5), k_px[i]);
      }
  });
  if (cancelled(cancel)) return std::nullopt;
  const std::size_t n_lit = static_cast<std::size_t>(std::count(lit_px.begin(), lit_px.end(), 1));
  view.units.reserve(n_lit);
  view.refs.reserve(n_lit);
  for (std::size_t i = 0; i < k_px.size(); ++i) {
    view.pixel_offset[i] = static_cast<int>(view.refs.size());
    if (!lit_px[i] || domains.opaque(dom)) continue;  // an opaque point under the crosshair: no figure
    EvalUnit u;
    u.domain = dom;
    u.thickness_um = d;
    u.k_air = k_px[i];
    view.units.push_back(u);
    view.refs.push_back({static_cast<int>(view.units.size()) - 1, 1.0f});
  }
  view.pixel_offset[k_px.size()] = static_cast<int>(view.refs.size());
  return view;
}

PixelView parallel_light_spot_view(const Scene& scene, const OpticalDomains& domains) {
  const int W = scene.render.width, H = scene.render.height;
  const FieldUnits field_units(scene, domains);
  PixelView view;
  view.kind = ViewKind::ParallelLightSpot;
  view.units = field_units.units();
  view.pixel_offset.assign(static_cast<std::size_t>(W) * H + 1, 0);
  // The field's light, sampled on an 8×8 grid, lights every pixel of the spot alike.
  RefBuilder field;
  const int n = 8;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      field_units.add_field_point(field, field_from_pixel(n, n, i + 0.5, j + 0.5), 1.0f / (n * n));
  const double rho_spot = kParallelBeamSinTheta / scene.objective.na;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * W + x;
      view.pixel_offset[i] = static_cast<int>(view.refs.size());
      const glm::dvec2 f = field_from_pixel(W, H, x + 0.5, y + 0.5);
      if (std::hypot(f.x, f.y) <= rho_spot)
        view.refs.insert(view.refs.end(), field.tmp.begin(), field.tmp.end());
    }
  view.pixel_offset[static_cast<std::size_t>(W) * H] = static_cast<int>(view.refs.size());
  return view;
}

std::optional<PixelView> field_view(const Scene& scene, const OpticalDomains& domains,
                                    const std::atomic<bool>* cancel) {
  const int W = scene.render.width, H = scene.render.height;
  const bool cone =
      scene.mode == ViewMode::Cono;  // without the Bertrand lens: the image plane lit by the whole cone
  const bool on_stage = scene.sample_in;
  const SampleType type = scene.sample.type;
  const FieldUnits field_units(scene, domains);
  PixelView view;
  view.kind = ViewKind::Field;
  view.units = field_units.units();
  view.pixel_offset.assign(static_cast<std::size_t>(W) * H + 1, 0);
  if (cone) {
    const double s_max = std::min(scene.condenser.na, scene.objective.na);
    view.cone_dirs = cone_directions(scene.render.spp > 0 ? std::max(1, scene.render.spp) : 64, s_max);
  }
  const int n = samples_per_side(scene.render.spp > 0 ? scene.render.spp
                                                      : (on_stage && type != SampleType::Plate ? 4 : 1));
  view.spatial_samples = n * n;
  // Sections: the domain at every pixel centre first; only pixels on a grain or lamella boundary
  // (a 4-neighbour differs) need the sub-pixel samples.
  const bool section_map = on_stage && type == SampleType::Section && n > 1;
  std::vector<int> centre_domain;
  const FieldToSection to_section(scene);
  if (section_map) {
    centre_domain.resize(static_cast<std::size_t>(W) * H);
    tbb::parallel_for(tbb::blocked_range<int>(0, H, 8), [&](const tbb::blocked_range<int>& r) {
      if (cancelled(cancel)) return;
      for (int y = r.begin(); y != r.end(); ++y)
        for (int x = 0; x < W; ++x)
          centre_domain[static_cast<std::size_t>(y) * W + x] =
              domains.domain_at_sample(to_section(field_from_pixel(W, H, x + 0.5, y + 0.5)));
    });
    if (cancelled(cancel)) return std::nullopt;
  }
  // A neighbour beyond the image's edge is looked up in the section too: an edge pixel whose
  // neighbour across a boundary lies outside the image straddles that boundary all the same (a
  // render of a larger field, or a flat response's canvas, samples it there).
  auto interior = [&](int x, int y) {
    const int d = centre_domain[static_cast<std::size_t>(y) * W + x];
    auto same = [&](int xx, int yy) {
      if (xx < 0 || yy < 0 || xx >= W || yy >= H)
        return domains.domain_at_sample(to_section(field_from_pixel(W, H, xx + 0.5, yy + 0.5))) == d;
      return centre_domain[static_cast<std::size_t>(yy) * W + xx] == d;
    };
    return same(x - 1, y) && same(x + 1, y) && same(x, y - 1) && same(x, y + 1);
  };
  // A uniform sample (one unit, no wedge or section): every pixel shows unit 0 with the summed
  // weight of its sub-samples — filled directly, without per-sample bookkeeping.
  const bool is_wedge = on_stage && type == SampleType::Wedge;
  const bool uniform = !is_wedge && !(on_stage && type == SampleType::Section) && view.units.size() == 1;
  if (uniform) {
    float w = 0.0f;
    for (int k = 0; k < n * n; ++k) w += 1.0f / (n * n);  // as RefBuilder sums them
    const std::size_t pixels = static_cast<std::size_t>(W) * H;
    view.refs.assign(pixels, PixelRef{0, w});
    for (std::size_t i = 0; i < pixels; ++i) view.pixel_offset[i] = static_cast<int>(i);
  }
  // Rows in parallel, each into its own list, then concatenated in order.
  std::vector<std::vector<PixelRef>> row_refs(uniform ? 0 : H);
  std::vector<std::vector<int>> row_counts(H);
  tbb::parallel_for(tbb::blocked_range<int>(0, uniform ? 0 : H, 4), [&](const tbb::blocked_range<int>& r) {
    RefBuilder rb;
    for (int y = r.begin(); y != r.end(); ++y) {
      if (cancelled(cancel)) return;
      row_counts[y].resize(W);
      for (int x = 0; x < W; ++x) {
        rb.tmp.clear();
        if (section_map && interior(x, y)) {
          const int d = centre_domain[static_cast<std::size_t>(y) * W + x];
          if (domains.opaque(d)) {
            row_counts[y][x] = 0;
            continue;
          }
          rb.tmp.push_back({d, 1.0f});
          row_counts[y][x] = 1;
          row_refs[y].push_back(rb.tmp[0]);
          continue;
        }
        for (int sy = 0; sy < n; ++sy)
          for (int sx = 0; sx < n; ++sx)
            field_units.add_field_point(rb, field_from_pixel(W, H, x + (sx + 0.5) / n, y + (sy + 0.5) / n),
                                        1.0f / (n * n));
        row_counts[y][x] = static_cast<int>(rb.tmp.size());
        row_refs[y].insert(row_refs[y].end(), rb.tmp.begin(), rb.tmp.end());
      }
    }
  });
  if (cancelled(cancel)) return std::nullopt;
  for (int y = 0; y < (uniform ? 0 : H); ++y) {
    int k = 0;
    for (int x = 0; x < W; ++x) {
      view.pixel_offset[static_cast<std::size_t>(y) * W + x] = static_cast<int>(view.refs.size()) + k;
      k += row_counts[y][x];
    }
    view.refs.insert(view.refs.end(), row_refs[y].begin(), row_refs[y].end());
  }
  view.pixel_offset[static_cast<std::size_t>(W) * H] = static_cast<int>(view.refs.size());
  return view;
}

std::optional<PixelView> pixel_view(const Scene& scene, const OpticalDomains& domains,
                                    const std::atomic<bool>* cancel) {
  if (scene.bertrand_in)
    return scene.mode == ViewMode::Cono ? conoscopic_figure_view(scene, domains, cancel)
                                        : std::optional<PixelView>(parallel_light_spot_view(scene, domains));
  return field_view(scene, domains, cancel);
}

}  // namespace pmsim
