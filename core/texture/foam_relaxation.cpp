#include "core/texture/foam_relaxation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/base/splitmix64.h"

namespace pmsim {

namespace {

// Nuclei bucketed on a grid of cubes about one nucleus spacing wide (compressed rows).
class NucleusGrid {
 public:
  NucleusGrid(const FoamBox& box, double bucket_mm, const std::vector<glm::dvec3>& nuclei)
      : box_(box), bucket_(bucket_mm), nuclei_(nuclei) {
    for (int a = 0; a < 3; ++a) n_[a] = std::max(1, static_cast<int>(std::ceil((box.hi[a] - box.lo[a]) / bucket_mm)));
    start_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
    for (const glm::dvec3& p : nuclei) ++start_[index(cell(p)) + 1];
    for (std::size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
    members_.resize(nuclei.size());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < nuclei.size(); ++i) members_[fill[index(cell(nuclei[i]))]++] = i;
  }

  // The nearest nucleus: rings of buckets outward from p's until no unvisited bucket can be nearer
  // (a bucket r rings out is at least (r − 1)·bucket from any point of p's bucket).
  std::size_t nearest(const glm::dvec3& p) const {
    const glm::ivec3 c = cell(p);
    double best = std::numeric_limits<double>::infinity();
    std::size_t arg = 0;
    const int max_ring = std::max({n_[0], n_[1], n_[2]});
    for (int r = 0; r <= max_ring; ++r) {
      for (int i = c.x - r; i <= c.x + r; ++i)
        for (int j = c.y - r; j <= c.y + r; ++j)
          for (int k = c.z - r; k <= c.z + r; ++k) {
            if (std::max({std::abs(i - c.x), std::abs(j - c.y), std::abs(k - c.z)}) != r) continue;
            if (i < 0 || j < 0 || k < 0 || i >= n_[0] || j >= n_[1] || k >= n_[2]) continue;
            const std::size_t b = index({i, j, k});
            for (std::size_t m = start_[b]; m < start_[b + 1]; ++m) {
              const glm::dvec3 d = nuclei_[members_[m]] - p;
              const double d2 = d.x * d.x + d.y * d.y + d.z * d.z;
              if (d2 < best || (d2 == best && members_[m] < arg)) best = d2, arg = members_[m];
            }
          }
      if (best <= double(r) * bucket_ * double(r) * bucket_) break;
    }
    return arg;
  }

 private:
  glm::ivec3 cell(const glm::dvec3& p) const {
    glm::ivec3 c;
    for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>((p[a] - box_.lo[a]) / bucket_), 0, n_[a] - 1);
    return c;
  }
  std::size_t index(const glm::ivec3& c) const {
    return (static_cast<std::size_t>(c.z) * n_[1] + c.y) * n_[0] + c.x;
  }

  FoamBox box_;
  double bucket_;
  const std::vector<glm::dvec3>& nuclei_;
  int n_[3] = {1, 1, 1};
  std::vector<std::size_t> start_, members_;
};

}  // namespace

std::vector<glm::dvec3> relaxed_foam_nuclei(const FoamBox& box, std::size_t count, int iterations, std::uint64_t seed) {
  std::uint64_t state = splitmix64(seed ^ 0xF0A3ull);
  const auto uniform = [&] {
    state = splitmix64(state);
    return unit_interval(state);
  };
  const glm::dvec3 extent = box.hi - box.lo;
  std::vector<glm::dvec3> nuclei(count);
  for (glm::dvec3& p : nuclei) p = box.lo + glm::dvec3(uniform(), uniform(), uniform()) * extent;
  if (count == 0) return nuclei;
  const double spacing = std::cbrt(extent.x * extent.y * extent.z / double(count));
  // ~27 centroid points a cell: the junction angles come out as with 64 (median |angle − 120°|
  // 13.0° against 12.75–13.25°, seeds 3–5) at 2.4× less work.
  const double h = spacing / 3.0;
  int n[3];
  for (int a = 0; a < 3; ++a) n[a] = std::max(1, static_cast<int>(std::floor(extent[a] / h)));
  std::vector<glm::dvec3> sum(count);
  std::vector<std::size_t> hits(count);
  std::vector<std::uint32_t> owner(std::size_t(n[0]) * n[1] * n[2]);
  for (int it = 0; it < iterations; ++it) {
    const NucleusGrid grid(box, spacing, nuclei);
    std::fill(sum.begin(), sum.end(), glm::dvec3(0.0));
    std::fill(hits.begin(), hits.end(), 0);
    // A fresh sub-cell shift each step, so the grid leaves no pattern in the centroids. The
    // nearest-nucleus searches run in parallel into `owner`; the sums then run in one fixed order,
    // so the result does not depend on the thread count.
    glm::dvec3 step, offset;
    for (int a = 0; a < 3; ++a) step[a] = extent[a] / n[a], offset[a] = uniform() * step[a];
    const auto point = [&](int i, int j, int k) { return box.lo + offset + glm::dvec3(i, j, k) * step; };
    tbb::parallel_for(tbb::blocked_range<int>(0, n[2]), [&](const tbb::blocked_range<int>& ks) {
      for (int k = ks.begin(); k < ks.end(); ++k)
        for (int j = 0; j < n[1]; ++j)
          for (int i = 0; i < n[0]; ++i)
            owner[(std::size_t(k) * n[1] + j) * n[0] + i] = static_cast<std::uint32_t>(grid.nearest(point(i, j, k)));
    });
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          const std::uint32_t o = owner[(std::size_t(k) * n[1] + j) * n[0] + i];
          sum[o] += point(i, j, k);
          ++hits[o];
        }
    for (std::size_t c = 0; c < count; ++c)
      if (hits[c] > 0) nuclei[c] = sum[c] / double(hits[c]);
  }
  return nuclei;
}

}  // namespace pmsim
