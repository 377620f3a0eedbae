// SectionMap's myrmekite (SectionGrain::Myrmekite; the geometry in core/texture/myrmekite.h):
// where each grain's bulbs stand, and which bulb a point of a host grain lies in.
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/base/splitmix64.h"
#include "core/base/units.h"
#include "core/crystal/mineral_series.h"
#include "core/microscope/section_map.h"

namespace pmsim {

namespace {
// The boundary search along a site's ray: a step well under a bulb (so a neighbour thinner than
// that between the centre and the rim is stepped over) and the root to half a micrometre.
constexpr double kRayStepMm = 0.02, kRootToleranceMm = 5e-4;
// The bulb sites' hash stream (which sites carry a bulb, where along their arc).
constexpr std::uint64_t kBulbSiteSalt = 0x3E7Full;
}  // namespace

// Sites one every bulb_mm of arc on the circle of the grain's mean semi-axis, each taken with probability
// `fraction` and jittered within its share of the turn; the ray from the grain's nucleus at the
// site's angle leaves the grain's tiling cell at the root, and a bulb stands there when the grain
// just beyond is of the host mineral. Its depth and width vary by hash: 0.5–1 of depth_mm, 0.6–1
// of bulb_mm.
void SectionMap::place_myrmekite() {
  std::vector<int> mine;
  std::set<std::string> hosts;
  for (const int i : grown_grain_)
    if (const auto& m = grains[static_cast<std::size_t>(i)].myrmekite) {
      mine.push_back(i);
      hosts.insert(series_name(m->host));
    }
  if (mine.empty()) return;
  hosts_bulbs_.assign(grains.size(), 0);
  for (std::size_t i = 0; i < grains.size(); ++i) hosts_bulbs_[i] = hosts.count(series_name(grains[i].mineral)) > 0;
  std::vector<std::vector<MyrmekiteBulb>> found(mine.size());
  tbb::parallel_for(std::size_t(0), mine.size(), [&](std::size_t k) {
    const int gi = mine[k];
    const SectionGrain& g = grains[static_cast<std::size_t>(gi)];
    const SectionGrain::Myrmekite& m = *g.myrmekite;
    const glm::dvec2 from{g.growth->nucleus_mm.x, g.growth->nucleus_mm.y};
    const double reach = g.growth->shape.circumradius_mm;
    const double radius = std::min(reach, 0.5 * (g.semi_major_mm + g.semi_minor_mm));  // the grain's ellipse
    const int sites = std::max(4, static_cast<int>(std::lround(2.0 * kPi * radius / m.bulb_mm)));
    const std::string host = series_name(m.host);
    const auto inside = [&](const glm::dvec2& q) { return nearest_grain(q) == gi; };
    for (int j = 0; j < sites; ++j) {
      const std::uint64_t h = splitmix64((static_cast<std::uint64_t>(gi) << 20) ^ static_cast<std::uint64_t>(j) ^ kBulbSiteSalt);
      if (unit_interval(h) >= m.fraction) continue;
      const double a = 2.0 * kPi * (j + 0.2 + 0.6 * unit_interval(splitmix64(h + 1))) / sites;
      const glm::dvec2 dir{std::cos(a), std::sin(a)};
      const auto t = ray_exit_mm(inside, from, dir, reach, std::min(kRayStepMm, 0.25 * m.bulb_mm), kRootToleranceMm);
      if (!t) continue;
      const glm::dvec2 root = from + *t * dir;  // the tiling runs past the section's edges
      if (std::abs(root.x) > 0.5 * width_mm || std::abs(root.y) > 0.5 * height_mm) continue;
      const int beyond = nearest_grain(from + (*t + 2.0 * kRootToleranceMm) * dir);
      if (beyond < 0 || series_name(grains[static_cast<std::size_t>(beyond)].mineral) != host) continue;
      MyrmekiteBulb b;
      b.root_mm = root;
      b.out = dir;
      b.depth_mm = m.depth_mm * (0.5 + 0.5 * unit_interval(splitmix64(h + 2)));
      b.half_width_mm = 0.5 * m.bulb_mm * (0.6 + 0.4 * unit_interval(splitmix64(h + 3)));
      b.grain = gi;
      b.hash = splitmix64(h + 4);
      found[k].push_back(b);
    }
  });
  std::vector<MyrmekiteBulb> all;
  for (auto& f : found) all.insert(all.end(), f.begin(), f.end());
  if (!all.empty()) bulbs_ = std::make_shared<const MyrmekiteBulbs>(std::move(all), width_mm, height_mm);
}

int SectionMap::myrmekite_bulb_of(int gi, const glm::dvec2& p) const {
  if (!bulbs_) return -1;
  const int b = bulbs_->at(p);
  if (b < 0 || bulbs_->bulb(b).grain != gi) return -1;
  const int c = grown_->owner(p);  // the host's point, not the grain's own
  return c >= 0 && hosts_bulbs_[static_cast<std::size_t>(grown_grain_[static_cast<std::size_t>(c)])] ? b : -1;
}

}  // namespace pmsim
