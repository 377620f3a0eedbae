#include "core/specimen/section_becke_probe.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/base/units.h"
#include "core/crystal/vibration_index.h"
#include "core/microscope/map_section.h"
#include "core/microscope/view_geometry.h"
#include "core/specimen/becke_probe.h"
#include "core/specimen/probe_point.h"
#include "core/specimen/section_slab.h"
#include "core/specimen/specimen_scene.h"

namespace pmsim {
namespace {

// Directions searched from the point, 2° apart: a straight boundary at distance d is found at
// most d·(1/cos 1° − 1) = 1.5·10⁻⁴·d too far (0.03 µm at 200 µm), far below the slab's grid.
constexpr int kDirections = 180;
// Marching steps per direction at most (a step is half the slab's grid spacing, so a crack the
// slab widens to one grid step is not stepped over, unless the radius is > 500 grid steps).
constexpr int kMaxSteps = 1000;
// The boundary is bisected to this (µm): far below the grid spacing (≥ 0.5 µm) it is drawn at.
constexpr double kBisectUm = 1e-4;

struct SlabMedia {
  const SectionMap& map;
  std::vector<int> of_domain;  // section_slab_media
  double spacing_um;
  IsotropicMedium mounting;
  glm::dvec3 vibration;

  int domain_at(const glm::dvec2& p_um) const {
    return section_slab_node(map, 1e-3 * p_um, spacing_um).domain;
  }
  int medium_at(const glm::dvec2& p_um) const { return of_domain[std::size_t(domain_at(p_um))]; }

  SectionBeckeSide side_at(const glm::dvec2& p_um) const {
    SectionBeckeSide s;
    s.domain = domain_at(p_um);
    if (of_domain[std::size_t(s.domain)] == kSpecimenLiquid) {
      s.n = mounting.n(kBeckeWavelengthNm);
      return s;
    }
    s.grain = map.grain_label(s.domain);
    s.mineral = map.mineral_of_domain(s.domain);
    const SectionGrain& g = map.grain_by_label(s.grain);
    const DomainPart part = map.domain_part(s.domain);
    s.zone = part.zone;
    s.zone_count = int(g.zones.size());
    s.twin = g.twinned ? part.twin : -1;
    s.n = vibration_index(*map.crystal_of_domain(s.domain), map.orientation_of_domain(s.domain),
                          kBeckeWavelengthNm, vibration);
    return s;
  }
};

}  // namespace

double section_becke_radius_um(const Scene& scene) { return std::max(10.0, 100.0 * field_of_view_mm(scene)); }

SectionBeckeProbe probe_section_becke_line(const SectionMap& map, const Scene& scene, double x, double y,
                                           double radius_um) {
  const ProbePoint pp = probe_point(scene, x, y);
  const SlabMedia media{map, section_slab_media(map), section_slab_options(scene).spacing_um,
                        section_mounting_medium(scene), pp.vibration};
  SectionBeckeProbe r;
  r.point_um = pp.specimen_um;
  r.radius_um = radius_um > 0.0 ? radius_um : section_becke_radius_um(scene);
  r.here = media.side_at(r.point_um);
  const int here = media.of_domain[std::size_t(r.here.domain)];

  const double step = std::max(0.5 * media.spacing_um, r.radius_um / kMaxSteps);
  double best = r.radius_um;
  glm::dvec2 beyond{0.0};
  for (int k = 0; k < kDirections; ++k) {
    const double a = 2.0 * kPi * k / kDirections;
    const glm::dvec2 dir{std::cos(a), std::sin(a)};
    // March out to the nearest boundary found so far (no farther one can win), then bisect.
    double lo = 0.0;
    for (double t = std::min(step, best); lo < best; lo = t, t = std::min(t + step, best)) {
      if (media.medium_at(r.point_um + t * dir) == here) continue;
      double hi = t;
      while (hi - lo > kBisectUm) {
        const double mid = 0.5 * (lo + hi);
        (media.medium_at(r.point_um + mid * dir) == here ? lo : hi) = mid;
      }
      if (hi <= best) {
        best = hi;
        r.found = true;
        r.boundary_um = r.point_um + 0.5 * (lo + hi) * dir;
        r.distance_um = 0.5 * (lo + hi);
        beyond = r.point_um + hi * dir;
      }
      break;
    }
  }
  if (!r.found) return r;
  r.there = media.side_at(beyond);
  const double d = r.here.n - r.there.n;
  r.moves_into = std::abs(d) < kBeckeMatch ? BeckeMovesInto::Matched
                 : d > 0                   ? BeckeMovesInto::Here
                                           : BeckeMovesInto::There;
  return r;
}

SectionBeckeProbe probe_section_becke_line(const Scene& scene, double x, double y) {
  return probe_section_becke_line(*load_scene_section(scene), scene, x, y);
}

std::string section_becke_side_name(const SectionBeckeSide& s) {
  if (s.is_medium()) return "mounting medium";
  std::string name = s.mineral + " (grain " + std::to_string(s.grain);
  if (s.zone_count > 1)
    name += ", zone " + std::to_string(s.zone + 1) + " of " + std::to_string(s.zone_count);
  if (s.twin >= 0) name += ", twin individual " + std::to_string(s.twin + 1);
  return name + ")";
}

std::string describe_section_becke_line(const SectionBeckeProbe& p) {
  const auto index = [](const SectionBeckeSide& s) {
    char b[32];
    std::snprintf(b, sizeof b, "%s %.4f", s.is_medium() ? "n_D" : "n'", s.n);
    return std::string(b);
  };
  const std::string here = section_becke_side_name(p.here), there = section_becke_side_name(p.there);
  char buf[512];
  if (!p.found) {
    std::snprintf(
        buf, sizeof buf,
        "No boundary within %.0f um: here %s, %s. Move to a grain edge or a crack to watch the Becke line.",
        p.radius_um, here.c_str(), index(p.here).c_str());
    return buf;
  }
  const int n =
      std::snprintf(buf, sizeof buf, "Nearest boundary %.1f um away: %s, %s | %s, %s. ", p.distance_um,
                    here.c_str(), index(p.here).c_str(), there.c_str(), index(p.there).c_str());
  const std::size_t used = std::min(sizeof buf - 1, std::size_t(std::max(0, n)));
  if (p.moves_into == BeckeMovesInto::Matched) {
    std::snprintf(
        buf + used, sizeof buf - used,
        "The indices match within %.3f: the boundary nearly vanishes and shows no Becke line, only faint "
        "dispersion colours.",
        kBeckeMatch);
  } else {
    const bool into_here = p.moves_into == BeckeMovesInto::Here;
    std::snprintf(buf + used, sizeof buf - used,
                  "Focusing up (focus +), the bright Becke line moves into the %s, the side of higher index; "
                  "focusing down, into the %s.",
                  (into_here ? here : there).c_str(), (into_here ? there : here).c_str());
  }
  return buf;
}

}  // namespace pmsim
