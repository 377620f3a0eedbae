#include "core/microscope/section_map.h"
#include "core/microscope/section_reorient.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <map>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <nlohmann/json.hpp>

#include "core/base/build_cache.h"
#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/base/units.h"
#include "core/crystal/axis_rotation.h"
#include "core/crystal/euler_angles.h"
#include "core/crystal/lattice.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/crystal/section_optics.h"
#include "core/microscope/sample_source.h"
#include "core/texture/rock_growth.h"
#include "core/texture/rock_recipe.h"

namespace pmsim {

namespace {

// Squared normalised ellipse distance q of p from grain g's centre: 1 on the grain's ellipse.
inline double ellipse_q(const SectionGrain& g, const glm::dvec2& p) {
  const double dx = p.x - g.centre_mm.x, dy = p.y - g.centre_mm.y;
  return g.metric_xx * dx * dx + 2.0 * g.metric_xy * dx * dy + g.metric_yy * dy * dy;
}

// The distance the tiling minimises: cell_scale·(q − cell_offset). With cell_scale = ab (the
// product of the semi-axes) and offset 1 it is the power distance |A(p − c)|² − ab of an
// area-preserving shear A (det 1): a power diagram, whose boundaries are straight between grains
// of the same shape, like the polygonal grain boundaries of a rock. Old-format files use q itself
// (scale 1, offset 0: the multiplicatively weighted cells they were made with).
inline double grain_distance2(const SectionGrain& g, const glm::dvec2& p) {
  return g.cell_scale * (ellipse_q(g, p) - g.cell_offset);
}

// grain_distance2 ≥ metric_min·|p − centre|² − cell_scale·cell_offset (metric_min: the smallest
// eigenvalue of the metric, 1/semi_major², times the scale).
inline double metric_min(const SectionGrain& g) { return g.cell_scale / (g.semi_major_mm * g.semi_major_mm); }
inline double metric_floor(const SectionGrain& g) { return g.cell_scale * g.cell_offset; }

// Deterministic hash to [0, 1) (splitmix64 finaliser, Steele et al. 2014): the crack jitter must be
// the same in every render and every thread.
double hash01(std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t d = 0) {
  std::uint64_t z = a * 0x9E3779B97F4A7C15ull ^ (b + 0x632BE59BD9B4E019ull) * 0xBF58476D1CE4E5B9ull ^
                    (c + 0x2545F4914F6CDD1Dull) * 0x94D049BB133111EBull ^ d * 0xD6E8FEB86659FD93ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

}  // namespace

DomainPart SectionMap::domain_part(int d) const {
  DomainPart part;
  if (d < 2 || domain_grain_[d] < 0) return part;
  part.grain = domain_grain_[d];
  const SectionGrain& g = grains[part.grain];
  const int per_twin = g.twin_individuals(), subgrains = g.subgrain_count();
  int k = d - g.first_domain;
  if (g.vein && k == g.crystal_domain_count()) {
    part.vein = true;
    return part;
  }
  if (g.has_dust() && d == g.dust_domain()) {
    part.dust = true;
    return part;
  }
  if (g.myrmekite && d == g.myrmekite_domain()) {
    part.myrmekite = true;
    return part;
  }
  if (g.has_halo() && d >= g.first_halo_domain()) {
    part.halo = true;
    k = d - g.first_halo_domain();
  } else if (d >= g.first_inclusion_domain()) {
    part.inclusion = d - g.first_inclusion_domain();
    return part;
  }
  part.subgrain = k % subgrains;
  part.twin = (k / subgrains) % per_twin;
  part.zone = k / subgrains / per_twin;
  return part;
}

const Crystal* SectionMap::crystal_of_domain(int d) const {
  const DomainPart part = domain_part(d);
  if (part.grain < 0) return nullptr;
  const SectionGrain& g = grains[part.grain];
  if (part.inclusion >= 0) return g.inclusions->crystal;
  if (part.dust) return g.overgrowth->dust->crystal;
  if (part.myrmekite) return g.myrmekite->quartz;
  if (part.halo) return g.inclusions->halo->zone_crystals[static_cast<std::size_t>(part.zone)].get();
  return part.vein ? g.vein->crystal : g.zones[part.zone].crystal;
}

const glm::dmat3& SectionMap::orientation_of_domain(int d) const { return domain_orientation_[d]; }

const std::string& SectionMap::mineral_of_domain(int d) const {
  static const std::string slide = "slide", medium = "mounting medium", opaque = "non-indexed (black)";
  if (d == kSlideDomain) return slide;
  if (d == kMediumDomain) return medium;
  const DomainPart part = domain_part(d);
  if (part.grain < 0) return opaque;
  const SectionGrain& g = grains[part.grain];
  if (part.inclusion >= 0) return g.inclusions->mineral;
  if (part.dust) return g.overgrowth->dust->mineral;
  if (part.myrmekite) return g.myrmekite->quartz_mineral;
  return part.vein ? g.vein->mineral : g.zones[part.zone].mineral;
}

void SectionMap::finish() {
  domain_grain_.assign(2, -1);
  domain_orientation_.assign(2, glm::dmat3(1.0));
  grown_.reset();
  grown_grain_.clear();
  matrix_grain_ = -1;
  for (std::size_t i = 0; i < grains.size(); ++i) {
    SectionGrain& g = grains[i];
    g.first_domain = static_cast<int>(domain_grain_.size());
    for (const SectionZone& z : g.zones)
      for (int twin = 0; twin < g.twin_individuals(); ++twin)
        for (int sub = 0; sub < g.subgrain_count(); ++sub) {
          const glm::dmat3 o = (twin & 2 ? g.cross_twin->op : glm::dmat3(1.0)) * (twin & 1 ? z.twin_orientation : z.orientation);
          domain_orientation_.push_back(g.subgrain_rotation.empty() ? o : g.subgrain_rotation[sub] * o);
          domain_grain_.push_back(static_cast<int>(i));
        }
    if (g.vein) {
      domain_orientation_.push_back(g.vein->orientation);
      domain_grain_.push_back(static_cast<int>(i));
    }
    if (g.inclusions)
      for (const glm::dmat3& o : g.inclusions->orientations) {
        domain_orientation_.push_back(o);
        domain_grain_.push_back(static_cast<int>(i));
      }
    if (g.has_halo())
      for (int k = 0; k < g.crystal_domain_count(); ++k) {
        domain_orientation_.push_back(domain_orientation_[static_cast<std::size_t>(g.first_domain + k)]);
        domain_grain_.push_back(static_cast<int>(i));
      }
    if (g.has_dust()) {
      domain_orientation_.push_back(glm::dmat3(1.0));
      domain_grain_.push_back(static_cast<int>(i));
    }
    if (g.myrmekite) {
      domain_orientation_.push_back(g.myrmekite->quartz_orientation);
      domain_grain_.push_back(static_cast<int>(i));
    }
  }
  if (raster) {  // domain_at reads the raster: no tiling grid
    if (has_opaque_domain) {
      domain_grain_.push_back(-1);
      domain_orientation_.push_back(glm::dmat3(1.0));
    }
    cell_start_.clear();
    cell_grains_.clear();
    return;
  }
  for (std::size_t i = 0; i < grains.size(); ++i) {
    if (grains[i].matrix) matrix_grain_ = static_cast<int>(i);
    if (grains[i].growth) grown_grain_.push_back(static_cast<int>(i));
  }
  cement_.reset();
  cement_grain_.clear();
  bulbs_.reset();
  hosts_bulbs_.clear();
  if (!grown_grain_.empty()) {
    grown_ = std::make_shared<const GrownTiling>(
        grown_grain_.size(), [&](std::size_t k) -> const GrainGrowth& { return *grains[grown_grain_[k]].growth; },
        matrix_grain_ >= 0, width_mm, height_mm);
    std::vector<GrainOvergrowth> overgrowths;
    for (const int i : grown_grain_)
      if (const auto& o = grains[i].overgrowth) {
        const GrainGrowth& b = *grains[i].growth;
        overgrowths.push_back({b.nucleus_mm, b.shape.support_mm[0], o->habit_scale, o->form});
        cement_grain_.push_back(i);
      }
    if (!overgrowths.empty()) cement_ = std::make_shared<const OvergrowthCement>(std::move(overgrowths), width_mm, height_mm);
    place_myrmekite();
    return;
  }
  // Grid over the extent with about two cells per grain, at most 1024 a side.
  const double area = width_mm * height_mm;
  cell_mm_ = std::sqrt(area / std::max<double>(1.0, 2.0 * static_cast<double>(grains.size())));
  cell_mm_ = std::max({cell_mm_, width_mm / 1024.0, height_mm / 1024.0});
  cells_x_ = std::max(1, static_cast<int>(std::ceil(width_mm / cell_mm_)));
  cells_y_ = std::max(1, static_cast<int>(std::ceil(height_mm / cell_mm_)));
  const int ncell = cells_x_ * cells_y_;
  const glm::dvec2 origin{-0.5 * width_mm, -0.5 * height_mm};
  auto cell_of = [&](const glm::dvec2& p, int& cx, int& cy) {
    cx = std::clamp(static_cast<int>(std::floor((p.x - origin.x) / cell_mm_)), 0, cells_x_ - 1);
    cy = std::clamp(static_cast<int>(std::floor((p.y - origin.y) / cell_mm_)), 0, cells_y_ - 1);
  };
  // Pass 1: an upper bound of the nearest distance per cell, from the grains centred in the
  // nearest non-empty rings of cells (any grain's largest corner distance bounds it: the
  // distance is a convex quadratic, so its maximum over a cell is at a corner).
  std::vector<std::vector<int>> bucket(ncell);
  for (std::size_t i = 0; i < grains.size(); ++i) {
    int cx, cy;
    cell_of(grains[i].centre_mm, cx, cy);
    bucket[cy * cells_x_ + cx].push_back(static_cast<int>(i));
  }
  std::vector<double> upper(ncell, 1e300);
  const int max_ring = std::max(cells_x_, cells_y_);
  for (int cy = 0; cy < cells_y_; ++cy)
    for (int cx = 0; cx < cells_x_; ++cx) {
      const glm::dvec2 lo = origin + cell_mm_ * glm::dvec2(cx, cy), hi = lo + glm::dvec2(cell_mm_);
      double u = 1e300;
      int found_ring = -1;
      for (int ring = 0; ring <= max_ring && (found_ring < 0 || ring <= found_ring + 1); ++ring)
        for (int y = cy - ring; y <= cy + ring; ++y)
          for (int x = cx - ring; x <= cx + ring; ++x) {
            if (std::max(std::abs(x - cx), std::abs(y - cy)) != ring) continue;
            if (x < 0 || y < 0 || x >= cells_x_ || y >= cells_y_) continue;
            for (const int i : bucket[y * cells_x_ + x]) {
              double m = 0.0;
              for (const glm::dvec2 c : {lo, hi, glm::dvec2(lo.x, hi.y), glm::dvec2(hi.x, lo.y)})
                m = std::max(m, grain_distance2(grains[i], c));
              u = std::min(u, m + 1e-9 * (std::abs(m) + metric_floor(grains[i])));  // rounding margin
              if (found_ring < 0) found_ring = ring;
            }
          }
      upper[cy * cells_x_ + cx] = u;
    }
  const double u_max = grains.empty() ? 0.0 : *std::max_element(upper.begin(), upper.end());
  // Pass 2: a grain can be nearest in a cell only if its lower bound there (metric_min times
  // the squared distance from its centre to the cell) is at most the cell's upper bound, which
  // never exceeds u_max: so only cells within sqrt(u_max / metric_min) of its centre are tried.
  std::vector<std::vector<int>> lists(ncell);
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const SectionGrain& g = grains[i];
    const double lam = metric_min(g), floor = metric_floor(g);
    if (u_max + floor < 0.0) continue;  // its distance exceeds every cell's upper bound
    const double reach = std::sqrt((u_max + floor) / lam) + cell_mm_;
    int x0, y0, x1, y1;
    cell_of(g.centre_mm - glm::dvec2(reach), x0, y0);
    cell_of(g.centre_mm + glm::dvec2(reach), x1, y1);
    for (int cy = y0; cy <= y1; ++cy)
      for (int cx = x0; cx <= x1; ++cx) {
        const glm::dvec2 lo = origin + cell_mm_ * glm::dvec2(cx, cy), hi = lo + glm::dvec2(cell_mm_);
        const double dx = std::max({lo.x - g.centre_mm.x, 0.0, g.centre_mm.x - hi.x});
        const double dy = std::max({lo.y - g.centre_mm.y, 0.0, g.centre_mm.y - hi.y});
        const double lower = lam * (dx * dx + dy * dy) - floor;
        if (lower - 1e-9 * (std::abs(lower) + floor) <= upper[cy * cells_x_ + cx])
          lists[cy * cells_x_ + cx].push_back(static_cast<int>(i));
      }
  }
  cell_start_.assign(1, 0);
  cell_grains_.clear();
  for (const auto& l : lists) {
    cell_grains_.insert(cell_grains_.end(), l.begin(), l.end());
    cell_start_.push_back(static_cast<int>(cell_grains_.size()));
  }
}

int SectionMap::nearest_grain_exhaustive(const glm::dvec2& p) const {
  int best = 0;
  double best_d = 1e300;
  if (grown_) return grown_owner(grown_->owner_exhaustive(p), p, true);
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const double dist = grain_distance2(grains[i], p);
    if (dist < best_d) {
      best_d = dist;
      best = static_cast<int>(i);
    }
  }
  return best;
}

// The grain of tiling crystal c at p; where no crystal reaches p (c < 0), an overgrowth's or the
// matrix's.
int SectionMap::grown_owner(int c, const glm::dvec2& p, bool exhaustive) const {
  if (c >= 0) {
    const int gi = grown_grain_[c];
    if (bulbs_ && hosts_bulbs_[static_cast<std::size_t>(gi)]) {  // a host's point may be in a bulb of its neighbour
      const int b = bulbs_->at(p);
      if (b >= 0) return bulbs_->bulb(b).grain;
    }
    return gi;
  }
  if (cement_) {
    const int k = exhaustive ? cement_->owner_exhaustive(p) : cement_->owner(p);
    if (k >= 0) return cement_grain_[k];
  }
  return matrix_grain_;
}

int SectionMap::nearest_grain(const glm::dvec2& p) const {
  if (grown_) return grown_owner(grown_->owner(p), p, false);
  if (cell_start_.empty()) return nearest_grain_exhaustive(p);
  const int cx = std::clamp(static_cast<int>(std::floor((p.x + 0.5 * width_mm) / cell_mm_)), 0, cells_x_ - 1);
  const int cy = std::clamp(static_cast<int>(std::floor((p.y + 0.5 * height_mm) / cell_mm_)), 0, cells_y_ - 1);
  const int c = cy * cells_x_ + cx;
  int best = 0;
  double best_d = 1e300;
  // Candidates in increasing index: the same winner as the exhaustive search, ties included.
  for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
    const int i = cell_grains_[k];
    const double dist = grain_distance2(grains[i], p);
    if (dist < best_d) {
      best_d = dist;
      best = i;
    }
  }
  return best;
}

int SectionMap::crack_family_in_grain(int gi, const glm::dvec2& p, double crack_mm) const {
  const SectionGrain& g = grains[gi];
  if (g.vein) crack_mm = std::max(crack_mm, g.vein->width_mm);
  const glm::dvec2 d = p - g.centre_mm;
  // Cleavage cracks: in family f, crack k lies near offset (k + ½ + jitter)·spacing along the
  // trace normal (jitter ±0.3 spacing) and is broken into segments 4 spacings long of which
  // about 80 % are open: cleavage cracks in thin section are discontinuous, unevenly spaced lines.
  for (std::size_t f = 0; f < g.cracks.size(); ++f) {
    const CleavageCracks& c = g.cracks[f];
    const double s = glm::dot(d, c.normal) / c.spacing_mm;
    const double k = std::floor(s);
    const auto ki = static_cast<std::uint64_t>(static_cast<std::int64_t>(k));
    const double centre = 0.5 + 0.6 * (hash01(gi, f, ki) - 0.5);
    if (std::abs(s - k - centre) * c.spacing_mm < 0.5 * crack_mm) {
      const double along = (d.x * c.normal.y - d.y * c.normal.x) / (4.0 * c.spacing_mm) + hash01(gi, f, ki, 1);
      const auto seg = static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(along)));
      if (hash01(gi, f + 17, ki, seg + 2) < 0.8) return static_cast<int>(f);
    }
  }
  return -1;
}

int SectionMap::crack_family_at(const glm::dvec2& p, int& grain, double min_width_mm) const {
  grain = -1;
  if (raster || grains.empty() || !(std::abs(p.x) <= 0.5 * width_mm && std::abs(p.y) <= 0.5 * height_mm)) return -1;
  const int gi = nearest_grain(p);
  const int f = crack_family_in_grain(gi, p, std::max(crack_width_mm, min_width_mm));
  if (f >= 0) grain = gi;
  return f;
}

int SectionMap::crack_domain(int grain) const {
  const SectionGrain& g = grains[std::size_t(grain)];
  return g.vein ? g.first_domain + g.crystal_domain_count() : kMediumDomain;
}

double SectionGrain::detrital_section_radius_mm() const {
  const double r = growth->shape.support_mm[0], z = growth->nucleus_mm.z;
  return std::sqrt(std::max(0.0, r * r - z * z));
}

// The inclusion (its orientation's index) of grain gi covering p, or −1. Each inclusion is a rigid
// ellipse: caught at the growth fraction s_c of its centre on a straight trail, then turned with
// the crystal by rotation·(1 − s_c) about the grain's centre. Its cell (trail, site) is found in
// the frame of p's own turn; the few neighbouring cells cover the difference between that frame and
// the centre's (a turn of rotation·Δs over an inclusion's length moves it by under a cell). Each
// cell holds at most one inclusion, jittered as far as it stays inside the cell (the reader keeps
// size ≤ spacing, width ≤ trail spacing).
namespace {
double grain_growth_fraction(const SectionGrain& g, const glm::dvec2& p) {
  return g.growth ? growth_fraction(*g.growth, p) : std::sqrt(ellipse_q(g, p));
}

// The smallest wedge's scale (SectionGrain::InclusionSet::wedges): scales uniform in [0.55, 1]
// give wedges a mean area E[k²] = (1 − 0.55³)/(3·0.45) = 0.6175 of the largest's.
constexpr double kWedgeMinScale = 0.55;

// inclusion_at's answer for a point of the host inside an inclusion's halo.
constexpr int kInHalo = -2;

int inclusion_at(const SectionGrain& g, int gi, const glm::dvec2& p) {
  const SectionGrain::InclusionSet& in = *g.inclusions;
  // A halo reaches radius_mm from its inclusion's centre, which lies in the point's cell or one
  // of its eight neighbours: the reader keeps radius_mm within both spacings.
  const double halo_r = in.halo ? in.halo->radius_mm : 0.0;
  bool in_halo = false;
  const auto turn = [&](double s) { return in.trail_rad + in.rotation_rad * (1.0 - std::min(s, 1.0)); };
  // within ≥ 1 is the whole grain: the gaps it filled after its faces stopped (s > 1: a crystal of
  // a holocrystalline rock takes the space no face reached, grown_tiling.h) hold inclusions too.
  const double within = in.within >= 1.0 ? std::numeric_limits<double>::infinity() : in.within;
  const double sp = grain_growth_fraction(g, p);
  if (!(sp <= within + (in.size_mm + 2.0 * halo_r) / std::max(g.semi_minor_mm, 1e-9))) return -1;
  const glm::dvec2 d = p - g.centre_mm;
  const double ap = turn(sp), cp = std::cos(ap), spn = std::sin(ap);
  const double site0 = std::floor((cp * d.x + spn * d.y) / in.spacing_mm + 0.5);
  const double trail0 = std::floor((-spn * d.x + cp * d.y) / in.trail_spacing_mm + 0.5);
  const double half_l = 0.5 * in.size_mm / in.spacing_mm, half_w = 0.5 * in.width_mm / in.trail_spacing_mm;
  const auto hg = static_cast<std::uint64_t>(gi) + 0x1C1u;
  for (int dt = -1; dt <= 1; ++dt)
    for (int ds = -1; ds <= 1; ++ds) {
      const double site = site0 + ds, trail = trail0 + dt;
      const auto hs = static_cast<std::uint64_t>(static_cast<std::int64_t>(site));
      const auto ht = static_cast<std::uint64_t>(static_cast<std::int64_t>(trail));
      if (hash01(hg, ht, hs, 0) >= in.fraction) continue;
      // The centre in the trails' own frame (mm), then turned by its own growth fraction's turn:
      // a turn moves the centre along a circle about the grain's centre, nearly along a contour
      // of s, so two fixed-point steps from p's turn settle it.
      // Wedges come in sizes (a graphic intergrowth's rods are not cast alike): a scale uniform in
      // [kWedgeMinScale, 1] by hash, the jitter then as far as the smaller wedge stays in its cell.
      const double scale = in.wedges ? kWedgeMinScale + (1.0 - kWedgeMinScale) * hash01(hg, ht, hs, 4) : 1.0;
      const double u = (site + (1.0 - 2.0 * scale * half_l) * (hash01(hg, ht, hs, 1) - 0.5)) * in.spacing_mm;
      const double v = (trail + (1.0 - 2.0 * scale * half_w) * (hash01(hg, ht, hs, 2) - 0.5)) * in.trail_spacing_mm;
      // Without a turn (rotation 0: sericite, perthite, fluid trails) the frame is p's own and
      // the centre's growth fraction matters only against a finite `within`: the same numbers
      // as the fixed point, without its gauges and sines.
      double a = ap, sc = sp, ca = cp, sa = spn;
      glm::dvec2 c{ca * u - sa * v, sa * u + ca * v};
      if (in.rotation_rad != 0.0) {
        for (int k = 0; k < 2; ++k) {
          c = {std::cos(a) * u - std::sin(a) * v, std::sin(a) * u + std::cos(a) * v};
          sc = grain_growth_fraction(g, g.centre_mm + c);
          a = turn(sc);
        }
        ca = std::cos(a);
        sa = std::sin(a);
        c = {ca * u - sa * v, sa * u + ca * v};
      } else if (std::isfinite(within)) {
        sc = grain_growth_fraction(g, g.centre_mm + c);
      }
      if (!(sc <= within)) continue;
      const auto n = static_cast<int>(in.orientations.size());
      const int k = std::min(n - 1, static_cast<int>(hash01(hg, ht, hs, 3) * n));
      // A trail's inclusions lie along it; a needle along its own c axis.
      double length = scale * in.size_mm, width = scale * in.width_mm;
      if (!in.needles.empty()) {
        const SectionGrain::InclusionSet::Needle& nd = in.needles[std::size_t(k)];
        ca = nd.axis.x, sa = nd.axis.y, length = nd.length_mm;
      }
      const glm::dvec2 e = d - c;
      const double eu = (ca * e.x + sa * e.y) / (0.5 * length), ev = (-sa * e.x + ca * e.y) / (0.5 * width);
      // A needle is a prism seen side-on, a rectangle; a wedge a triangle, its base (the full
      // width) at eu = −1 and its apex at eu = 1; other inclusions are ellipses.
      const bool outside = !in.needles.empty() ? std::max(std::abs(eu), std::abs(ev)) > 1.0
                           : in.wedges        ? std::abs(eu) > 1.0 || std::abs(ev) > 0.5 * (1.0 - eu)
                                              : eu * eu + ev * ev > 1.0;
      if (outside) {
        in_halo = in_halo || glm::dot(e, e) <= halo_r * halo_r;
        continue;
      }
      return k;
    }
  return in_halo ? kInHalo : -1;
}

// A lamella index as an integer for parities and hashes. Past 2⁵² lamellae (a width of 10⁻¹⁵ of
// the section, which no reader forbids) a double holds no parity; 0 there instead of an overflowing
// cast.
std::int64_t lamella_index(double k) { return std::abs(k) < 0x1p52 ? static_cast<std::int64_t>(k) : 0; }

// Cross-hatched lamellae pinch and swell ("spindles": Nesse 2012, microcline; unlike plagioclase's
// lamellae of even width): each slot 2w wide across the trace holds one twin lens about its middle,
// its half-width (w/2)·(1 + 0.8·cos(2π(u/L + φ))) along the trace coordinate u, with L = 8w and a
// phase φ of its own. The lenses fill half the area on average, as even lamellae do.
int in_spindle(const glm::dvec2& d, const glm::dvec2& normal, double w, int gi, int set) {
  const double t = glm::dot(d, normal), u = normal.x * d.y - normal.y * d.x;
  const double slot = std::floor(t / (2.0 * w)), tau = t - (2.0 * slot + 1.0) * w;
  const double phase = hash01(static_cast<std::uint64_t>(gi) + 0x5B1Du, static_cast<std::uint64_t>(set),
                              static_cast<std::uint64_t>(lamella_index(slot)), 7);
  const double half = 0.5 * w * (1.0 + 0.8 * std::cos(2.0 * kPi * (u / (8.0 * w) + phase)));
  return std::abs(tau) < half ? 1 : 0;
}

// Whether p lies in a speck of grain gi's dust line (SectionGrain::Overgrowth): discs of the dust's
// size touching the ball's section circle (radius ρ) from inside, their centres on the circle of
// radius ρ − size/2 in n equal sites, each occupied by hash and jittered along it as far as it
// stays in its site. `s` is p's growth fraction in the ball.
bool in_dust(const SectionGrain& g, int gi, const glm::dvec2& p, double s) {
  const SectionGrain::Overgrowth::Dust& dust = *g.overgrowth->dust;
  const double r = g.growth->shape.support_mm[0];
  const double half = 0.5 * dust.size_mm, rc = g.detrital_section_radius_mm() - half;
  if (!(rc > half) || std::abs(s * r - r) > dust.size_mm + 1e-12) return false;  // s·r ≈ |x|: near the surface only
  const glm::dvec2 d = p - glm::dvec2(g.growth->nucleus_mm);
  if (std::abs(glm::length(d) - rc) > half) return false;
  const int n = std::max(3, static_cast<int>(2.0 * kPi * rc / dust.spacing_mm));
  const double site_rad = 2.0 * kPi / n, jitter = std::max(0.0, 1.0 - dust.size_mm / (rc * site_rad));
  const double a = std::atan2(d.y, d.x);
  const int k0 = static_cast<int>(std::floor(a / site_rad));
  const auto hg = static_cast<std::uint64_t>(gi) + 0xD057u;
  for (int dk = -1; dk <= 1; ++dk) {
    const int k = ((k0 + dk) % n + n) % n;
    const auto hk = static_cast<std::uint64_t>(k);
    if (hash01(hg, hk, 0) >= dust.fraction) continue;
    const double c = (k + 0.5 + jitter * (hash01(hg, hk, 1) - 0.5)) * site_rad;
    const glm::dvec2 e = d - rc * glm::dvec2(std::cos(c), std::sin(c));
    if (glm::dot(e, e) <= half * half) return true;
  }
  return false;
}

}  // namespace

int SectionMap::domain_in_grain(int gi, const glm::dvec2& p) const {
  if (crack_family_in_grain(gi, p, crack_width_mm) >= 0) return crack_domain(gi);
  const SectionGrain& g = grains[gi];
  int halo_offset = 0;  // to the host's darkened domain, in an inclusion's halo
  // An overgrown grain: its cement (s > 1 in the ball) holds none of what the grain brought along.
  const double s_ball = g.overgrowth ? growth_fraction(*g.growth, p) : 0.0;
  if (g.has_dust() && in_dust(g, gi, p, s_ball)) return g.dust_domain();
  if (g.myrmekite) {  // in a bulb, a quartz rod or the grain's own plagioclase (below)
    const int b = myrmekite_bulb_of(gi, p);
    if (b >= 0 && in_vermicule(bulbs_->bulb(b), g.myrmekite->rods, p)) return g.myrmekite_domain();
  }
  if (g.inclusions && s_ball <= 1.0) {
    const int k = inclusion_at(g, gi, p);
    if (k >= 0) return g.first_inclusion_domain() + k;
    if (k == kInHalo) halo_offset = g.first_halo_domain() - g.first_domain;
  }
  const glm::dvec2 d = p - g.centre_mm;
  int zone = static_cast<int>(g.zones.size()) - 1;
  if (zone > 0 && g.growth) {
    const double s = growth_fraction(*g.growth, p);
    for (int z = 0; z < zone; ++z)
      if (s <= g.zones[z].outer_fraction) {
        zone = z;
        break;
      }
  } else if (zone > 0) {
    const double r2 = ellipse_q(g, p);
    for (int z = 0; z < zone; ++z)
      if (r2 <= g.zones[z].outer_fraction * g.zones[z].outer_fraction) {
        zone = z;
        break;
      }
  }
  int twin = 0;
  if (g.twinned) {
    const double t = glm::dot(d, g.twin_normal);
    if (const auto& x = g.cross_twin)
      twin = in_spindle(d, g.twin_normal, g.lamella_mm, gi, 0) | in_spindle(d, x->normal, x->lamella_mm, gi, 1) << 1;
    else
      twin = g.lamella_mm > 0.0 ? static_cast<int>(lamella_index(std::floor(t / g.lamella_mm)) & 1) : (t < 0.0 ? 1 : 0);
  }
  int sub = 0;
  if (const int n = g.subgrain_count(); n > 1) {  // bands centred on the grain's centre; the outer two take the rest
    const int half = (n - 1) / 2;
    const double band = std::round(glm::dot(d, g.subgrain_normal) / g.subgrain_mm);
    sub = half + static_cast<int>(std::clamp(band, -double(half), double(half)));
  }
  return g.first_domain + halo_offset + (zone * g.twin_individuals() + twin) * g.subgrain_count() + sub;
}

int DomainRaster::domain_at(const glm::dvec2& p, int outside) const {
  // Row r's centres lie at first_y − r·step_y (rows go south), column c's at first_x + c·step_x
  // (+ step_x/2 in the shifted rows of a hexagonal grid).
  const double fr = (first_y_mm - p.y) / step_y_mm + 0.5;
  if (!(fr >= 0.0 && fr < rows)) return outside;
  const int r = static_cast<int>(fr);
  const double shift = (hexagonal && r % 2 == 1) ? 0.5 : 0.0;
  const double fc = (p.x - first_x_mm) / step_x_mm + 0.5 - shift;
  const int n = r % 2 == 0 ? columns_odd : columns_even;
  if (!(fc >= 0.0 && fc < n)) return outside;
  const std::size_t pair = static_cast<std::size_t>(columns_odd) + static_cast<std::size_t>(columns_even);
  const std::size_t i = static_cast<std::size_t>(r / 2) * pair + (r % 2 == 1 ? columns_odd : 0) + static_cast<int>(fc);
  return domain[i];
}

int SectionMap::domain_at(const glm::dvec2& p) const {
  if (raster) return raster->domain_at(p, kSlideDomain);
  if (grains.empty() || !(std::abs(p.x) <= 0.5 * width_mm && std::abs(p.y) <= 0.5 * height_mm))
    return kSlideDomain;
  return domain_in_grain(nearest_grain(p), p);
}

namespace {

using nlohmann::json;

// Rotation by π about unit axis u: R = 2uuᵀ − I.
glm::dmat3 half_turn(const glm::dvec3& u) {
  glm::dmat3 r(0.0);
  for (int c = 0; c < 3; ++c)
    for (int rr = 0; rr < 3; ++rr) r[c][rr] = 2.0 * u[c] * u[rr] - (c == rr ? 1.0 : 0.0);
  return r;
}

// Crack spacing by cleavage quality (mm): perfect cleavages (micas, amphiboles) show closely
// spaced traces, good ones (pyroxenes) wider, poor ones (olivine) a few irregular fractures per
// grain (Nesse 2012, "Introduction to Optical Mineralogy", 4th ed., §5 "cleavage"; the figures of
// MacKenzie & Adams 1994, "A Colour Atlas of Rocks and Minerals in Thin Section"). Partings are
// not drawn: they develop only in some crystals.
std::optional<double> crack_spacing_mm(CleavageQuality q) {
  switch (q) {
    case CleavageQuality::Perfect: return 0.025;
    case CleavageQuality::VeryGood: return 0.04;
    case CleavageQuality::Good: return 0.06;
    case CleavageQuality::Distinct: return 0.09;
    case CleavageQuality::Fair: return 0.12;
    case CleavageQuality::Imperfect: return 0.16;
    case CleavageQuality::Poor: return 0.22;
    case CleavageQuality::Parting: return std::nullopt;
  }
  return std::nullopt;
}

// The indicatrix (columns X, Y, Z) of a grain whose crystal frame is L in the section: L times
// the mineral file's X, Y, Z in the crystal frame. A mineral with a lattice but no
// optical_orientation in its file (plagioclase, the whole series: the library has no published
// orientation of its X, Y, Z; see its file's "note") gets X, Y, Z along the
// crystal frame's e1, e2, e3. That is a stand-in, not data: such grains are shaped, twinned and
// cracked from their lattice and show their indices' birefringence, but their extinction angles
// to those traces (and so the Michel-Lévy curve) are not the mineral's.
glm::dmat3 indicatrix_in_section(const MineralCrystallography* mc, const glm::dmat3& L) {
  return mc && mc->orientation ? L * mc->indicatrix_axes : L;
}
// Lamellae of width w stay distinct while the smear t·tan θ is under half a lamella, θ ≤
// atan(w / 2t) (18° for 20 µm lamellae in a 30 µm section), but no more than the cleavage limit.
double lamella_max_inclination_deg(double lamella_mm, double thickness_um) {
  return std::min(kCleavageMaxInclinationDeg, degrees(std::atan(lamella_mm / (2.0 * thickness_um * 1e-3))));
}
// A simple twin's two halves are told apart unless its plane is near the section (they overlap
// through the thickness over t·tan θ: 52 µm at 60°, small against mm-sized grains).
constexpr double kSimpleTwinMaxInclinationDeg = 60.0;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Sets the grain's ellipse from the central section of a shape ellipsoid Σ uᵢuᵢᵀ/sᵢ² (section
// frame): points (x, y, 0) inside it satisfy the top-left 2×2 block of the quadratic form.
void set_ellipse(SectionGrain& g, const glm::dmat3& Q) {
  g.metric_xx = Q[0][0];
  g.metric_xy = 0.5 * (Q[0][1] + Q[1][0]);
  g.metric_yy = Q[1][1];
  const double tr = g.metric_xx + g.metric_yy, det = g.metric_xx * g.metric_yy - g.metric_xy * g.metric_xy;
  const double disc = std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
  const double lmin = 0.5 * tr - disc, lmax = 0.5 * tr + disc;
  g.semi_major_mm = 1.0 / std::sqrt(lmin);
  g.semi_minor_mm = 1.0 / std::sqrt(lmax);
  // Eigenvector of lmin: (xy, lmin − xx) or (lmin − yy, xy).
  glm::dvec2 v = std::abs(g.metric_xy) > 1e-15 * tr ? glm::dvec2(g.metric_xy, lmin - g.metric_xx)
                                                     : (g.metric_xx <= g.metric_yy ? glm::dvec2(1, 0) : glm::dvec2(0, 1));
  g.elongation_rad = std::atan2(v.y, v.x);
  if (g.elongation_rad < 0) g.elongation_rad += kPi;
  if (g.elongation_rad >= kPi) g.elongation_rad -= kPi;
  g.elongated = g.semi_major_mm > g.semi_minor_mm * (1.0 + 1e-6);
}

glm::dmat3 outer(const glm::dvec3& u, double s) {
  glm::dmat3 m(0.0);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m[c][r] = u[c] * u[r] / (s * s);
  return m;
}

// Any unit vector perpendicular to u.
glm::dvec3 perpendicular(const glm::dvec3& u) {
  const glm::dvec3 a = std::abs(u.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(u, a));
}

std::vector<double> numbers(const JsonReader& gr, const char* k, int n) {
  const json& gj = gr.node();
  if (!gj.contains(k) || !gj[k].is_array() || static_cast<int>(gj[k].size()) != n)
    throw InputError(gr.file(), gr.path(k), gj.contains(k) ? shown(gj[k]) : "",
                     "expected an array of " + std::to_string(n) + " numbers");
  std::vector<double> v;
  for (const json& x : gj[k]) v.push_back(gr.checked(k, gj[k], [&](const json&) { return number_value(x); }));
  return v;
}

const Crystal& known_mineral(const JsonReader& r, const char* key, const std::string& name) {
  if (const auto problem = mineral_name_problem(name)) throw InputError(r.file(), r.path(key), name, *problem);
  return find_mineral(name);
}

// The old format: seeds in field units, explicit elongation, weight and twin trace; no
// crystallography (kept so that older files keep loading with the same grain map).
void read_legacy_grain(const JsonReader& gr, SectionGrain& g) {
  const auto s = numbers(gr, "seed", 2);
  g.centre_mm = {s[0], s[1]};
  const double e = gr.get_or("elongation", 1.0, Range::above(0));
  const double ang = radians(gr.get_or("elongation_deg", 0.0));
  const double w = gr.get_or("weight", 1.0, Range::above(0));
  const glm::dvec3 u{std::cos(ang), std::sin(ang), 0.0}, v{-std::sin(ang), std::cos(ang), 0.0};
  set_ellipse(g, outer(u, e * w) + outer(v, w) + outer({0, 0, 1}, 1.0));
  if (const auto t = gr.optional_object("twin")) {
    g.twinned = true;
    g.twin_law = "albite";
    g.twin_trace_rad = radians(t->get_or("trace_deg", 0.0));
    g.lamella_mm = t->get_or("width", 0.05, Range::above(0));
    g.twin_normal = {-std::sin(g.twin_trace_rad), std::cos(g.twin_trace_rad)};
    const glm::dvec3 axis{g.twin_normal.x, g.twin_normal.y, 0.0};
    g.twin_orientation = half_turn(axis) * g.orientation;
  } else {
    g.twin_orientation = g.orientation;
  }
}

// What a reader looks up again and again, for one file (and one thread): habit templates by
// mineral and aspect (a grown rock places a few templates on up to 10⁵–10⁶ grains, and a
// template's circumradius, every triple of its faces, costs ~10 µs) and minerals by name (each
// lookup canonicalises the name, a composition's number printed and parsed: ~1 µs, several a
// grain). The library's answers for a name never change; a name it refuses is asked again, so
// the fault is named as without the cache.
class GrainLookups {
 public:
  const CrystalPolyhedron& get(const MineralCrystallography* mc, double aspect) {
    auto [it, fresh] = templates_.try_emplace({mc, aspect});
    if (fresh) it->second = habit_template(mc, aspect);
    return it->second;
  }
  const Crystal& mineral(const JsonReader& r, const char* key, const std::string& name) {
    if (const auto it = crystals_.find(name); it != crystals_.end()) return *it->second;
    const Crystal& c = known_mineral(r, key, name);
    crystals_.emplace(name, &c);
    return c;
  }
  const CrystalPolyhedron& overgrowth_form(const MineralCrystallography& mc) {
    auto [it, fresh] = forms_.try_emplace(&mc);
    if (fresh) it->second = overgrowth_unit_form(mc);
    return it->second;
  }
  const MineralCrystallography* crystallography(const std::string& name) {
    if (const auto it = crystallography_.find(name); it != crystallography_.end()) return it->second;
    const MineralCrystallography* mc = find_mineral_crystallography(name);
    crystallography_.emplace(name, mc);
    return mc;
  }

 private:
  std::map<std::pair<const MineralCrystallography*, double>, CrystalPolyhedron> templates_;
  std::unordered_map<std::string, const Crystal*> crystals_;
  std::unordered_map<std::string, const MineralCrystallography*> crystallography_;
  std::map<const MineralCrystallography*, CrystalPolyhedron> forms_;
};

// A twin law of the grain's mineral file (the twin object's "law", matched as a prefix of the
// file's names) as it shows in this section: the twin operation in the section frame and the
// composition plane's normal; `shows` false where that plane lies too flat (lamellae of width
// lamella_mm smeared through the thickness, or a simple twin's halves overlapping).
struct TwinInSection {
  std::string law;
  glm::dmat3 op{1.0};
  glm::dvec3 plane_normal{0.0, 0.0, 1.0};
  bool shows = false;
};
TwinInSection twin_in_section(const JsonReader& t, const std::string& mineral, const MineralCrystallography* mc,
                              const glm::dmat3& L, double lamella_mm, double thickness_um) {
  TwinInSection r;
  r.law = t.require<std::string>("law");
  if (!mc || mc->twins.empty())
    t.fail("law", "mineral '" + mineral + "' has no twin laws in its file (or the grain no euler_deg)");
  const TwinLaw* found = nullptr;
  for (const TwinLaw& tl : mc->twins)
    if (lower(tl.law).rfind(lower(r.law), 0) == 0) {
      found = &tl;
      break;
    }
  if (!found) {
    std::string known;
    for (const TwinLaw& tl : mc->twins) known += (known.empty() ? "" : "; ") + tl.law;
    t.fail("law", "not a twin law of " + mineral + " (its file lists: " + known + ")");
  }
  r.plane_normal = L * plane_normal(mc->cell, found->plane);
  // The twin operation: a half-turn about the twin axis. A law whose name gives "twin axis
  // [uvw]" is a parallel twin about that lattice direction; otherwise it is a normal twin, the
  // half-turn about the composition-plane normal (albite, Manebach, Baveno, the pyroxene and
  // amphibole (100) twins; Nesse 2012 §7 "twinning").
  // A law named without its axis takes the axis of the named law: Carlsbad [001], pericline
  // [010] (parallel twins; Nesse 2012 §7, Deer, Howie & Zussman 2013 feldspars), mica law
  // [310] (Handbook of Mineralogy, muscovite).
  glm::dvec3 axis = r.plane_normal;
  const std::string lt = lower(found->law);
  std::optional<LatticeDirection> named_axis;
  if (lt.rfind("carlsbad", 0) == 0) named_axis = LatticeDirection{0, 0, 1};
  if (lt.rfind("pericline", 0) == 0) named_axis = LatticeDirection{0, 1, 0};
  if (lt.rfind("mica", 0) == 0) named_axis = LatticeDirection{3, 1, 0};
  if (const auto at = lt.find("twin axis ["); at != std::string::npos) {
    const auto end = lt.find(']', at);
    named_axis = t.checked("law", *t.find("law"), [&](const json&) {
      return parse_lattice_direction(found->law.substr(at + 10, end - at - 9));
    });
  }
  if (named_axis) axis = L * lattice_direction(mc->cell, *named_axis);
  const double limit =
      lamella_mm > 0.0 ? lamella_max_inclination_deg(lamella_mm, thickness_um) : kSimpleTwinMaxInclinationDeg;
  r.shows = inclination_from_vertical_deg(r.plane_normal) <= limit;
  r.op = half_turn(axis);
  return r;
}

void read_grain(const JsonReader& gr, SectionGrain& g, double thickness_um, GrainLookups& templates) {
  const MineralCrystallography* mc = templates.crystallography(g.mineral);
  const bool has_lattice = g.lattice_to_section.has_value() && mc;
  const glm::dmat3 L = has_lattice ? *g.lattice_to_section : glm::dmat3(1.0);
  const auto c = numbers(gr, "centre_mm", 2);
  g.centre_mm = {c[0], c[1]};
  const double size = gr.require<double>("size_mm", Range::above(0));
  // The crystal's shape: an ellipsoid whose longest axis is size_mm, along the habit.
  glm::dmat3 Q = outer({1, 0, 0}, 0.5 * size) + outer({0, 1, 0}, 0.5 * size) + outer({0, 0, 1}, 0.5 * size);
  // A "sphere" grain (granoblastic, or a rounded detrital grain) has no habit to show: its
  // ellipse, and so the report's elongation, is the ball's.
  const auto growth_json = gr.optional_object("growth");
  const std::string shape = growth_json ? growth_json->get_or<std::string>("shape", "habit") : "habit";
  if (shape != "habit" && shape != "sphere") growth_json->fail("shape", "expected \"habit\" or \"sphere\"");
  const bool ball = shape == "sphere";
  const bool habit = has_lattice && (mc->habit.elongation || mc->habit.tabular) && !ball;
  if (ball && gr.has("aspect")) gr.fail("aspect", "a \"sphere\" grain is a ball: it has no aspect");
  const double aspect = habit ? gr.get_or("aspect", default_habit_aspect(mc), Range::at_least(1)) : 1.0;
  if (const auto& gw = growth_json) {
    GrainGrowth growth;
    growth.nucleus_mm = {g.centre_mm.x, g.centre_mm.y, gw->get_or("nucleus_z_mm", 0.0)};
    // Times of order 1, as the texture engine writes them: a porphyroblast's lead (arrival_time,
    // grown_tiling.cpp) must exceed any time span.
    growth.from = gw->require<double>("from", Range::closed(-100, 100));
    growth.to = gw->require<double>("to", Range::closed(-100, 100));
    if (!(growth.to > growth.from)) gw->fail("to", "growth must end after it starts (to > from)");
    growth.overgrows = gw->get_or("overgrows", false);
    // A ball: its neighbours alone bound it (crystal_polyhedron.h).
    growth.shape = ball ? sphere_polyhedron(size) : placed(templates.get(has_lattice ? mc : nullptr, aspect), L, size);
    g.growth = growth;
  }
  if (habit) {
    const bool both = mc->habit.elongation && mc->habit.tabular;
    if (both) {  // a lath: length along [uvw], thickness ⟂ (hkl), width between (√aspect)
      const glm::dvec3 e = L * lattice_direction(mc->cell, *mc->habit.elongation);
      const glm::dvec3 n0 = L * plane_normal(mc->cell, *mc->habit.tabular);
      const glm::dvec3 n = glm::normalize(n0 - glm::dot(n0, e) * e);
      Q = outer(e, 0.5 * size) + outer(n, 0.5 * size / aspect) + outer(glm::cross(e, n), 0.5 * size / std::sqrt(aspect));
    } else if (mc->habit.elongation) {
      const glm::dvec3 e = L * lattice_direction(mc->cell, *mc->habit.elongation);
      const glm::dvec3 p = perpendicular(e);
      Q = outer(e, 0.5 * size) + outer(p, 0.5 * size / aspect) + outer(glm::cross(e, p), 0.5 * size / aspect);
    } else {
      const glm::dvec3 n = L * plane_normal(mc->cell, *mc->habit.tabular);
      const glm::dvec3 p = perpendicular(n);
      Q = outer(n, 0.5 * size / aspect) + outer(p, 0.5 * size) + outer(glm::cross(n, p), 0.5 * size);
    }
  } else if (gr.has("aspect")) {
    gr.fail("aspect", "an aspect needs a mineral with a habit in its file and euler_deg");
  }
  set_ellipse(g, Q);
  g.cell_scale = g.semi_major_mm * g.semi_minor_mm;
  g.cell_offset = 1.0;

  if (gr.has("zones")) {
    double prev = 0.0;
    for (const JsonReader& z : gr.objects("zones", 1)) {
      SectionZone zone;
      zone.mineral = z.require<std::string>("mineral");
      zone.crystal = &templates.mineral(z, "mineral", zone.mineral);
      zone.outer_fraction = z.require<double>("outer_fraction", Range::open_closed(0, 1e308));
      if (zone.outer_fraction <= prev) z.fail("outer_fraction", "zone radii must increase outward");
      prev = zone.outer_fraction;
      const MineralCrystallography* zc = templates.crystallography(zone.mineral);
      zone.orientation = has_lattice && zc ? indicatrix_in_section(zc, L) : g.orientation;
      g.zones.push_back(zone);
    }
  }

  if (const auto t = gr.optional_object("twin")) {
    g.lamella_mm = t->get_or("lamella_mm", 0.0, Range::at_least(0));
    const TwinInSection tw = twin_in_section(*t, g.mineral, has_lattice ? mc : nullptr, L, g.lamella_mm, thickness_um);
    if (tw.shows) {
      g.twinned = true;
      g.twin_law = tw.law;
      const glm::dvec3 tr = plane_trace({0, 0, 1}, tw.plane_normal);
      g.twin_trace_rad = std::atan2(tr.y, tr.x);
      g.twin_normal = glm::normalize(glm::dvec2(tw.plane_normal.x, tw.plane_normal.y));
      g.twin_orientation = tw.op * g.orientation;
      for (SectionZone& z : g.zones) z.twin_orientation = tw.op * z.orientation;
    }
    if (const auto x = t->optional_object("cross")) {
      const double w = x->require<double>("lamella_mm", Range::above(0));
      if (!(g.lamella_mm > 0.0)) t->fail("lamella_mm", "a cross-hatched twin crosses lamellae: the first set needs lamella_mm > 0 too");
      const TwinInSection cx = twin_in_section(*x, g.mineral, has_lattice ? mc : nullptr, L, w, thickness_um);
      // Only across lamellae that show: where the first set's plane lies too flat, the grain
      // shows neither grid nor lamellae (a cut near the second set's plane would show that set
      // alone; not modelled).
      if (g.twinned && cx.shows)
        g.cross_twin = SectionGrain::CrossTwin{cx.law, cx.op, glm::normalize(glm::dvec2(cx.plane_normal.x, cx.plane_normal.y)), w};
    }
  }
  if (!g.twinned) {
    g.twin_orientation = g.orientation;
    for (SectionZone& z : g.zones) z.twin_orientation = z.orientation;
  }

  if (has_lattice)
    for (const Cleavage& cl : mc->cleavage) {
      const auto spacing = crack_spacing_mm(cl.quality);
      const glm::dvec3 n = L * plane_normal(mc->cell, cl.plane);
      if (!spacing || inclination_from_vertical_deg(n) > kCleavageMaxInclinationDeg) continue;
      CleavageCracks k;
      k.plane = miller_text(cl.plane);
      const glm::dvec3 tr = plane_trace({0, 0, 1}, n);
      k.trace_rad = std::atan2(tr.y, tr.x);
      k.normal = glm::normalize(glm::dvec2(n.x, n.y));
      k.spacing_mm = *spacing;
      k.plane_normal = glm::normalize(n);
      g.cracks.push_back(k);
    }
}

// "overgrowth": {"habit_scale": H, "dust": {"mineral": m, "size_mm": d, "spacing_mm": s, "fraction": f}}
// (SectionGrain::Overgrowth): on a detrital ball of a mineral with a unit cell and an orientation
// (euler_deg) to lay the form in. H in (0, kMaxOvergrowthScale]: the form at 3 is three times the
// grain, far beyond any cement a sandstone holds.
constexpr double kMaxOvergrowthScale = 3.0;
void read_overgrowth(const JsonReader& gr, SectionGrain& g, GrainLookups& lookups) {
  const auto o = gr.optional_object("overgrowth");
  if (!o) return;
  o->warn_unknown_keys({"habit_scale", "dust"});
  const MineralCrystallography* mc = lookups.crystallography(g.mineral);
  if (!g.growth || !g.growth->shape.normals.empty())
    gr.fail("overgrowth", "an overgrowth grows on a detrital grain: a grown \"sphere\" (\"growth\": {\"shape\": \"sphere\"})");
  if (!mc || !g.lattice_to_section)
    gr.fail("overgrowth", "an overgrowth continues its grain's lattice: " + g.mineral +
                              " needs a unit cell in the library and the grain an euler_deg");
  SectionGrain::Overgrowth og;
  og.habit_scale = o->require<double>("habit_scale", Range::open_closed(0, kMaxOvergrowthScale));
  og.form = overgrowth_form(lookups.overgrowth_form(*mc), *g.lattice_to_section, g.growth->shape.support_mm[0], og.habit_scale);
  if (const auto d = o->optional_object("dust")) {
    d->warn_unknown_keys({"mineral", "size_mm", "spacing_mm", "fraction"});
    SectionGrain::Overgrowth::Dust dust;
    dust.mineral = d->require<std::string>("mineral");
    dust.crystal = &lookups.mineral(*d, "mineral", dust.mineral);
    if (dust.crystal->symmetry() != CrystalSymmetry::Isotropic)
      d->fail("mineral", "a dust line's specks are fluid, glass or an opaque or cubic mineral (isotropic): " + dust.mineral +
                             " would need an orientation of its own");
    dust.size_mm = d->require<double>("size_mm", Range::open_closed(0, 0.1));
    dust.spacing_mm = d->require<double>("spacing_mm", Range::closed(dust.size_mm, 1.0));
    dust.fraction = d->get_or("fraction", 1.0, Range::closed(0, 1));
    og.dust = dust;
  }
  g.overgrowth = std::move(og);
}

// "myrmekite": {"host": "microcline", "depth_mm": d, "bulb_mm": b, "fraction": f,
//               "quartz": {"mineral": "quartz", "width_mm": w, "spacing_mm": s, "euler_deg": [φ1, Φ, φ2]}}
// (SectionGrain::Myrmekite) on a grown grain. Bulbs up to 1 mm deep and 2 mm wide: myrmekite
// is a rim texture, tens to hundreds of micrometres (Phillips 1974).
void read_myrmekite(const JsonReader& gr, SectionGrain& g) {
  const auto m = gr.optional_object("myrmekite");
  if (!m) return;
  using L = MyrmekiteRecipe;  // the bounds a recipe's myrmekite meets too (rock_recipe.h)
  m->warn_unknown_keys({"host", "depth_mm", "bulb_mm", "fraction", "quartz"});
  if (!g.growth) gr.fail("myrmekite", "myrmekite stands on a grown grain's boundary: the grain needs a \"growth\"");
  SectionGrain::Myrmekite my;
  my.host = m->require<std::string>("host");
  my.depth_mm = m->require<double>("depth_mm", Range::open_closed(0, L::kMaxDepthMm));
  my.bulb_mm = m->require<double>("bulb_mm", Range::open_closed(0, L::kMaxBulbMm));
  my.fraction = m->get_or("fraction", 1.0, Range::closed(0, 1));
  const JsonReader q = m->object("quartz");
  q.warn_unknown_keys({"mineral", "width_mm", "spacing_mm", "euler_deg"});
  my.quartz_mineral = q.require<std::string>("mineral");
  my.quartz = &known_mineral(q, "mineral", my.quartz_mineral);
  my.rods.width_mm = q.require<double>("width_mm", Range::open_closed(0, L::kMaxRodWidthMm));
  my.rods.spacing_mm = q.require<double>("spacing_mm", Range::closed(my.rods.width_mm, L::kMaxRodSpacingMm));
  const auto e = numbers(q, "euler_deg", 3);
  my.quartz_orientation = indicatrix_in_section(find_mineral_crystallography(my.quartz_mineral),
                                                crystal_to_sample_from_bunge({radians(e[0]), radians(e[1]), radians(e[2])}));
  g.myrmekite = std::move(my);
}

// "subgrains": {"width_mm": w, "step_deg": s, "axis": [x, y, z], "wall_normal": [x, y, z]}
// (section frame). The bands cover the grain's longest extent on either side of its centre
// (the outer two take whatever of a grown grain lies further); a misorientation step above 15°
// is a high-angle boundary, a new grain rather than a subgrain (Passchier & Trouw 2005, §3.7).
void read_subgrains(const JsonReader& gr, SectionGrain& g) {
  const auto sg = gr.optional_object("subgrains");
  if (!sg) return;
  g.subgrain_mm = sg->require<double>("width_mm", Range::above(0));
  g.subgrain_step_deg = sg->require<double>("step_deg", Range::open_closed(0, 15));
  const auto a = numbers(*sg, "axis", 3), n = numbers(*sg, "wall_normal", 3);
  const glm::dvec3 axis{a[0], a[1], a[2]}, wall{n[0], n[1], n[2]};
  if (!(glm::length(axis) > 0.0)) sg->fail("axis", "the bend axis must be a non-zero vector");
  const glm::dvec2 trace_normal{wall.x, wall.y};
  if (!(glm::length(trace_normal) > 1e-6 * glm::length(wall)))
    sg->fail("wall_normal", "walls parallel to the section have no trace in it (a vertical normal)");
  g.subgrain_normal = glm::normalize(trace_normal);
  // Counted as a double first: a tiny width would overflow an int (5.0000001 counts as 5).
  const double bands = std::ceil(2.0 * g.semi_major_mm / g.subgrain_mm - 1e-9);
  if (!(bands <= 200.0)) sg->fail("width_mm", "over 401 subgrains across the grain: wider bands, please");
  const int half = static_cast<int>(bands);
  const glm::dvec3 u = glm::normalize(axis);
  for (int k = -half; k <= half; ++k) g.subgrain_rotation.push_back(axis_rotation(u, radians(k * g.subgrain_step_deg)));
}

// "alteration": {"mineral": m, "vein_mm": w, "euler_deg": [φ1, Φ, φ2]}: the grain's cracks are
// veins w wide of mineral m in that orientation (its crystal frame to the section frame).
void read_vein(const JsonReader& gr, SectionGrain& g) {
  const auto a = gr.optional_object("alteration");
  if (!a) return;
  SectionGrain::VeinFill v;
  v.mineral = a->require<std::string>("mineral");
  v.crystal = &known_mineral(*a, "mineral", v.mineral);
  v.width_mm = a->require<double>("vein_mm", Range::open_closed(0, 1));
  const auto e = numbers(*a, "euler_deg", 3);
  const glm::dmat3 L = crystal_to_sample_from_bunge({radians(e[0]), radians(e[1]), radians(e[2])});
  v.orientation = indicatrix_in_section(find_mineral_crystallography(v.mineral), L);
  g.vein = v;
}

// A needle's shape in the section from its crystal's orientation L (crystal Cartesian → section):
// its mineral's elongation (apatite's [0001]), c = L·[uvw], projected on the section.
SectionGrain::InclusionSet::Needle needle_in_section(const MineralCrystallography& mc, const glm::dmat3& L,
                                                     double size_mm, double width_mm) {
  const glm::dvec3 c = glm::normalize(L * lattice_direction(mc.cell, *mc.habit.elongation));
  const double along = std::hypot(c.x, c.y);
  SectionGrain::InclusionSet::Needle n;
  if (along > 1e-12) n.axis = {c.x / along, c.y / along};
  n.length_mm = std::max(width_mm, size_mm * along);
  return n;
}

// "inclusions": {"mineral": m, "size_mm": l, "aspect": a, "spacing_mm": s, "trail_spacing_mm": t,
//  "trail_deg": θ, "rotation_deg": ω, "fraction": f, "within": w, "habit": "trail" | "needle",
//  "euler_deg": [[φ1, Φ, φ2], ...]} (SectionGrain::InclusionSet): each listed orientation is one
// domain.
void read_inclusions(const JsonReader& gr, SectionGrain& g) {
  const auto a = gr.optional_object("inclusions");
  if (!a) return;
  a->warn_unknown_keys({"mineral", "size_mm", "aspect", "spacing_mm", "trail_spacing_mm", "trail_deg", "rotation_deg",
                        "fraction", "within", "euler_deg", "halo", "habit"});
  using L = InclusionRecipe;  // the limits a recipe's inclusions meet too (rock_recipe.h)
  SectionGrain::InclusionSet in;
  in.mineral = a->require<std::string>("mineral");
  in.crystal = &known_mineral(*a, "mineral", in.mineral);
  in.size_mm = a->require<double>("size_mm", Range::open_closed(0, L::kMaxSizeMm));
  in.width_mm = in.size_mm / a->get_or("aspect", 1.0, Range::closed(1, L::kMaxAspect));
  in.spacing_mm = a->require<double>("spacing_mm", Range::closed(in.size_mm, L::kMaxSpacingMm));
  in.trail_spacing_mm = a->get_or("trail_spacing_mm", in.spacing_mm, Range::closed(in.width_mm, L::kMaxSpacingMm));
  in.trail_rad = radians(a->get_or("trail_deg", 0.0, Range::closed(-L::kMaxTrailDeg, L::kMaxTrailDeg)));
  in.rotation_rad = radians(a->get_or("rotation_deg", 0.0, Range::closed(-L::kMaxRotationDeg, L::kMaxRotationDeg)));
  in.fraction = a->get_or("fraction", 1.0, Range::closed(0, 1));
  in.within = a->get_or("within", 1.0, Range::open_closed(0, 1));
  const MineralCrystallography* mc = find_mineral_crystallography(in.mineral);
  const InclusionHabit habit = read_inclusion_habit(*a, in.mineral, in.size_mm, in.trail_spacing_mm);
  const bool needles = habit == InclusionHabit::Needle;
  in.wedges = habit == InclusionHabit::Wedge;
  const json* list = a->find("euler_deg");
  if (!list || !list->is_array() || list->empty() || list->size() > std::size_t(L::kMaxOrientations))
    throw InputError(a->file(), a->path("euler_deg"), list ? shown(*list) : "",
                     "expected an array of 1 to " + std::to_string(L::kMaxOrientations) +
                         " orientations, each [phi1, Phi, phi2] in degrees");
  for (const json& e : *list) {
    const auto v = a->checked("euler_deg", *list, [&](const json&) {
      if (!e.is_array() || e.size() != 3) throw BadValue{"each orientation is an array of 3 numbers"};
      return std::array<double, 3>{number_value(e[0]), number_value(e[1]), number_value(e[2])};
    });
    const glm::dmat3 to_section = crystal_to_sample_from_bunge({radians(v[0]), radians(v[1]), radians(v[2])});
    in.orientations.push_back(indicatrix_in_section(mc, to_section));
    if (needles) in.needles.push_back(needle_in_section(*mc, to_section, in.size_mm, in.width_mm));
  }
  if (const auto h = a->optional_object("halo")) {
    const HaloRecipe halo = read_halo(*h, in.size_mm, in.spacing_mm, in.trail_spacing_mm);
    in.halo = SectionGrain::InclusionSet::Halo{halo.radius_mm, halo.darkening, {}};
  }
  g.inclusions = std::move(in);
}

// A halo's darkened crystals, one per zone (after the zones are read): a host that absorbs no
// light has nothing to darken, and its halo would not show.
void darken_halo(const JsonReader& gr, SectionGrain& g) {
  if (!g.has_halo()) return;
  SectionGrain::InclusionSet::Halo& h = *g.inclusions->halo;
  bool absorbing = false;
  for (const SectionZone& z : g.zones) {
    absorbing = absorbing || z.crystal->absorbing();
    h.zone_crystals.push_back(std::make_shared<const Crystal>(
        z.crystal->with_absorption_scaled(h.darkening, z.crystal->name() + " (pleochroic halo)")));
  }
  if (!absorbing)
    gr.object("inclusions").fail("halo", "a pleochroic halo darkens its host's absorption, and " + g.mineral +
                                             " has no absorption data: it would not show");
}

// The matrix grain: no shape of its own; it owns what no grown crystal reaches (its ellipse, for
// reports, is the section's extent).
void read_matrix_grain(const JsonReader& gr, SectionGrain& g, const SectionMap& m) {
  for (const char* k : {"growth", "zones", "twin", "size_mm", "aspect", "subgrains", "alteration", "inclusions", "overgrowth", "myrmekite"})
    if (gr.has(k)) gr.fail(k, "a matrix grain has no shape, growth, zones, twins, subgrains, veins, inclusions, overgrowth or myrmekite of its own");
  g.matrix = true;
  g.centre_mm = {0.0, 0.0};
  set_ellipse(g, outer({1, 0, 0}, 0.5 * m.width_mm) + outer({0, 1, 0}, 0.5 * m.height_mm) + outer({0, 0, 1}, 1.0));
  g.twin_orientation = g.orientation;
}

// Grown and ellipse grains do not share a tiling (their distances are not comparable), and one
// matrix at most fills what the crystals leave.
void check_grown(const JsonReader& r, const SectionMap& m) {
  int grown = 0, matrices = 0;
  for (const SectionGrain& g : m.grains) {
    grown += g.growth ? 1 : 0;
    matrices += g.matrix ? 1 : 0;
  }
  const int others = static_cast<int>(m.grains.size()) - grown - matrices;
  if (grown > 0 && others > 0)
    r.fail("grains", "grains with \"growth\" and grains without it cannot share a section");
  if (matrices > 1) r.fail("grains", "a section has at most one matrix grain");
  if (matrices > 0 && grown == 0) r.fail("grains", "a matrix grain needs grown crystals (\"growth\") around it");
}

// The file's keys other than "grains".
SectionMap section_header(const JsonReader& r, const std::string& path) {
  SectionMap m;
  m.path = path;
  m.name = r.get_or<std::string>("name", path);
  m.source = r.get_or<std::string>("source", "");
  if (r.has("thickness_um")) m.thickness_um = r.require<double>("thickness_um", Range::above(0));
  if (r.has("size_mm")) {
    const auto s = numbers(r, "size_mm", 2);
    if (!(s[0] > 0 && s[1] > 0)) r.fail("size_mm", "the extent must be positive");
    m.width_mm = s[0];
    m.height_mm = s[1];
  }
  return m;
}

// One grain object of section m (its header read).
SectionGrain read_section_grain(const JsonReader& gr, const SectionMap& m, GrainLookups& templates) {
  SectionGrain g;
  g.mineral = gr.require<std::string>("mineral");
  g.crystal = &templates.mineral(gr, "mineral", g.mineral);
  const MineralCrystallography* mc = templates.crystallography(g.mineral);
  try {
    if (gr.has("euler_deg")) {
      const auto e = numbers(gr, "euler_deg", 3);
      const glm::dmat3 L = crystal_to_sample_from_bunge({radians(e[0]), radians(e[1]), radians(e[2])});
      if (mc) g.lattice_to_section = L;
      g.orientation = indicatrix_in_section(mc, L);
      g.optics_stand_in = optical_orientation_is_stand_in(mc, *g.crystal);
    } else if (g.crystal->symmetry() == CrystalSymmetry::Biaxial) {
      const auto x = numbers(gr, "x_axis", 3), z = numbers(gr, "z_axis", 3);
      g.orientation = biaxial_orientation({x[0], x[1], x[2]}, {z[0], z[1], z[2]});
      // The file's X and Z are as arbitrary against the grain's drawn shape as the stand-in
      // against its lattice when the library has no orientation of the mineral to check them by.
      g.optics_stand_in = optical_orientation_is_stand_in(mc, *g.crystal);
    } else {
      const auto a = numbers(gr, "optic_axis", 3);
      g.orientation = uniaxial_orientation({a[0], a[1], a[2]});  // the whole uniaxial orientation: no stand-in
    }
  } catch (const std::invalid_argument& e) {
    throw InputError(gr.file(), gr.prefix(), gr.node().dump(), e.what());
  }
  if (gr.has("seed"))
    read_legacy_grain(gr, g);
  else if (gr.get_or("matrix", false))
    read_matrix_grain(gr, g, m);
  else
    read_grain(gr, g, m.thickness_um, templates);
  if (!g.matrix) read_subgrains(gr, g);
  if (!g.matrix) read_vein(gr, g);
  if (!g.matrix) read_inclusions(gr, g);
  if (!g.matrix) read_overgrowth(gr, g, templates);
  if (!g.matrix) read_myrmekite(gr, g);
  if (g.zones.empty()) g.zones.push_back({g.mineral, g.crystal, g.orientation, g.twin_orientation, 1.0});
  darken_halo(gr, g);
  return g;
}

SectionMap parse_section(const json& j, const std::string& path) {
  if (!j.is_object()) throw InputError(path, "", "", "a thin-section file must hold a JSON object");
  const JsonReader r(j, path);
  SectionMap m = section_header(r, path);
  GrainLookups templates;
  for (const JsonReader& gr : r.objects("grains", 1)) m.grains.push_back(read_section_grain(gr, m, templates));
  check_grown(r, m);
  m.finish();
  return m;
}

// A grown rock's section, each grain parsed as its JSON is written (rock_growth.h): the same map
// as section_from_json(rock_section_json(…)) without the whole file in memory at once. Blocks of
// grains are written and read in parallel (each thread its own habit templates, the same shapes);
// a fault is the first in file order, as the serial reader would throw it.
SectionMap parse_grown_rock(const RockRecipe& recipe, const RockGrowth& growth, std::uint64_t seed,
                            std::optional<std::uint64_t> orientation_seed, const std::string& path) {
  const json header = rock_section_header_json(recipe, seed);
  const JsonReader r(header, path);
  SectionMap m = section_header(r, path);
  const RockGrainsJson grains(recipe, growth, seed);
  m.grains.resize(grains.size());
  constexpr std::size_t kBlock = 1024;
  const std::size_t blocks = (grains.size() + kBlock - 1) / kBlock;
  std::vector<std::exception_ptr> fault(blocks);
  tbb::enumerable_thread_specific<GrainLookups> templates;
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    GrainLookups& mine = templates.local();
    try {
      for (std::size_t k = b * kBlock; k < std::min(grains.size(), (b + 1) * kBlock); ++k) {
        json grain = grains.grain(k);
        if (orientation_seed) reorient_section_grain(grain, *orientation_seed, k);
        m.grains[k] = read_section_grain(JsonReader(grain, path, "grains[" + std::to_string(k) + "]"), m, mine);
      }
    } catch (...) {
      fault[b] = std::current_exception();
    }
  });
  for (const std::exception_ptr& f : fault)
    if (f) std::rethrow_exception(f);
  if (m.grains.empty()) throw InputError(path, "grains", "[]", "expected an array of at least 1 objects");
  check_grown(r, m);
  m.finish();
  return m;
}

}  // namespace

double inclination_from_vertical_deg(const glm::dvec3& n) { return degrees(std::asin(std::min(1.0, std::abs(n.z)))); }

SectionMap section_from_json(const nlohmann::json& j, const std::string& origin) {
  try {
    return parse_section(j, origin);
  } catch (const nlohmann::json::exception& e) {  // a value of the wrong type somewhere
    throw InputError(origin, "", "", std::string("bad thin-section file: ") + e.what());
  }
}

SectionMap section_from_grown_rock(const RockRecipe& recipe, const RockGrowth& growth, std::uint64_t seed,
                                   std::optional<std::uint64_t> orientation_seed, const std::string& origin) {
  try {
    return parse_grown_rock(recipe, growth, seed, orientation_seed, origin);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(origin, "", "", std::string("bad thin-section file: ") + e.what());
  }
}

std::shared_ptr<const SectionMap> load_section(const std::string& name_or_path, std::optional<int> orientation_seed,
                                               std::optional<int> seed) {
  if (const std::string rock = rock_recipe_path(name_or_path); !rock.empty()) {
    static BuildCache<std::tuple<std::string, std::optional<int>, std::optional<int>>, SectionMap> rocks;
    return rocks.get(std::tuple{rock, orientation_seed, seed}, [&] {
      const RockRecipe recipe = read_rock_recipe(rock);
      const std::uint64_t s = seed ? static_cast<std::uint64_t>(*seed) : recipe.seed;
      std::optional<std::uint64_t> turn;
      if (orientation_seed) turn = static_cast<std::uint64_t>(*orientation_seed);
      return std::make_shared<const SectionMap>(section_from_grown_rock(recipe, grow_rock(recipe, s), s, turn, rock));
    });
  }
  if (seed) throw InputError("", "sample.seed", std::to_string(*seed), "'" + name_or_path + "' is not a rock with a recipe in assets/rocks");
  const std::string path = section_path(name_or_path);
  if (path.empty())
    throw InputError("", "sample.section", name_or_path, "no such thin-section file in assets/sections");
  static BuildCache<std::pair<std::string, std::optional<int>>, SectionMap> cache;
  return cache.get(std::pair{path, orientation_seed}, [&] {
    nlohmann::json j = read_json_file(path, "thin-section file");
    if (orientation_seed) reorient_section_grains(j, std::uint64_t(*orientation_seed));
    return std::make_shared<const SectionMap>(section_from_json(j, path));
  });
}

}  // namespace pmsim
