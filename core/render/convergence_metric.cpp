#include "core/render/convergence_metric.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"

namespace pmsim {

double unit_error(const EvaluationPlan& plan, const std::vector<double>& area,
                  const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b, std::size_t stride,
                  const std::atomic<bool>& cancel) {
  const glm::dvec3 white = illuminant_white_xyz(plan.scene().illuminant);
  const bool mono = plan.scene().render.single_wavelength_nm > 0;
  struct Acc {
    double sum = 0.0, weight = 0.0;
  };
  const std::size_t m = (a.size() + stride - 1) / stride;
  const Acc acc = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, m, 2048), Acc{},
      [&](const tbb::blocked_range<std::size_t>& r, Acc s) {
        if (cancel.load(std::memory_order_relaxed)) return s;  // the caller checks it next
        for (std::size_t j = r.begin(); j != r.end(); ++j) {
          const std::size_t u = j * stride;
          if (area[u] <= 0) continue;
          const glm::dvec3 xa = mono ? white * a[u].y : a[u], xb = mono ? white * b[u].y : b[u];
          s.sum += area[u] * ciede2000(xyz_to_lab(xa, white), xyz_to_lab(xb, white));
          s.weight += area[u];
        }
        return s;
      },
      [](Acc x, const Acc& y) {
        x.sum += y.sum;
        x.weight += y.weight;
        return x;
      });
  return acc.weight > 0 ? acc.sum / acc.weight : 0.0;
}

}  // namespace pmsim
