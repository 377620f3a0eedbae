#include "core/specimen/specimen_tracer.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/optics/interaction.h"

namespace pmsim {

void InterfaceCounters::add(const InterfaceCounters& o) {
  paths += o.paths;
  events += o.events;
  tir += o.tir;
  lost += o.lost;
  incident += o.incident;
  reflected += o.reflected;
  transmitted += o.transmitted;
  max_defect = std::max(max_defect, o.max_defect);
  capped_power += o.capped_power;
}

SpecimenPath trace_specimen(const SpecimenScene& scene, PolarizedRay ray, InterfaceCounters* counters,
                            int max_interfaces) {
  SpecimenPath path;
  if (counters) ++counters->paths;
  ray.dir = glm::normalize(ray.dir);
  ray.pol = glm::normalize(ray.pol - glm::dot(ray.pol, ray.dir) * ray.dir);
  int medium = kSpecimenAir;
  InteractionResult res;
  SpecimenHit hit;
  // The first segment starts in the air above everything; later ones on a surface, nudged off it.
  double tnear = 0.0;
  for (int i = 0; i < max_interfaces; ++i) {
    if (!scene.intersect(ray.origin, ray.dir, tnear, hit)) {
      path.left_below = medium == kSpecimenAir && ray.dir.z < 0.0;
      path.throughput = path.left_below ? ray.intensity : 0.0;
      path.exit_dir = ray.dir;
      return path;
    }
    const bool from_front = glm::dot(ray.dir, hit.normal) < 0.0;
    const int from = from_front ? hit.front : hit.back;
    const int to = from_front ? hit.back : hit.front;
    medium = from;
    const double n_i = scene.index(from, ray.wavelength_nm, ray.pol);
    const double n_t = scene.index(to, ray.wavelength_nm, ray.pol);
    interact(ray, hit.point, hit.normal, n_i, n_t, FresnelModel::Exact, res);
    ++path.interfaces;
    const double R = res.reflected_intensity();
    const double T = res.has_refracted ? res.refracted.intensity : 0.0;
    if (counters) {
      ++counters->events;
      counters->tir += res.tir ? 1 : 0;
      counters->incident += ray.intensity;
      counters->reflected += R;
      counters->transmitted += T;
      if (ray.intensity > 0.0)
        counters->max_defect = std::max(counters->max_defect, std::abs(ray.intensity - R - T) / ray.intensity);
    }
    if (res.has_refracted) {
      ray = res.refracted;
      medium = to;
    } else if (res.reflected_count > 0) {
      // TIR: the E⊥ and E∥ parts go the same way; one ray of their summed intensity, vibrating
      // along their intensity-weighted sum (the phase between them does not change the power
      // of later Fresnel events of this single-path estimate beyond second order).
      glm::dvec3 pol{0.0};
      for (int k = 0; k < res.reflected_count; ++k)
        pol += std::sqrt(res.reflected[k].intensity) * res.reflected[k].pol;
      ray = res.reflected[0];
      ray.intensity = R;
      const double len = glm::length(pol);
      ray.pol = len > 0.0 ? pol / len : res.reflected[0].pol;
      medium = from;
    } else {
      return path;  // nothing goes on (grazing exactly at the critical angle)
    }
    // Start the next segment a little off the surface, on the side it travels into.
    const double side = glm::dot(ray.dir, hit.normal) > 0.0 ? 1.0 : -1.0;
    ray.origin = hit.point + (1e-3 * side) * hit.normal;
    tnear = 0.0;
  }
  if (counters) ++counters->lost;
  return path;
}

}  // namespace pmsim
