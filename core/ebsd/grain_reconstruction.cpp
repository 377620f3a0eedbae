#include "core/ebsd/grain_reconstruction.h"

#include <algorithm>
#include <cmath>

namespace pmsim {

namespace {

// How many of a grain's latest clusters a point tries before starting one: enough for the
// gradual bending of a deformed grain (neighbouring points fall in recent clusters), bounded so
// that a heavily misoriented grain costs O(points), not O(points × clusters).
constexpr int kRecentClusters = 16;

}  // namespace

int grid_neighbours(const OrientationMap& m, std::size_t i, std::size_t out[6]) {
  const int r = m.row_of(i);
  const int c = static_cast<int>(i - m.row_start(r));
  const int n_here = m.columns_in_row(r);
  int k = 0;
  if (c > 0) out[k++] = i - 1;
  if (c + 1 < n_here) out[k++] = i + 1;
  for (const int rr : {r - 1, r + 1}) {
    if (rr < 0 || rr >= m.rows) continue;
    const int n = m.columns_in_row(rr);
    const std::size_t s = m.row_start(rr);
    if (m.grid == MapGrid::Square) {
      if (c < n) out[k++] = s + c;
      continue;
    }
    // Hexagonal: a row without shift (even index) meets the shifted rows' columns c − 1 and c
    // (centres at (c − ½)·step and (c + ½)·step); a shifted row meets columns c and c + 1.
    const int c0 = r % 2 == 0 ? c - 1 : c;
    for (const int cc : {c0, c0 + 1})
      if (cc >= 0 && cc < n) out[k++] = s + cc;
  }
  return k;
}

MapGrains reconstruct_grains(const OrientationMap& m, const std::vector<glm::quat>& orientation_in,
                             const std::vector<std::uint8_t>& in_grain,
                             const std::vector<std::vector<glm::dquat>>& symmetry,
                             const GrainReconstructionOptions& opt) {
  const std::size_t n = m.size();
  MapGrains g;
  g.grain_of_point.assign(n, -1);
  g.cluster_of_point.assign(n, -1);
  std::vector<glm::quat> q = orientation_in;  // variants aligned within each grain as it grows
  // cos(θ/2) thresholds: |w| of the relative rotation ≥ this means angle ≤ θ.
  const float cos_boundary = static_cast<float>(std::cos(0.5 * opt.boundary_deg * M_PI / 180.0));
  const float cos_cluster = static_cast<float>(std::cos(0.5 * opt.cluster_deg * M_PI / 180.0));
  std::vector<std::vector<glm::quat>> sym(symmetry.size());
  for (std::size_t p = 0; p < symmetry.size(); ++p)
    for (const glm::dquat& s : symmetry[p]) sym[p].push_back(glm::quat(s));
  std::vector<std::size_t> stack;
  std::size_t nb[6];
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (!in_grain[seed] || g.grain_of_point[seed] >= 0) continue;
    const auto grain = static_cast<std::int32_t>(g.grain_phase.size());
    const std::uint8_t phase = m.phase[seed];
    const std::vector<glm::quat>& ops = sym[phase < sym.size() ? phase : 0];
    g.grain_phase.push_back(phase);
    g.grain_first_cluster.push_back(static_cast<std::int32_t>(g.cluster_orientation.size()));
    g.grain_clusters.push_back(0);
    g.grain_points.push_back(0);
    auto new_cluster = [&](std::size_t i) {
      g.cluster_orientation.push_back(q[i]);
      g.cluster_points.push_back(0);
      ++g.grain_clusters[grain];
      return static_cast<std::int32_t>(g.cluster_orientation.size() - 1);
    };
    auto join = [&](std::size_t i, std::int32_t cluster) {
      g.grain_of_point[i] = grain;
      g.cluster_of_point[i] = cluster;
      ++g.cluster_points[cluster];
      ++g.grain_points[grain];
    };
    join(seed, new_cluster(seed));
    stack.assign(1, seed);
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      const int k = grid_neighbours(m, i, nb);
      for (int t = 0; t < k; ++t) {
        const std::size_t j = nb[t];
        if (!in_grain[j] || g.grain_of_point[j] >= 0 || m.phase[j] != phase) continue;
        const glm::quat a = glm::conjugate(q[i]) * q[j];
        // The identity first (inside a grain the common case), then the other variants.
        float best = std::abs(a.w);
        int best_s = -1;
        if (best < cos_boundary)
          for (std::size_t s = 0; s < ops.size(); ++s) {
            const glm::quat& o = ops[s];
            const float w = std::abs(a.w * o.w - a.x * o.x - a.y * o.y - a.z * o.z);
            if (w > best) {
              best = w;
              best_s = static_cast<int>(s);
            }
          }
        if (best < cos_boundary) continue;
        if (best_s >= 0) q[j] = q[j] * ops[best_s];
        // The cluster: the neighbour's, else one of the grain's latest.
        std::int32_t cl = -1;
        const std::int32_t ci = g.cluster_of_point[i];
        if (std::abs(glm::dot(g.cluster_orientation[ci], q[j])) >= cos_cluster) cl = ci;
        const std::int32_t last = g.grain_first_cluster[grain] + g.grain_clusters[grain] - 1;
        for (std::int32_t c = last; cl < 0 && c >= std::max(g.grain_first_cluster[grain], last - kRecentClusters + 1); --c)
          if (std::abs(glm::dot(g.cluster_orientation[c], q[j])) >= cos_cluster) cl = c;
        if (cl < 0) cl = new_cluster(j);
        join(j, cl);
        stack.push_back(j);
      }
    }
  }
  return g;
}

}  // namespace pmsim
