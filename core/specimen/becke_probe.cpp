#include "core/specimen/becke_probe.h"

#include <cmath>
#include <cstdio>

#include "core/base/units.h"
#include "core/crystal/section_optics.h"
#include "core/specimen/probe_point.h"

namespace pmsim {

FragmentOptics fragment_optics(const SpecimenScene& specimen, int fragment, const glm::dvec3& vibration) {
  const int medium = kFirstFragment + fragment;
  FragmentOptics f;
  f.liquid_n = specimen.liquid().n(kBeckeWavelengthNm);
  f.n_vibration = specimen.index(medium, kBeckeWavelengthNm, vibration);
  if (const Crystal* crystal = specimen.crystal_of(medium)) {
    const SectionOptics so =
        section_optics(specimen.orientation_of(medium), crystal->principal_indices(kBeckeWavelengthNm), {0.0, 0.0, 1.0});
    f.n_fast = so.n_fast;
    f.n_slow = so.n_slow;
  } else {
    f.n_fast = f.n_slow = f.n_vibration;
  }
  const double d = f.n_vibration - f.liquid_n;
  f.relief = std::abs(d) < kBeckeMatch ? 0 : (d > 0 ? 1 : -1);
  return f;
}

BeckeProbe probe_becke_line(const SpecimenScene& specimen, const Scene& scene, double x, double y) {
  const ProbePoint pp = probe_point(scene, x, y);
  const glm::dvec3& vibration = pp.vibration;
  BeckeProbe r;
  r.liquid_n = specimen.liquid().n(kBeckeWavelengthNm);
  r.fragment = specimen.fragment_under(pp.specimen_um.x, pp.specimen_um.y);
  r.on_fragment = r.fragment >= 0;
  if (!r.on_fragment) {
    // Over liquid: the mineral's index for a fragment in this mount is the same crystal's along
    // the polarizer in the first fragment's orientation (any orientation would do for an
    // isotropic mineral; for an anisotropic one the panel says it depends on the fragment).
    if (specimen.fragment_count() == 0) return r;
    r.fragment = 0;
  }
  const FragmentOptics f = fragment_optics(specimen, r.fragment, vibration);
  r.mineral_n = f.n_vibration;
  r.n_fast = f.n_fast;
  r.n_slow = f.n_slow;
  r.moves_into_mineral = f.relief;
  return r;
}

std::string describe_becke_line(const BeckeProbe& p) {
  char buf[320];
  if (p.moves_into_mineral == 0)
    std::snprintf(buf, sizeof buf,
                  "n' %.4f matches the liquid's n_D %.4f: the outline nearly vanishes; the liquid's larger "
                  "dispersion leaves bluish and orange fringes.",
                  p.mineral_n, p.liquid_n);
  else if (p.moves_into_mineral > 0)
    std::snprintf(buf, sizeof buf,
                  "n' %.4f > liquid %.4f: focusing up (focus +), the bright Becke line moves into the "
                  "grain; focusing down it moves out into the liquid.",
                  p.mineral_n, p.liquid_n);
  else
    std::snprintf(buf, sizeof buf,
                  "n' %.4f < liquid %.4f: focusing up (focus +), the bright Becke line moves out into the "
                  "liquid; focusing down it moves into the grain.",
                  p.mineral_n, p.liquid_n);
  return buf;
}

std::string describe_crossed_polars(const BeckeProbe& p) {
  char buf[320];
  if (p.n_slow - p.n_fast < 1e-6)
    std::snprintf(buf, sizeof buf,
                  "Crossed polars: n' %.4f for every vibration (isotropic here): the grain stays dark at every "
                  "stage angle; only its outline and the light it bends show.",
                  p.n_fast);
  else
    std::snprintf(buf, sizeof buf,
                  "Crossed polars: the light splits into two waves vibrating along n'a %.4f and n'g %.4f; their "
                  "path difference (n'g - n'a) x thickness = %.1f nm per um sets the colour, thicker at the "
                  "centre, thinning to first-order fringes at the edge; dark when a vibration is along a polar.",
                  p.n_fast, p.n_slow, 1000.0 * (p.n_slow - p.n_fast));
  return buf;
}

}  // namespace pmsim
