#include "core/microscope/radial_modal_table.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

namespace pmsim {

bool RadialModalTable::build(const PreparedPlate anchors[3], double s_max) {
  du_ = std::max(1e-12, s_max * s_max) / (kEntries - 1);
  e_.resize(kEntries);
  std::vector<char> good(kEntries, 0);
  int kind = -1;  // 0: e1 radial, 1: e1 tangential
  auto dir = [&](int i) {
    const double s = std::sqrt(i * du_), c = std::sqrt(std::max(0.0, 1.0 - s * s));
    return glm::dvec3{s, 0.0, c};
  };
  // The fits (the cost: three mode solutions each) over the cores; a restart waits for this.
  std::vector<ModalFit> fits(kEntries);
  tbb::parallel_for(tbb::blocked_range<int>(0, kEntries, 32), [&](const tbb::blocked_range<int>& rg) {
    for (int i = rg.begin(); i != rg.end(); ++i) fits[i].fit(anchors, dir(i));
  });
  for (int i = 0; i < kEntries; ++i) {
    const glm::dvec3 k = dir(i), r{k.z, 0.0, -k.x}, t{0.0, 1.0, 0.0};
    glm::dvec3 a, b;
    transverse_basis(k, a, b);
    const ModalFit& fit = fits[i];
    Entry& E = e_[i];
    bool ok = true;
    for (int q = 0; q < 3; ++q) {
      E.gamma[q] = fit.gamma_at_anchor(q);
      E.t1[q] = fit.t1_at_anchor(q);
      E.t2[q] = fit.t2_at_anchor(q);
      const glm::dvec2 v[2] = {fit.e1_at_anchor(q), fit.e2_at_anchor(q)};
      glm::dvec2* out[2] = {&E.e1[q], &E.e2[q]};
      for (int m = 0; m < 2; ++m) {
        const glm::dvec3 e3 = v[m].x * a + v[m].y * b;
        glm::dvec2 rt{glm::dot(e3, r), glm::dot(e3, t)};
        const double len = glm::length(rt);
        rt = len > 1e-300 ? rt / len : glm::dvec2(1.0, 0.0);
        // Canonical sign: the larger component positive (a mode is defined up to sign).
        if ((std::fabs(rt.x) >= std::fabs(rt.y) ? rt.x : rt.y) < 0) rt = -rt;
        *out[m] = rt;
      }
      const int kq = std::fabs(E.e1[q].x) > 0.9999 ? 0 : (std::fabs(E.e1[q].y) > 0.9999 ? 1 : 2);
      const bool orth = std::fabs(glm::dot(E.e1[q], E.e2[q])) < 1e-4;
      if (kq == 2 || !orth || (kind >= 0 && kq != kind && i > 0 && good[i - 1])) ok = false;
      if (ok && q == 2) kind = kq;
    }
    good[i] = ok;
  }
  // Near the axis the modes are degenerate and their directions arbitrary; there Γ is tiny and
  // the directions are taken from the first radial/tangential entry outwards.
  if (!good[kEntries - 1]) return false;
  for (int i = kEntries - 2; i >= 0; --i) {
    if (good[i]) {
      const int kq = std::fabs(e_[i].e1[0].x) > 0.9999 ? 0 : 1;
      const int kn = std::fabs(e_[i + 1].e1[0].x) > 0.9999 ? 0 : 1;
      if (kq != kn) return false;  // the fast mode changes kind: not a simple uniaxial figure
      continue;
    }
    for (int q = 0; q < 3; ++q)
      if (std::fabs(e_[i].gamma[q]) > 0.5) return false;  // ≥ 0.008 rad at 400 nm: must be right
    for (int q = 0; q < 3; ++q) {
      e_[i].e1[q] = e_[i + 1].e1[q];
      e_[i].e2[q] = e_[i + 1].e2[q];
    }
  }
  return true;
}

ModalFit RadialModalTable::at(const glm::dvec3& k) const {
  const double s2 = k.x * k.x + k.y * k.y, s = std::sqrt(s2);
  const double pos = s2 / du_;
  const int i0 = std::clamp(static_cast<int>(pos), 0, kEntries - 2);
  const double f = pos - i0, g = 1.0 - f;
  const Entry& A = e_[i0];
  const Entry& B = e_[i0 + 1];
  const double cp = s > 0 ? k.x / s : 1.0, sp = s > 0 ? k.y / s : 0.0;
  const glm::dvec3 r{cp * k.z, sp * k.z, -s}, t{-sp, cp, 0.0};
  glm::dvec3 a, b;
  transverse_basis(k, a, b);
  const double ra = glm::dot(r, a), ta = glm::dot(t, a), rb = glm::dot(r, b), tb = glm::dot(t, b);
  auto turn = [&](const glm::dvec2& p, const glm::dvec2& q) {
    const glm::dvec2 rt = g * p + f * q;
    const glm::dvec2 v{rt.x * ra + rt.y * ta, rt.x * rb + rt.y * tb};
    const double len = glm::length(v);
    return len > 1e-300 ? v / len : glm::dvec2(1.0, 0.0);
  };
  double gamma[3], t1[3], t2[3];
  glm::dvec2 e1[3], e2[3];
  for (int q = 0; q < 3; ++q) {
    gamma[q] = g * A.gamma[q] + f * B.gamma[q];
    t1[q] = g * A.t1[q] + f * B.t1[q];
    t2[q] = g * A.t2[q] + f * B.t2[q];
    e1[q] = turn(A.e1[q], B.e1[q]);
    e2[q] = turn(A.e2[q], B.e2[q]);
  }
  ModalFit fit;
  fit.assign(gamma, e1, e2, t1, t2);
  return fit;
}

}  // namespace pmsim
