#include "core/microscope/direction_modal_table.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <tbb/parallel_for.h>

namespace pmsim {

namespace {

// Self-check tolerances. |ΔB| ≤ 0.5 nm: an error of Γ or of Γ·2θ of 0.5 nm moves the interference
// phase by at most 2π·0.5/400 = 0.008 rad at 400 nm (intensity error ≤ 0.8 %). |Δt| ≤ 1e-3: the
// mode transmissions are ~0.9 (Fresnel at two faces); 1e-3 of amplitude is 0.2 % of intensity.
constexpr double kMaxBErrorNm = 0.5;
constexpr double kMaxTError = 1e-3;
constexpr int kCheckStride = 4;  // every 4th cell centre in each direction is checked

glm::dvec3 direction(double kx, double ky) {
  return {kx, ky, std::sqrt(std::max(0.0, 1.0 - kx * kx - ky * ky))};
}

// The mode direction of a birefringence vector: half its angle.
glm::dvec2 mode_of(const double b[2], const glm::dvec2& fallback) {
  const double len = std::sqrt(b[0] * b[0] + b[1] * b[1]);
  if (len < 1e-12) return fallback;
  const double c2 = b[0] / len, s2 = b[1] / len;  // cos 2θ, sin 2θ
  // cos θ = sqrt((1 + cos 2θ)/2), sin θ = sin 2θ/(2 cos θ), on the branch cos θ ≥ 0.
  const double c = std::sqrt(std::max(0.0, 0.5 * (1.0 + c2)));
  if (c < 1e-8) return {0.0, 1.0};
  return {c, s2 / (2.0 * c)};
}

// Catmull–Rom weights of the nodes at −1, 0, 1, 2 for a point at t ∈ [0, 1) of the cell (cubic
// convergence, exact for quadratics; interpolating, so the nodes' values are kept).
void catmull_rom(double t, double w[4]) {
  const double t2 = t * t, t3 = t2 * t;
  w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
  w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
  w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
  w[3] = 0.5 * (t3 - t2);
}

}  // namespace

int DirectionModalTable::nodes_needed(double s_max) {
  DirectionModalTable t;
  t.set_grid(s_max);
  if (!t.fits_aperture()) return 0;
  int n = 0;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) n += t.in_reach(i, j);
  return n;
}

// Nodes from −s_max − 2h to s_max + 2h: the 4×4 nodes of every cell that meets the disk.
void DirectionModalTable::set_grid(double s_max) {
  s_max_ = std::max(1e-6, s_max);
  h_ = 2.0 * s_max_ / (kSide - 5);
  origin_ = -s_max_ - 2.0 * h_;
}

// Every node a pixel can use is a real direction in air (sin θ < 1).
bool DirectionModalTable::fits_aperture() const { return s_max_ + 3.0 * h_ < 0.999; }

// A node is needed when a cell meeting the disk uses it: within s_max + 2√2·h of the centre.
bool DirectionModalTable::in_reach(int i, int j) const {
  const double kx = origin_ + i * h_, ky = origin_ + j * h_;
  const double r = s_max_ + 3.0 * h_;
  return kx * kx + ky * ky <= r * r;
}

DirectionModalTable::Node DirectionModalTable::node_of(const ModalFit& fit) {
  Node n;
  for (int a = 0; a < 3; ++a) {
    const double g = fit.gamma_at_anchor(a);
    const glm::dvec2 e1 = fit.e1_at_anchor(a), e2 = fit.e2_at_anchor(a);
    n.b1[a][0] = g * (e1.x * e1.x - e1.y * e1.y);
    n.b1[a][1] = g * (2.0 * e1.x * e1.y);
    n.b2[a][0] = g * (e2.x * e2.x - e2.y * e2.y);
    n.b2[a][1] = g * (2.0 * e2.x * e2.y);
    n.t1[a] = fit.t1_at_anchor(a);
    n.t2[a] = fit.t2_at_anchor(a);
  }
  return n;
}

bool DirectionModalTable::build(const PreparedPlate anchors[3], double s_max, const std::atomic<bool>* cancel) {
  set_grid(s_max);
  if (!fits_aperture()) return false;
  n_.assign(static_cast<std::size_t>(kSide) * kSide, Node{});
  std::atomic<bool> stop{false};
  tbb::parallel_for(tbb::blocked_range<int>(0, kSide, 4), [&](const tbb::blocked_range<int>& r) {
    if (stop || (cancel && *cancel)) {
      stop = true;
      return;
    }
    for (int j = r.begin(); j != r.end(); ++j)
      for (int i = 0; i < kSide; ++i) {
        if (!in_reach(i, j)) continue;
        ModalFit fit;
        fit.fit(anchors, direction(origin_ + i * h_, origin_ + j * h_));
        n_[static_cast<std::size_t>(j) * kSide + i] = node_of(fit);
      }
  });
  if (stop) return false;
  // The check: exact fits at cell centres inside the disk against the interpolation.
  const int cells = (kSide - 1 + kCheckStride - 1) / kCheckStride;  // rows of checked cells
  std::vector<double> berr(cells, 0.0), terr(cells, 0.0);
  tbb::parallel_for(tbb::blocked_range<int>(0, cells, 1), [&](const tbb::blocked_range<int>& r) {
    for (int cj = r.begin(); cj != r.end(); ++cj)
      for (int ci = 0; ci * kCheckStride < kSide - 1; ++ci) {
        const double kx = origin_ + (ci * kCheckStride + 0.5) * h_;
        const double ky = origin_ + (cj * kCheckStride + 0.5) * h_;
        if (kx * kx + ky * ky > s_max_ * s_max_) continue;
        const glm::dvec3 k = direction(kx, ky);
        ModalFit exact;
        exact.fit(anchors, k);
        const Node e = node_of(exact), t = node_of(at(k));
        for (int a = 0; a < 3; ++a) {
          for (int c = 0; c < 2; ++c)
            berr[cj] = std::max({berr[cj], std::fabs(e.b1[a][c] - t.b1[a][c]), std::fabs(e.b2[a][c] - t.b2[a][c])});
          terr[cj] = std::max({terr[cj], std::fabs(e.t1[a] - t.t1[a]), std::fabs(e.t2[a] - t.t2[a])});
        }
      }
  });
  check_b_nm_ = *std::max_element(berr.begin(), berr.end());
  check_t_ = *std::max_element(terr.begin(), terr.end());
  return check_b_nm_ <= kMaxBErrorNm && check_t_ <= kMaxTError;
}

ModalFit DirectionModalTable::at(const glm::dvec3& k) const {
  const double px = (k.x - origin_) / h_, py = (k.y - origin_) / h_;
  const int i0 = std::clamp(static_cast<int>(px), 1, kSide - 3);
  const int j0 = std::clamp(static_cast<int>(py), 1, kSide - 3);
  double wx[4], wy[4];
  catmull_rom(px - i0, wx);
  catmull_rom(py - j0, wy);
  double w[16];
  const Node* c[16];
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) {
      w[4 * b + a] = wx[a] * wy[b];
      c[4 * b + a] = &n_[static_cast<std::size_t>(j0 - 1 + b) * kSide + (i0 - 1 + a)];
    }
  // The 16 nodes' 18 values summed as flat arrays (contiguous, so the compiler vectorises it).
  constexpr int kValues = sizeof(Node) / sizeof(double);
  static_assert(kValues == 18);
  double acc[kValues] = {};
  for (int q = 0; q < 16; ++q) {
    double v[kValues];
    std::memcpy(v, c[q], sizeof v);
    for (int i = 0; i < kValues; ++i) acc[i] += w[q] * v[i];
  }
  Node sum;
  std::memcpy(&sum, acc, sizeof sum);
  double gamma[3], t1[3], t2[3];
  glm::dvec2 e1[3], e2[3];
  for (int a = 0; a < 3; ++a) {
    const double* b1 = sum.b1[a];
    const double* b2 = sum.b2[a];
    t1[a] = sum.t1[a];
    t2[a] = sum.t2[a];
    gamma[a] = std::sqrt(b1[0] * b1[0] + b1[1] * b1[1]);  // |B| ≤ 1e7 nm: no overflow, hypot is slow
    e1[a] = mode_of(b1, {1.0, 0.0});
    e2[a] = mode_of(b2, {-e1[a].y, e1[a].x});
    // One branch across the anchors, as ModalFit::fit keeps them (the Lagrange interpolation in
    // the wavelength must not pass through zero).
    if (a > 0) {
      if (e1[a].x * e1[0].x + e1[a].y * e1[0].y < 0) e1[a] = -e1[a];
      if (e2[a].x * e2[0].x + e2[a].y * e2[0].y < 0) e2[a] = -e2[a];
    }
  }
  ModalFit fit;
  fit.assign(gamma, e1, e2, t1, t2);
  return fit;
}

}  // namespace pmsim
