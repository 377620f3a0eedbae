#include "core/microscope/grain_report.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/matrix.hpp>

#include "core/base/input_error.h"
#include "core/base/units.h"
#include "core/crystal/euler_angles.h"
#include "core/crystal/opacity.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/microscope/grain_labels.h"

namespace pmsim {

namespace {

constexpr glm::dvec3 kSectionNormal{0.0, 0.0, 1.0};

// Image angle of a line lying in the section (section frame, z ≈ 0).
double image_angle_deg(const glm::dvec3& t, double stage_deg) {
  return line_direction_deg(degrees(std::atan2(t.y, t.x)) + stage_deg);
}

// The stage angles in [0, 180) that put a vibration direction on the polarizer: the fast
// direction's image angle φ_fast + θ ≡ polarizer (mod 90°), since the slow one is ⟂ it.
std::vector<double> extinction_stages(const SectionOptics& s, double polarizer_deg) {
  if (s.circular) return {};
  const double fast_section_deg = degrees(std::atan2(s.fast.y, s.fast.x));
  double t = std::fmod(polarizer_deg - fast_section_deg, 90.0);
  if (t < 0) t += 90.0;
  if (t >= 90.0) t -= 90.0;
  return {t, t + 90.0};
}

SectionOptics optics_of(const SectionGrain& g, const glm::dmat3& orientation, double wavelength_nm) {
  const glm::dvec3 n = g.crystal ? g.crystal->principal_indices(wavelength_nm) : glm::dvec3(1.0);
  return section_optics(orientation, n, kSectionNormal);
}

GrainSubgrainReport subgrain_report(const SectionGrain& g) {
  GrainSubgrainReport r{g.subgrain_mm, g.subgrain_step_deg, std::nullopt};
  const int half = (g.subgrain_count() - 1) / 2;
  const int within = std::min(half, static_cast<int>(std::floor(g.semi_major_mm / g.subgrain_mm + 0.5)));
  double first = 0.0, lo = 0.0, hi = 0.0;
  for (int k = -within; k <= within; ++k) {
    const SectionOptics s = optics_of(g, g.subgrain_rotation[std::size_t(half + k)] * g.orientation,
                                      kGrainReportIndexWavelengthNm);
    if (s.circular) return r;
    const double a = degrees(std::atan2(s.slow.y, s.slow.x));
    if (k == -within) first = a;
    const double rel = std::remainder(a - first, 180.0);  // lines: modulo 180°
    lo = std::min(lo, rel), hi = std::max(hi, rel);
  }
  r.extinction_sweep_deg = hi - lo;
  return r;
}

// The library's crystallography of a grain placed by its lattice (a mineral with a unit cell and
// a section grain given by euler_deg); else nullptr.
const MineralCrystallography* crystallography_of(const SectionGrain& g) {
  if (!g.lattice_to_section) return nullptr;
  try {
    return find_mineral_crystallography(g.mineral);
  } catch (const InputError&) {
    return nullptr;
  }
}

// Whether a cleavage shows in the section as the cracks section_map draws: a cleavage proper (a
// parting draws none) whose plane is within kCleavageMaxInclinationDeg of vertical.
bool cleavage_shows(const Cleavage& c, const glm::dvec3& normal_in_section) {
  return c.quality != CleavageQuality::Parting &&
         inclination_from_vertical_deg(normal_in_section) <= kCleavageMaxInclinationDeg;
}

}  // namespace

const char* sign_of_elongation_name(SignOfElongation s) {
  switch (s) {
    case SignOfElongation::LengthSlow:
      return "length-slow";
    case SignOfElongation::LengthFast:
      return "length-fast";
    case SignOfElongation::Indeterminate:
      break;
  }
  return "indeterminate";
}

const char* grain_optics_name(const GrainReport& r) { return r.optics_stand_in ? "stand-in" : "published"; }

std::string grain_optics_warning(const GrainReport& r) {
  if (!r.optics_stand_in) return {};
  return std::string("Optics        stand-in: ") + r.mineral +
         "'s file has no published optical orientation, so its indicatrix is placed on the crystal "
         "axes and these extinction angles are not the real mineral's";
}

GrainReport report_grain(const Scene& scene, const SectionMap& section, int label) {
  if (label < 1 || label > static_cast<int>(section.grains.size()))
    throw std::out_of_range("grain label " + std::to_string(label) + " not in 1…" +
                            std::to_string(section.grains.size()));
  const SectionGrain& g = section.grain_by_label(label);
  GrainReport r;
  r.id = label;
  r.mineral = g.mineral;
  r.opaque = g.crystal && is_opaque(*g.crystal, scene.sample.thickness_um);
  r.optics_stand_in = g.optics_stand_in;
  const SectionOptics optics = optics_of(g, g.orientation, kGrainReportIndexWavelengthNm);
  r.extinction_stage_deg = extinction_stages(optics, scene.polarizer_deg);
  if (!optics.circular) r.slow_vibration_deg = image_angle_deg(optics.slow, scene.stage_deg);
  r.retardation_nm = retardation_nm(optics_of(g, g.orientation, kGrainReportRetardationWavelengthNm),
                                    scene.sample.thickness_um);
  // Features in the section frame: the first cleavage trace and the elongation.
  std::optional<glm::dvec3> first_cleavage, elongation;
  if (const MineralCrystallography* m = crystallography_of(g)) {
    const glm::dmat3& lattice_to_section = *g.lattice_to_section;
    try {
      const EulerBunge e = bunge_from_crystal_to_sample(lattice_to_section);
      r.euler_deg = std::array<double, 3>{degrees(e.phi1_rad), degrees(e.Phi_rad), degrees(e.phi2_rad)};
    } catch (const std::invalid_argument&) {
      // An improper or non-orthonormal grain frame has no Euler angles: left empty.
    }
    for (const Cleavage& c : m->cleavage) {
      const glm::dvec3 n = lattice_to_section * plane_normal(m->cell, c.plane);
      if (!cleavage_shows(c, n)) continue;
      try {
        const glm::dvec3 t = plane_trace(kSectionNormal, n);
        if (!first_cleavage) first_cleavage = t;
        r.cleavage_traces_deg.push_back(image_angle_deg(t, scene.stage_deg));
      } catch (const std::invalid_argument&) {
        // The cleavage plane is the section plane: no trace.
      }
    }
    try {
      if (m->habit.elongation)
        elongation = projected_direction(
            kSectionNormal, lattice_to_section * lattice_direction(m->cell, *m->habit.elongation));
      else if (m->habit.tabular)
        elongation =
            plane_trace(kSectionNormal, lattice_to_section * plane_normal(m->cell, *m->habit.tabular));
    } catch (const std::invalid_argument&) {
      // Seen end-on (elongation along the normal) or flat on the tabular plane: equant in section.
    }
  } else if (g.elongated) {
    // No crystallography: the grain's drawn shape (SectionGrain::elongation_rad) is its elongation.
    elongation = glm::dvec3(std::cos(g.elongation_rad), std::sin(g.elongation_rad), 0.0);
  }
  if (elongation) {
    r.elongation_deg = image_angle_deg(*elongation, scene.stage_deg);
    const SignOfElongation s = sign_of_elongation(optics, *elongation);
    if (s != SignOfElongation::Indeterminate) r.sign_of_elongation = s;
  }
  const std::optional<glm::dvec3> feature = first_cleavage ? first_cleavage : elongation;
  if (feature && !optics.circular) r.extinction_angle_deg = extinction_from(optics, *feature).angle_deg;
  if (g.vein) r.alteration = GrainAlterationReport{g.vein->mineral, g.vein->width_mm};
  if (const auto& in = g.inclusions) {
    // Trails at growth fraction s run at trail + rotation·(1 − s) (section_map.h): s = within at the rim.
    const auto trail = [&](double s) {
      const double a = in->trail_rad + in->rotation_rad * (1.0 - s);
      return image_angle_deg({std::cos(a), std::sin(a), 0.0}, scene.stage_deg);
    };
    r.inclusions = GrainInclusionReport{in->mineral, in->size_mm, trail(in->within), trail(0.0),
                                        degrees(in->rotation_rad * in->within)};
    if (!in->needles.empty()) r.inclusions->habit = "needle";
    if (in->wedges) r.inclusions->habit = "wedge";
    if (in->halo) {
      r.inclusions->halo_radius_mm = in->halo->radius_mm;
      r.inclusions->halo_darkening = in->halo->darkening;
    }
  }
  if (const auto& o = g.overgrowth) {
    r.overgrowth = GrainOvergrowthReport{o->habit_scale, g.detrital_section_radius_mm(), o->dust ? o->dust->mineral : ""};
  }
  if (const auto& m = g.myrmekite) {
    GrainMyrmekiteReport my{m->host, 0, m->quartz_mineral, {}};
    if (const MyrmekiteBulbs* b = section.myrmekite_bulbs())
      my.bulbs = b->count_of(label - 1);
    const glm::dvec3 n = m->quartz->principal_indices(kGrainReportIndexWavelengthNm);
    my.quartz_extinction_stage_deg =
        extinction_stages(section_optics(m->quartz_orientation, n, kSectionNormal), scene.polarizer_deg);
    r.myrmekite = std::move(my);
  }
  if (r.opaque) {
    // Black in every light: no extinction, interference colour or slow direction to observe.
    r.extinction_stage_deg.clear();
    r.slow_vibration_deg.reset();
    r.retardation_nm = 0.0;
    r.extinction_angle_deg.reset();
    r.sign_of_elongation.reset();
    if (g.twinned) r.twin = GrainTwinReport{g.twin_law, {}, g.cross_twin ? g.cross_twin->law : "", {}};
    if (!g.subgrain_rotation.empty()) r.subgrains = GrainSubgrainReport{g.subgrain_mm, g.subgrain_step_deg, std::nullopt};
    return r;
  }
  if (!g.subgrain_rotation.empty()) r.subgrains = subgrain_report(g);
  if (g.twinned) {
    r.twin = GrainTwinReport{};
    r.twin->law = g.twin_law;
    r.twin->extinction_stage_deg =
        extinction_stages(optics_of(g, g.twin_orientation, kGrainReportIndexWavelengthNm), scene.polarizer_deg);
    if (const auto& x = g.cross_twin) {
      r.twin->cross_law = x->law;
      r.twin->cross_extinction_stage_deg =
          extinction_stages(optics_of(g, x->op * g.orientation, kGrainReportIndexWavelengthNm), scene.polarizer_deg);
    }
  }
  return r;
}

std::vector<GrainReport> report_grains(const Scene& scene, const SectionMap& section,
                                       const std::vector<std::uint16_t>& labels) {
  const std::vector<long long> counts = label_counts(labels, section);
  std::vector<GrainReport> out;
  for (std::size_t k = 1; k < counts.size(); ++k)
    if (counts[k] > 0) {
      out.push_back(report_grain(scene, section, static_cast<int>(k)));
      out.back().area_px = counts[k];
    }
  return out;
}

}  // namespace pmsim
