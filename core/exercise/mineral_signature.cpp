#include "core/exercise/mineral_signature.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include <glm/geometric.hpp>

#include "core/base/build_cache.h"
#include "core/crystal/crystal.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/crystal/opacity.h"
#include "core/crystal/section_optics.h"
#include "core/exercise/exercise_kind.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"
#include "core/spectrum/reference_wavelengths.h"

namespace pmsim {

namespace {

constexpr double kIndexNm = kMineralTableDNm;
constexpr double kThicknessUm = 30.0;
constexpr double kVisibleDeltaE = 5.0;
// Cleavages whose planes lie within 30° of the section's normal show as traces (section_map.h).
constexpr double kTraceSin = 0.5;

double deg(double rad) { return rad * 180.0 / std::numbers::pi; }

std::array<glm::dvec3, 3> axis_colours(const Crystal& c, double thickness_um) {
  std::array<glm::dvec3, 3> xyz{};
  for (double l = kVisibleMinNm; l <= kVisibleMaxNm; l += 5.0) {
    const glm::dvec3 w = observer_weight(Illuminant::D65, l) * 5.0;
    const glm::dvec3 mu = c.principal_absorption_per_um(l);
    for (int a = 0; a < 3; ++a) xyz[std::size_t(a)] += std::exp(-mu[a] * thickness_um) * w;
  }
  const glm::dvec3 white = illuminant_white_xyz(Illuminant::D65);
  std::array<glm::dvec3, 3> lab{};
  for (int a = 0; a < 3; ++a) lab[std::size_t(a)] = xyz_to_lab(xyz[std::size_t(a)], white);
  return lab;
}

void colour_facts(const Crystal& c, MineralSignature& s) {
  if (!c.absorbing()) return;
  const auto lab = axis_colours(c, kThicknessUm);
  for (const auto& l : lab) s.colour_delta_e = std::max(s.colour_delta_e, glm::length(l - glm::dvec3(100, 0, 0)));
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b)
      s.pleochroism_delta_e = std::max(s.pleochroism_delta_e, glm::length(lab[std::size_t(a)] - lab[std::size_t(b)]));
  s.coloured = s.colour_delta_e > kVisibleDeltaE;
  s.pleochroic = s.pleochroism_delta_e > kVisibleDeltaE;
}

glm::dvec3 any_perpendicular(const glm::dvec3& d) {
  const glm::dvec3 t = std::abs(d.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(d, t));
}

// Whether a vibration direction bisects two of the traces (angle > 10°) within kParallelExtinctionDeg.
bool symmetric_to_traces(const SectionOptics& so, const std::vector<glm::dvec3>& traces) {
  for (std::size_t i = 0; i < traces.size(); ++i)
    for (std::size_t j = i + 1; j < traces.size(); ++j) {
      if (trace_angle_deg(traces[i], traces[j]) < 10.0) continue;
      glm::dvec3 b = traces[j];
      if (glm::dot(traces[i], b) < 0) b = -b;
      const glm::dvec3 bis1 = glm::normalize(traces[i] + b), bis2 = glm::normalize(glm::cross(so.normal, bis1));
      for (const glm::dvec3& bis : {bis1, bis2})
        if (is_parallel_extinction(extinction_from(so, bis).angle_deg)) return true;
    }
  return false;
}

// Sections that show the feature, one a degree about the zone axis, and what each shows.
void extinction_facts(const Crystal& c, const MineralCrystallography& m, MineralSignature& s) {
  if (!m.orientation) return;
  std::optional<glm::dvec3> zone;     // the sections' normals are ⟂ this
  bool feature_is_zone = false;       // the feature is the zone axis itself (a prism's length)
  if (m.habit.elongation) {
    zone = glm::normalize(lattice_direction(m.cell, *m.habit.elongation));
    feature_is_zone = true;
    s.feature = "the elongation " + direction_text(*m.habit.elongation);
  } else if (m.habit.tabular) {
    zone = glm::normalize(plane_normal(m.cell, *m.habit.tabular));
    s.feature = "the trace of the tabular face " + miller_text(*m.habit.tabular);
  } else if (!m.cleavage.empty()) {
    zone = glm::normalize(plane_normal(m.cell, m.cleavage.front().plane));
    s.feature = "the cleavage trace " + miller_text(m.cleavage.front().plane);
  } else {
    return;
  }
  const glm::dvec3 idx = c.principal_indices(kIndexNm);
  const glm::dvec3 u = any_perpendicular(*zone), v = glm::cross(*zone, u);
  double lo = 90.0, hi = 0.0;
  for (int k = 0; k < 180; ++k) {
    const double phi = k * std::numbers::pi / 180.0;
    const glm::dvec3 n = std::cos(phi) * u + std::sin(phi) * v;
    const SectionOptics so = section_optics(m.indicatrix_axes, idx, n);
    if (so.circular) continue;
    const glm::dvec3 feature = feature_is_zone ? *zone : plane_trace(n, *zone);
    const double a = extinction_from(so, feature).angle_deg;
    lo = std::min(lo, a), hi = std::max(hi, a);
    s.extinction_types.insert(is_parallel_extinction(a) ? "parallel" : "inclined");
    if (m.habit.elongation || m.habit.tabular) {
      const SignOfElongation e = sign_of_elongation(so, feature);
      if (e != SignOfElongation::Indeterminate)
        s.elongation_signs.insert(e == SignOfElongation::LengthSlow ? "length-slow" : "length-fast");
    }
  }
  // Symmetric extinction: in any section (the zone's and the one ⟂ the zone axis, the basal
  // section of a prism) where two cleavage traces show and a vibration direction bisects them.
  std::vector<glm::dvec3> normals{*zone};
  for (int k = 0; k < 180; k += 5) normals.push_back(std::cos(k * std::numbers::pi / 180) * u + std::sin(k * std::numbers::pi / 180) * v);
  for (const glm::dvec3& n : normals) {
    std::vector<glm::dvec3> traces;
    for (const Cleavage& cl : m.cleavage) {
      const glm::dvec3 p = glm::normalize(plane_normal(m.cell, cl.plane));
      if (std::abs(glm::dot(p, n)) <= kTraceSin) traces.push_back(plane_trace(n, p));
    }
    const SectionOptics so = section_optics(m.indicatrix_axes, idx, n);
    if (!so.circular && symmetric_to_traces(so, traces)) s.extinction_types.insert("symmetric");
  }
  if (hi >= lo) s.extinction_min_deg = lo, s.extinction_max_deg = hi;
}

}  // namespace

std::array<glm::dvec3, 3> principal_colours_lab(const std::string& mineral, double thickness_um) {
  return axis_colours(find_mineral(mineral), thickness_um);
}

const char* relief_class_name(ReliefClass r) {
  switch (r) {
    case ReliefClass::Low: return "low";
    case ReliefClass::Moderate: return "moderate";
    case ReliefClass::High: return "high";
    case ReliefClass::VeryHigh: return "very_high";
  }
  return "low";
}

ReliefClass relief_class(double n) {
  const double d = std::abs(n - kReliefMediumIndex);
  return d < 0.04 ? ReliefClass::Low : d < 0.12 ? ReliefClass::Moderate : d < 0.22 ? ReliefClass::High : ReliefClass::VeryHigh;
}

int max_interference_order(double birefringence, double thickness_um) {
  const double gamma_nm = 1000.0 * thickness_um * birefringence;
  return gamma_nm <= 0.0 ? 0 : std::max(1, int(std::ceil(gamma_nm / kOrderWavelengthNm)));
}

MineralSignature mineral_signature(const std::string& mineral) {
  const Crystal& c = find_mineral(mineral);
  MineralSignature s;
  s.mineral = mineral;
  const glm::dvec3 n = c.principal_indices(kIndexNm);
  s.n_min = std::min({n.x, n.y, n.z});
  s.n_max = std::max({n.x, n.y, n.z});
  s.birefringence = s.n_max - s.n_min;
  for (double x = s.n_min; x < s.n_max + 1e-9; x += 0.002) s.relief.insert(relief_class(std::min(x, s.n_max)));
  s.relief.insert(relief_class(s.n_max));
  if (s.n_max > kReliefMediumIndex) s.relief_signs.push_back("positive");
  if (s.n_min < kReliefMediumIndex) s.relief_signs.push_back("negative");
  switch (c.symmetry()) {
    case CrystalSymmetry::Isotropic: s.character = "isotropic"; break;
    case CrystalSymmetry::Uniaxial:
      s.character = "uniaxial";
      s.optic_sign = n.z > n.x ? "positive" : "negative";
      break;
    case CrystalSymmetry::Biaxial: {
      s.character = "biaxial";
      const double two_vz = optic_angle_2v_rad(n.x, n.y, n.z);
      s.optic_sign = two_vz < std::numbers::pi / 2 ? "positive" : "negative";
      s.two_v_deg = deg(std::min(two_vz, std::numbers::pi - two_vz));
      break;
    }
  }
  s.opaque = is_opaque(c, kThicknessUm);
  if (!s.opaque) colour_facts(c, s);  // an opaque grain has no colour to see: it is black
  if (const MineralCrystallography* m = find_mineral_crystallography(mineral)) {
    s.cleavages = m->cleavage.size();
    for (const TwinLaw& t : m->twins)
      if (std::find(s.twin_laws.begin(), s.twin_laws.end(), t.law) == s.twin_laws.end()) s.twin_laws.push_back(t.law);
    extinction_facts(c, *m, s);
  }
  return s;
}

const MineralSignature& cached_mineral_signature(const std::string& mineral) {
  static BuildCache<std::string, MineralSignature> cache;
  return *cache.get(mineral, [&] { return std::make_shared<const MineralSignature>(mineral_signature(mineral)); });
}

const std::vector<MineralSignature>& library_signatures() {
  static const std::vector<MineralSignature> all = [] {
    std::vector<MineralSignature> v;
    for (const std::string& name : mineral_names()) v.push_back(mineral_signature(name));
    return v;
  }();
  return all;
}

}  // namespace pmsim
