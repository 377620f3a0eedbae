#include "core/microscope/map_section.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <mutex>

#include <glm/gtc/quaternion.hpp>

#include "core/base/build_cache.h"
#include "core/base/input_error.h"
#include "core/crystal/mineral_crystallography.h"
#include "core/ebsd/ebsd_frames.h"
#include "core/ebsd/laue_rotations.h"
#include "core/ebsd/phase_names.h"
#include "core/ebsd/read_orientation_map.h"
#include "core/microscope/sample_source.h"

namespace pmsim {

namespace {

// What a map phase is on the section.
struct PhaseUse {
  enum Kind { Unused, None, Isotropic, Mineral } kind = Unused;
  std::string mineral;  // as mapped ("olivine:Fo90")
  const Crystal* crystal = nullptr;
  const MineralCrystallography* crystallography = nullptr;  // with an optical orientation, else null
  glm::dmat3 vendor_frame{1.0};
};

// The grain's outline as the ellipse of the same second moments: a uniform ellipse of semi-axes
// a, b has variances a²/4 and b²/4 along them. Each point adds its step rectangle's own variance
// (step²/12), so that a grain of one point or one row is not degenerate.
void set_moment_ellipse(SectionGrain& g, double sxx, double sxy, double syy) {
  const double tr = sxx + syy, det = sxx * syy - sxy * sxy;
  const double disc = std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
  const double lmax = 0.5 * tr + disc, lmin = std::max(0.5 * tr - disc, 1e-30);
  g.semi_major_mm = 2.0 * std::sqrt(lmax);
  g.semi_minor_mm = 2.0 * std::sqrt(lmin);
  const double ang = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  g.elongation_rad = ang < 0 ? ang + M_PI : ang;
  const double c = std::cos(g.elongation_rad), s = std::sin(g.elongation_rad);
  const double ia = 1.0 / (g.semi_major_mm * g.semi_major_mm), ib = 1.0 / (g.semi_minor_mm * g.semi_minor_mm);
  g.metric_xx = ia * c * c + ib * s * s;
  g.metric_xy = (ia - ib) * c * s;
  g.metric_yy = ia * s * s + ib * c * c;
  g.elongated = g.semi_major_mm > g.semi_minor_mm * (1.0 + 1e-6);
}

// The file's size and modification time are part of the key: a map rewritten on disk (a new
// export under the same name) is read again.
std::string cache_key(const std::string& path, const std::map<std::string, std::string>& phases, NonIndexed ni) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  const auto time = std::filesystem::last_write_time(path, ec).time_since_epoch().count();
  std::string k = path + '\n' + std::to_string(size) + '\n' + std::to_string(time) + '\n' +
                  (ni == NonIndexed::Black ? "black" : "medium");
  for (const auto& [a, b] : phases) k += '\n' + a + '\t' + b;
  return k;
}

std::mutex& facts_mutex() {
  static std::mutex mu;
  return mu;
}
std::map<const SectionMap*, MapSectionFacts>& facts_table() {
  static std::map<const SectionMap*, MapSectionFacts> t;
  return t;
}

}  // namespace

SectionMap section_from_orientation_map(const OrientationMap& m, const std::map<std::string, std::string>& phases,
                                        NonIndexed nonindexed, const std::string& file, MapSectionFacts* facts) {
  const std::size_t n = m.size();
  // Phases the points use, mapped to minerals (an unmapped one is bad input).
  std::vector<PhaseUse> use(m.phases.size() + 1);
  for (std::size_t i = 0; i < n; ++i) {
    const int p = m.phase[i];
    if (p == 0 || use[p].kind != PhaseUse::Unused) continue;
    const EbsdPhase& ph = m.phases[p - 1];
    PhaseUse& u = use[p];
    u.mineral = map_phase_name(ph.name, phases, file);
    if (u.mineral == "none") {
      u.kind = PhaseUse::None;
    } else if (u.mineral == "isotropic") {
      u.kind = PhaseUse::Isotropic;
    } else {
      u.kind = PhaseUse::Mineral;
      u.crystal = &find_mineral(u.mineral);
      const MineralCrystallography* mc = find_mineral_crystallography(u.mineral);
      u.crystallography = mc && mc->orientation ? mc : nullptr;
    }
    u.vendor_frame = vendor_crystal_frame(m.vendor, ph.system, ph.cell);
  }
  // Per point: its crystal-to-section rotation (pmsim's frames) and whether it forms grains.
  std::vector<glm::quat> q(n, glm::quat(1, 0, 0, 0));
  std::vector<std::uint8_t> in_grain(n, 0);
  std::size_t indexed = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int p = m.phase[i];
    if (p == 0) continue;
    ++indexed;
    if (use[p].kind == PhaseUse::None) continue;
    in_grain[i] = 1;
    q[i] = glm::quat(glm::quat_cast(crystal_to_section(m.vendor, use[p].vendor_frame, m.euler(i))));
  }
  std::vector<std::vector<glm::dquat>> sym(m.phases.size() + 1);
  for (std::size_t p = 1; p <= m.phases.size(); ++p) sym[p] = laue_rotations(m.phases[p - 1].laue_group);
  GrainReconstructionOptions opt;
  opt.boundary_deg = kGrainBoundaryDeg;
  opt.cluster_deg = kClusterToleranceDeg;
  const MapGrains mg = reconstruct_grains(m, q, in_grain, sym, opt);

  SectionMap s;
  s.path = m.file;
  s.name = m.file;
  s.source = std::string("EBSD map (") + ebsd_vendor_name(m.vendor) + ")";
  const double step_x_mm = m.step_x_um * 1e-3, step_y_mm = (m.rows > 1 ? m.step_y_um : m.step_x_um) * 1e-3;
  s.width_mm = m.width_um() * 1e-3 + step_x_mm;
  s.height_mm = m.height_um() * 1e-3 + step_y_mm;
  s.crack_width_mm = 0.0;
  // Grain moments (centroid, second moments) from the points' positions.
  const std::size_t ng = mg.grain_phase.size();
  std::vector<glm::dvec2> sum(ng, glm::dvec2(0.0));
  std::vector<glm::dvec3> sum2(ng, glm::dvec3(0.0));
  for (std::size_t i = 0; i < n; ++i) {
    const int gi = mg.grain_of_point[i];
    if (gi < 0) continue;
    const glm::dvec2 p = section_position_mm(m, i);
    sum[gi] += p;
    sum2[gi] += glm::dvec3(p.x * p.x, p.x * p.y, p.y * p.y);
  }
  // Per cluster: its zone index in its grain (isotropic grains: all zone 0).
  std::vector<std::int32_t> zone_of_cluster(mg.cluster_orientation.size(), 0);
  s.grains.reserve(ng);
  for (std::size_t gi = 0; gi < ng; ++gi) {
    const PhaseUse& u = use[mg.grain_phase[gi]];
    SectionGrain g;
    g.mineral = u.kind == PhaseUse::Isotropic ? "isotropic" : u.mineral;
    g.crystal = u.crystal;
    const double np = static_cast<double>(mg.grain_points[gi]);
    g.centre_mm = sum[gi] / np;
    const double sxx = sum2[gi].x / np - g.centre_mm.x * g.centre_mm.x + step_x_mm * step_x_mm / 12.0;
    const double sxy = sum2[gi].y / np - g.centre_mm.x * g.centre_mm.y;
    const double syy = sum2[gi].z / np - g.centre_mm.y * g.centre_mm.y + step_y_mm * step_y_mm / 12.0;
    set_moment_ellipse(g, sxx, sxy, syy);
    const bool isotropic = !u.crystal || u.crystal->symmetry() == CrystalSymmetry::Isotropic;
    const int first = mg.grain_first_cluster[gi], count = mg.grain_clusters[gi];
    int largest = first;
    for (int c = first; c < first + count; ++c)
      if (mg.cluster_points[c] > mg.cluster_points[largest]) largest = c;
    auto frames = [&](int c, glm::dmat3& orientation, glm::dmat3& lattice) {
      lattice = glm::mat3_cast(glm::dquat(mg.cluster_orientation[c]));
      // Without an optical orientation in the mineral file the crystal frame stands for the
      // indicatrix axes, as for a section file's euler_deg (section_map.h).
      orientation = u.crystallography ? lattice * u.crystallography->indicatrix_axes : lattice;
    };
    glm::dmat3 lattice;
    frames(largest, g.orientation, lattice);
    if (u.crystallography) g.lattice_to_section = lattice;
    if (g.crystal) g.optics_stand_in = optical_orientation_is_stand_in(u.crystallography, *g.crystal);
    if (isotropic) {
      g.zones.push_back({g.mineral, g.crystal, g.orientation, g.orientation, 1.0});
    } else {
      for (int c = first; c < first + count; ++c) {
        SectionZone z{g.mineral, g.crystal, glm::dmat3(1.0), glm::dmat3(1.0), 1.0};
        glm::dmat3 l;
        frames(c, z.orientation, l);
        z.twin_orientation = z.orientation;
        zone_of_cluster[c] = c - first;
        g.zones.push_back(z);
      }
    }
    g.twin_orientation = g.orientation;
    s.grains.push_back(std::move(g));
  }
  auto raster = std::make_shared<DomainRaster>();
  raster->hexagonal = m.grid == MapGrid::Hexagonal;
  raster->columns_odd = m.columns_odd;
  raster->columns_even = m.columns_even;
  raster->rows = m.rows;
  raster->step_x_mm = step_x_mm;
  raster->step_y_mm = step_y_mm;
  if (n > 0) {
    const glm::dvec2 first = section_position_mm(m, 0);
    raster->first_x_mm = first.x;
    raster->first_y_mm = first.y;
  }
  s.raster = raster;
  s.has_opaque_domain = nonindexed == NonIndexed::Black;
  s.finish();
  raster->domain.resize(n);
  const int non_indexed_domain = s.has_opaque_domain ? s.opaque_domain() : SectionMap::kMediumDomain;
  for (std::size_t i = 0; i < n; ++i) {
    const int gi = mg.grain_of_point[i];
    if (gi >= 0)
      raster->domain[i] = s.grains[gi].first_domain + zone_of_cluster[mg.cluster_of_point[i]];
    else
      raster->domain[i] = m.phase[i] == 0 ? non_indexed_domain : SectionMap::kMediumDomain;  // phase "none"
  }
  if (facts) {
    facts->points = n;
    facts->indexed = indexed;
    facts->grains = ng;
    facts->clusters = mg.cluster_orientation.size();
    facts->domains = static_cast<std::size_t>(s.domain_count());
    facts->columns = std::max(m.columns_odd, m.columns_even);
    facts->rows = m.rows;
    facts->step_x_um = m.step_x_um;
    facts->step_y_um = m.rows > 1 ? m.step_y_um : m.step_x_um;
    facts->vendor = ebsd_vendor_name(m.vendor);
    facts->warnings = m.warnings;
  }
  return s;
}

std::shared_ptr<const SectionMap> load_map_section(const std::string& path_given,
                                                   const std::map<std::string, std::string>& phases,
                                                   NonIndexed nonindexed) {
  const std::string path = section_path(path_given);
  if (path.empty()) throw InputError("", "sample.section", path_given, "no such EBSD map file");
  const std::string key = cache_key(path, phases, nonindexed);
  static BuildCache<std::string, SectionMap> cache;
  return cache.get(key, [&] {
    const OrientationMap m = read_orientation_map(path);
    MapSectionFacts facts;
    auto s = std::make_shared<const SectionMap>(section_from_orientation_map(m, phases, nonindexed, path, &facts));
    std::lock_guard<std::mutex> lock(facts_mutex());
    facts_table()[s.get()] = std::move(facts);
    return s;
  });
}

const MapSectionFacts* map_section_facts(const SectionMap& section) {
  std::lock_guard<std::mutex> lock(facts_mutex());
  const auto it = facts_table().find(&section);
  return it == facts_table().end() ? nullptr : &it->second;
}

std::string map_section_summary(const MapSectionFacts& f) {
  return "EBSD map: " + std::to_string(f.points) + " points (" + std::to_string(f.indexed) + " indexed), " +
         std::to_string(f.grains) + " grains (boundaries > " +
         std::to_string(static_cast<int>(kGrainBoundaryDeg)) + "°), " + std::to_string(f.clusters) +
         " orientation clusters (within " + std::to_string(kClusterToleranceDeg).substr(0, 3) +
         "°): " + std::to_string(f.domains) + " optical domains";
}

std::shared_ptr<const SectionMap> load_scene_section(const Scene& scene) {
  if (is_orientation_map_path(scene.sample.section))
    return load_map_section(scene.sample.section, scene.sample.phases, scene.sample.nonindexed);
  return load_section(scene.sample.section, scene.sample.orientation_seed, scene.sample.seed);
}

}  // namespace pmsim
