#include "core/crystal/mineral_series.h"

#include <algorithm>

#include "core/base/json_reader.h"
#include "core/crystal/crystal_indices.h"

namespace pmsim {

glm::dvec3 MineralSeries::indices_at(double composition) const {
  if (points.size() == 1 || composition <= points.front().composition) return points.front().indices;
  if (composition >= points.back().composition) return points.back().indices;
  const auto hi = std::upper_bound(points.begin(), points.end(), composition,
                                   [](double x, const SeriesPoint& p) { return x < p.composition; });
  const auto lo = hi - 1;
  const double t = (composition - lo->composition) / (hi->composition - lo->composition);
  return lo->indices + t * (hi->indices - lo->indices);
}

MineralSeries read_mineral_series(const JsonReader& r) {
  r.refuse_unknown_keys({"component", "complement", "source", "points"});
  MineralSeries s;
  s.component = r.require<std::string>("component");
  if (s.component.empty()) r.fail("component", "names the end member, e.g. An or Fo");
  s.complement = r.get_or<std::string>("complement", "");
  s.source = r.require<std::string>("source");
  if (s.source.empty()) r.fail("source", "every block must cite the publication of its data");
  for (const JsonReader& p : r.objects("points", 2)) {
    p.refuse_unknown_keys({"composition", "nalpha", "nbeta", "ngamma", "optic_angle_2vz_deg"});
    SeriesPoint pt;
    pt.composition = p.require<double>("composition", Range::closed(0, 100));
    if (!s.points.empty() && !(pt.composition > s.points.back().composition))
      p.fail("composition", "compositions must increase strictly along the series");
    const char* keys[3] = {"nalpha", "nbeta", "ngamma"};
    for (int k = 0; k < 3; ++k) {
      pt.indices[k] = p.require<double>(keys[k]);
      p.checked(keys[k], *p.find(keys[k]), [&](const nlohmann::json&) {
        check_refractive_index(pt.indices[k]);
        return 0;
      });
    }
    p.checked("", p.node(), [&](const nlohmann::json&) {
      check_biaxial_order(pt.indices.x, pt.indices.y, pt.indices.z);
      return 0;
    });
    pt.literature_2vz_deg = p.optional<double>("optic_angle_2vz_deg", Range::closed(0, 180));
    s.points.push_back(pt);
  }
  if (s.points.front().composition != 0.0 || s.points.back().composition != 100.0)
    r.fail("points", "a series covers the compositions 0 to 100");
  return s;
}

std::string series_name(std::string_view name) { return std::string(name.substr(0, name.find(':'))); }

}  // namespace pmsim
