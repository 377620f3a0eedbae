#include "core/bench/image_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "core/spectrum/color.h"

namespace pmsim {

ImageError image_error_de2000(const std::vector<float>& a, const std::vector<float>& b,
                              const std::vector<std::uint8_t>& lit, const glm::dvec3& white) {
  if (a.size() != b.size() || a.size() % 3 != 0 || (!lit.empty() && lit.size() * 3 != a.size()))
    throw std::invalid_argument("image_error_de2000: image sizes differ");
  const std::size_t n = a.size() / 3;
  std::vector<double> de(n, -1.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        if (!lit.empty() && !lit[i]) continue;
                        const glm::dvec3 xa(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
                        const glm::dvec3 xb(b[3 * i], b[3 * i + 1], b[3 * i + 2]);
                        const double d = ciede2000(xyz_to_lab(xa, white), xyz_to_lab(xb, white));
                        de[i] = std::isfinite(d) ? d : std::numeric_limits<double>::infinity();
                      }
                    });
  de.erase(std::remove(de.begin(), de.end(), -1.0), de.end());
  ImageError e;
  e.pixels = de.size();
  if (de.empty()) return e;
  double sum = 0.0;
  for (double d : de) sum += d;
  e.mean_de2000 = sum / static_cast<double>(de.size());
  const std::size_t k = std::min(de.size() - 1, static_cast<std::size_t>(0.95 * (de.size() - 1) + 0.5));
  std::nth_element(de.begin(), de.begin() + static_cast<std::ptrdiff_t>(k), de.end());
  e.p95_de2000 = de[k];
  e.max_de2000 = *std::max_element(de.begin(), de.end());
  return e;
}

}  // namespace pmsim
