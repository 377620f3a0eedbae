#include "core/microscope/lens_model_difference.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/microscope/evaluation_plan.h"
#include "core/microscope/optical_train.h"
#include "core/spectrum/color.h"

namespace pmsim {

double lens_model_difference(const EvaluationPlan& plan, const LensPolarizationTable& table) {
  const TrainState train = make_train(plan.scene(), plan.compensator(), 550.0);
  const std::vector<OpticalDomain>& domains = plan.domains();
  const std::vector<EvalUnit>& units = plan.units();
  // Plates prepared as the sampled units reach their domains: an EBSD map has 10⁴ domains, of
  // which the ≤ 512 samples see a few hundred.
  std::vector<PreparedPlate> prepared(domains.size());
  std::vector<char> ready(domains.size(), 0);
  const std::size_t stride = std::max<std::size_t>(1, units.size() / 512);
  double sum = 0.0;
  int n = 0;
  for (std::size_t u = 0; u < units.size(); u += stride) {
    const EvalUnit& unit = units[u];
    const int dirs = plan.dirs_of(unit);
    for (int d = 0; d < dirs; d += std::max(1, dirs / 8)) {
      const glm::dvec3 k = plan.dir(unit, d);
      JonesMatrix sample = JonesMatrix::identity();
      if (domains[unit.domain].crystal && unit.thickness_um > 0) {
        if (!ready[unit.domain]) {
          prepared[unit.domain] = plan.prepare(unit.domain, 550.0);
          ready[unit.domain] = 1;
        }
        PreparedPlate p = prepared[unit.domain];
        p.thickness_um = unit.thickness_um;
        sample = plate_jones(p, k);
      }
      // Ideal lenses: the aplanatic frame change alone; physical: with the lens' diattenuation
      // (as EvaluationPlan::lens_jones).
      const glm::dmat2 frame = aplanatic_frame(k), frame_back = glm::transpose(frame), lens = table.jones(k);
      const JonesMatrix ideal_in = jones_from_real(frame), ideal_out = jones_from_real(frame_back);
      const JonesMatrix physical_in = jones_from_real(lens * frame),
                        physical_out = jones_from_real(frame_back * lens);
      const double ideal = jones_transmission(train, ideal_out * sample * ideal_in);
      const double physical = jones_transmission(train, physical_out * sample * physical_in);
      sum += std::fabs(cielab_lightness(ideal) - cielab_lightness(physical));
      ++n;
    }
  }
  return n ? sum / n : 0.0;
}

}  // namespace pmsim
