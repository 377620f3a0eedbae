#include "core/microscope/modal_units.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/base/units.h"
#include "core/microscope/evaluation_plan.h"
#include "core/microscope/optical_train.h"
#include "core/microscope/direction_modal_table.h"
#include "core/microscope/radial_modal_table.h"

namespace pmsim {

double modal_thickness_scale(const EvalUnit& unit, const OpticalDomain& domain) {
  return domain.crystal && unit.thickness_um > 0.0 ? unit.thickness_um / domain.thickness_um : 1.0;
}

std::optional<ModalUnits> fit_modal_units(const EvaluationPlan& plan, const ExactnessCriteria& exact,
                                          const std::atomic<bool>* cancel, bool keep_fits) {
  const Scene& scene = plan.scene();
  const std::vector<OpticalDomain>& domains = plan.domains();
  const std::vector<EvalUnit>& units = plan.units();
  ModalUnits out;
  out.dirs_per_unit = plan.cone_dirs().empty() ? 1 : static_cast<int>(plan.cone_dirs().size());
  const int dirs_per_unit = out.dirs_per_unit;
  out.terms.resize(units.size() * dirs_per_unit);
  if (keep_fits) out.fits.resize(out.terms.size(), identity_modal_fit());
  out.unit_exact.assign(units.size(), 0);
  const TrainState train = make_train(scene, plan.compensator(), 550.0);  // its directions only
  // Anchors prepared once per domain that a unit shows (a coarse pass over an EBSD map misses
  // some of its 10⁴ domains). In parallel over those domains (each anchor independent, the same
  // values in any order).
  std::vector<char> shown(domains.size(), 0);
  for (const EvalUnit& u : units) shown[u.domain] = 1;
  std::vector<int> todo;
  for (std::size_t d = 0; d < domains.size(); ++d)
    if (shown[d] && domains[d].crystal) todo.push_back(static_cast<int>(d));
  std::vector<std::array<PreparedPlate, 3>> anchors(domains.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, todo.size(), 64), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t j = r.begin(); j != r.end(); ++j)
      for (int a = 0; a < 3; ++a) anchors[todo[j]][a] = plan.prepare(todo[j], ModalFit::kAnchorNm[a]);
  });
  // A conoscopic figure of a uniaxial plate cut ⟂ its optic axis: a radial table of fits.
  RadialModalTable radial;
  // The table costs kEntries fits plus its checks; the direct way one fit per unit: the table
  // wins from about twice as many units (a 64² glance of a figure has ~3 200).
  if (scene.mode == ViewMode::Cono && scene.bertrand_in && units.size() > 2 * RadialModalTable::kEntries) {
    const int dom = units.front().domain;
    const OpticalDomain& domain = domains[dom];
    bool one_domain = true;
    double s_max = 0.0;
    for (const EvalUnit& u : units) {
      one_domain = one_domain && u.domain == dom;
      s_max = std::max(s_max, std::hypot(u.k_air.x, u.k_air.y));
    }
    if (one_domain && domain.crystal && domain.crystal->symmetry() == CrystalSymmetry::Uniaxial &&
        std::fabs(domain.crystal_to_lab[2].z) > 1.0 - 1e-12)
      out.radial_table = radial.build(anchors[dom].data(), std::min(1.0, s_max * (1.0 + 1e-9)));
  }
  // Any other figure of one plate (a biaxial one, or a uniaxial one tilted): a table over the
  // direction, when it replaces at least 4× as many fits as it costs (so the small figures of the
  // previews and the golden images keep their per-pixel fits).
  DirectionModalTable by_direction;
  if (!out.radial_table && scene.mode == ViewMode::Cono && scene.bertrand_in && !units.empty()) {
    const int dom = units.front().domain;
    const OpticalDomain& domain = domains[dom];
    bool one_domain = true;
    double s_max = 0.0;
    for (const EvalUnit& u : units) {
      one_domain = one_domain && u.domain == dom && u.thickness_um == units.front().thickness_um;
      s_max = std::max(s_max, std::hypot(u.k_air.x, u.k_air.y));
    }
    s_max = std::min(0.999, s_max * (1.0 + 1e-9));
    if (one_domain && domain.crystal && !domain.crystal->absorbing() && !domain.crystal->optically_active() &&
        units.size() >= 4 * static_cast<std::size_t>(DirectionModalTable::nodes_needed(s_max))) {
      out.direction_table = by_direction.build(anchors[dom].data(), s_max, cancel);
      if (cancel && *cancel) return std::nullopt;
    }
  }
  const bool use_radial = out.radial_table;
  const bool use_direction = out.direction_table;
  std::atomic<bool> stop{false};
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, units.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
        if (stop || (cancel && *cancel)) {
          stop = true;
          return;
        }
        for (std::size_t u = r.begin(); u != r.end(); ++u) {
          const EvalUnit& unit = units[u];
          const OpticalDomain& dom = domains[unit.domain];
          for (int d = 0; d < plan.dirs_of(unit); ++d) {
            glm::dmat2 jc, jo;
            plan.lens_jones(plan.dir(unit, d), jc, jo);
            const glm::dmat2* pc = &jc;
            const glm::dmat2* po = &jo;
            const std::size_t at = u * dirs_per_unit + d;
            if (!dom.crystal || unit.thickness_um <= 0.0) {
              out.terms[at] = identity_modal_terms(train, pc, po);
              continue;
            }
            ModalFit fit;
            if (use_radial)
              fit = radial.at(plan.dir(unit, d));
            else if (use_direction)
              fit = by_direction.at(plan.dir(unit, d));
            else
              fit.fit(anchors[unit.domain].data(), plan.dir(unit, d));
            if (exact.absorbing_in_field && dom.crystal->absorbing()) out.unit_exact[u] = 1;
            if (exact.optically_active_near_axis && dom.crystal->optically_active()) {
              // Elliptical modes have ellipticity ≈ (rotation)/(linear phase);
              // the linear model's intensity error is its square: keep it below
              // ~1e-3 (rotation < linear phase / 30) or go exact.
              const double rot = std::fabs(dom.crystal->rotatory_power_rad_per_um(400.0)) * unit.thickness_um;
              const double lin =
                  2.0 * kPi * fit.retardation_nm(400.0) * unit.thickness_um / dom.thickness_um / 400.0;
              if (lin < 30.0 * rot) out.unit_exact[u] = 1;
            }
            out.terms[at] = make_modal_terms(fit, train, modal_thickness_scale(unit, dom), pc, po);
            if (keep_fits) out.fits[at] = fit;
          }
        }
      });
  if (stop) return std::nullopt;
  return out;
}

}  // namespace pmsim
