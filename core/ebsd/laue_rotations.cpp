#include "core/ebsd/laue_rotations.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace pmsim {

namespace {

glm::dquat turn(const glm::dvec3& axis, int fold) {
  return glm::angleAxis(2.0 * M_PI / fold, glm::normalize(axis));
}

// The group the generators span: products until closed (q and −q are one rotation).
std::vector<glm::dquat> closure(const std::vector<glm::dquat>& generators) {
  std::vector<glm::dquat> g{glm::dquat(1, 0, 0, 0)};
  auto known = [&](const glm::dquat& q) {
    for (const glm::dquat& p : g)
      if (std::abs(glm::dot(p, q)) > 1.0 - 1e-9) return true;
    return false;
  };
  for (std::size_t i = 0; i < g.size(); ++i)
    for (const glm::dquat& s : generators) {
      glm::dquat q = g[i] * s;
      if (q.w < 0 || (q.w == 0 && (q.x < 0 || (q.x == 0 && (q.y < 0 || (q.y == 0 && q.z < 0)))))) q = -q;
      if (!known(q)) g.push_back(glm::normalize(q));
    }
  return g;
}

}  // namespace

std::vector<glm::dquat> laue_rotations(std::string_view s) {
  const glm::dvec3 e1{1, 0, 0}, e2{0, 1, 0}, e3{0, 0, 1};
  if (s == "-1") return closure({});
  if (s == "2/m") return closure({turn(e2, 2)});
  if (s == "mmm") return closure({turn(e1, 2), turn(e2, 2)});
  if (s == "4/m") return closure({turn(e3, 4)});
  if (s == "4/mmm") return closure({turn(e3, 4), turn(e1, 2)});
  if (s == "-3") return closure({turn(e3, 3)});
  if (s == "-3m") return closure({turn(e3, 3), turn(e1, 2)});
  if (s == "6/m") return closure({turn(e3, 6)});
  if (s == "6/mmm") return closure({turn(e3, 6), turn(e1, 2)});
  if (s == "m-3") return closure({turn(e1, 2), turn(e2, 2), turn({1, 1, 1}, 3)});
  if (s == "m-3m") return closure({turn(e3, 4), turn({1, 1, 1}, 3)});
  return {};
}

}  // namespace pmsim
