#pragma once
// A thin section as a map of grains (assets/sections/*.json, format in docs/sections.md).
// Section coordinates are millimetres: origin at the section centre, x east, y north at stage 0°.
//
// Each grain is the central section of its crystal's shape ellipsoid (built from the mineral's
// habit: prismatic along [uvw], tabular on (hkl), else equant) cut by the section plane, and owns
// the points where its power distance to that ellipse is smallest (an anisotropic power diagram:
// near-straight boundaries, each grain roughly filling its ellipse). Inside a grain: growth zones (one optical domain each), twin
// individuals on the trace of the twin plane (only where that plane is steep enough to show) and
// cleavage cracks along the traces of the cleavage planes, filled with mounting medium.
//
// Optical domains: 0 the slide beyond the section's extent, 1 the mounting medium in cracks (both
// without a crystal), then per grain zones × twin individuals × subgrains, its vein fill and its
// inclusions' orientations, its haloes' and its dust line's.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <nlohmann/json_fwd.hpp>

#include "core/crystal/crystal.h"
#include "core/texture/grown_tiling.h"
#include "core/texture/myrmekite.h"
#include "core/texture/overgrowth_cement.h"
#include "core/texture/rock_growth.h"

namespace pmsim {

// A growth zone: the part of its grain whose normalised ellipse radius is ≤ outer_fraction
// (and > the previous zone's); the outermost zone takes the rest of the cell.
struct SectionZone {
  std::string mineral;  // with composition, e.g. "plagioclase:An55"
  const Crystal* crystal = nullptr;
  glm::dmat3 orientation{1.0};       // indicatrix columns X, Y, Z in the section frame
  glm::dmat3 twin_orientation{1.0};  // the same for the twin individual (= orientation untwinned)
  double outer_fraction = 1.0;
};

// A family of parallel cleavage cracks in a grain (the trace of one cleavage plane).
struct CleavageCracks {
  std::string plane;         // "(110)"
  double trace_rad = 0.0;    // direction of the trace, counter-clockwise from +x
  glm::dvec2 normal{0, 1};   // unit normal of the trace in the section
  double spacing_mm = 0.05;  // mean distance between cracks
  // Unit normal of the cleavage plane in the section frame (z ⟂ the section): the crack's real
  // inclination in a slab (core/specimen/section_slab.h). Its horizontal part is along `normal`.
  glm::dvec3 plane_normal{0, 1, 0};
};

// Cleavage planes within this angle of vertical show as sharp crack traces: a plane inclined θ
// from the vertical smears across t·tan θ of a t = 30 µm section (17 µm at 30°), comparable to the
// crack spacing of a good cleavage; steeper inclinations give diffuse bands not seen as cracks.
// The section's cracks and the grain report's cleavage traces both follow it.
inline constexpr double kCleavageMaxInclinationDeg = 30.0;
// Inclination of a plane (unit normal in the section frame, z ⟂ the section) from the vertical, degrees.
double inclination_from_vertical_deg(const glm::dvec3& n);

struct SectionGrain {
  std::string mineral;  // with composition text
  const Crystal* crystal = nullptr;
  glm::dmat3 orientation{1.0};  // indicatrix columns X, Y, Z in the section frame (of zone 0)
  // Crystal Cartesian frame (lattice.h) columns in the section frame, when the mineral has
  // crystallography (a unit cell) and the file gives euler_deg. Without an optical orientation in
  // the mineral file (plagioclase, microcline) orientation = lattice_to_section: X, Y, Z along
  // e1, e2, e3, a stand-in that gives such grains no published extinction angles.
  std::optional<glm::dmat3> lattice_to_section;
  // True when `orientation` is that stand-in: an anisotropic grain placed by a crystal frame
  // (euler_deg, an EBSD orientation), or a biaxial one by its x_axis/z_axis, whose mineral file
  // has no optical_orientation (issue 22: --grains' "optics": "stand-in", the teaching panel's
  // warning). Set from the mineral data where the orientation is built, never from a name list.
  bool optics_stand_in = false;

  glm::dvec2 centre_mm{0.0};
  // The grain's ellipse in the section: x·metric·x = 1 on its outline (mm⁻²; symmetric 2×2 as
  // (xx, xy, yy)). semi_major_mm / semi_minor_mm and elongation_rad (direction of the major
  // axis, counter-clockwise from +x) are its principal form.
  double metric_xx = 1.0, metric_xy = 0.0, metric_yy = 1.0;
  double semi_major_mm = 1.0, semi_minor_mm = 1.0, elongation_rad = 0.0;
  bool elongated = false;  // the habit shows in this section (aspect > 1 + 1e-6)
  // The tiling distance is cell_scale·(x·metric·x − cell_offset) (section_map.cpp).
  double cell_scale = 1.0, cell_offset = 0.0;

  bool twinned = false;  // the file asks for a twin and its plane is steep enough to show
  std::string twin_law;  // as named in the mineral file ("albite", ...); empty when untwinned
  glm::dmat3 twin_orientation{1.0};  // orientation of the twin individual (zone 0)
  double twin_trace_rad = 0.0;       // direction of the composition-plane trace
  double lamella_mm = 0.0;           // lamella width; 0: a simple twin (one composition plane)
  glm::dvec2 twin_normal{0.0, 1.0};  // unit normal of the trace in the section
  // A second set of lamellae crossing the first ("twin": {..., "cross": {"law", "lamella_mm"}}):
  // microcline's pericline twins across its albite twins, the cross-hatched (tartan) grid
  // (Deer, Howie & Zussman 2013, alkali feldspars). Its individuals are the first set's turned by
  // `op`, the second law's twin operation: four per zone, the first set's parity in bit 0 of the
  // twin index and this set's in bit 1. Only on a lamellar twin whose planes both show. Both sets'
  // lamellae are spindles (section_map.cpp in_spindle), not the even lamellae of a single set.
  struct CrossTwin {
    std::string law;
    glm::dmat3 op{1.0};                // the twin operation, in the section frame
    glm::dvec2 normal{0.0, 1.0};       // unit normal of its trace
    double lamella_mm = 0.0;
  };
  std::optional<CrossTwin> cross_twin;
  int twin_individuals() const { return twinned ? (cross_twin ? 4 : 2) : 1; }

  // Undulose extinction ("subgrains" in a section file): the lattice bent about an axis and
  // polygonized into subgrains, bands subgrain_mm wide between parallel low-angle tilt walls, each
  // band turned by one step about the bend axis from its neighbour (recovery of a bent crystal:
  // Cahn 1949, J. Inst. Metals 76, 121; Passchier & Trouw 2005, Microtectonics, §3.4 and §3.7).
  // Per band the rotation applied to every zone and twin orientation; the middle band keeps the
  // grain's own. Empty: no subgrains.
  std::vector<glm::dmat3> subgrain_rotation;
  glm::dvec2 subgrain_normal{1.0, 0.0};  // unit normal of the walls' trace in the section
  double subgrain_mm = 0.0;
  double subgrain_step_deg = 0.0;
  int subgrain_count() const { return subgrain_rotation.empty() ? 1 : static_cast<int>(subgrain_rotation.size()); }

  // Grown grains (core/texture/grown_tiling.h; "growth" in a section file; all or none of a
  // section's grains but its matrix): the tiling is by arrival time and the
  // zones are growth zones, zone outer_fraction the fraction of the growth time (from → to), so
  // zone boundaries run parallel to the crystal faces. The ellipse above is then the central
  // section of the habit ellipsoid, kept for the grain report's elongation.
  std::optional<GrainGrowth> growth;
  // The matrix (glass of a volcanic rock's groundmass): every point no grown crystal reaches.
  bool matrix = false;

  std::vector<SectionZone> zones;  // inner to outer, at least one
  std::vector<CleavageCracks> cracks;
  // Alteration along the cracks ("alteration" in a section file): the cracks are veins width_mm
  // wide filled with a secondary mineral instead of open cracks — serpentine along the fractures
  // of olivine, the mesh texture of serpentinised peridotite (Wicks & Whittaker 1977, Can.
  // Mineral. 15, 459–488). One optical domain, after the grain's others.
  struct VeinFill {
    std::string mineral;
    const Crystal* crystal = nullptr;
    glm::dmat3 orientation{1.0};  // indicatrix columns in the section frame
    double width_mm = 0.0;
  };
  std::optional<VeinFill> vein;
  // Inclusions ("inclusions" in a section file): small crystals of another mineral that the grain
  // grew round without consuming them — a poikiloblast's inclusion trails (the quartz a garnet
  // overgrew, preserving the foliation as an internal one, Si), sericite dusting a plagioclase
  // core. They lie on parallel trails trail_spacing_mm apart, one site every spacing_mm along a
  // trail, each occupied with probability `fraction` (a hash of grain, trail and site: the same in
  // every render), jittered within its cell and shaped as an ellipse size_mm long along the trail
  // and width_mm across it. Only where the growth fraction s (grown grains; the normalised ellipse
  // radius otherwise) is ≤ within. A porphyroblast that turned by rotation_rad while it grew
  // turned the trails it caught at s by rotation_rad·(1 − s) since: at s the trails run at
  // trail_rad + rotation_rad·(1 − s), curving from the core to the rim, where they meet the
  // external foliation (spiral, "snowball" Si: Rosenfeld 1970, Geol. Soc. Am. Spec. Pap. 129;
  // Passchier & Trouw 2005, Microtectonics, §7.4). One optical domain per orientation, after the
  // vein's; an inclusion takes one by hash.
  // Needles ("habit": "needle"): each inclusion is a prism size_mm long and width_mm wide along its
  // mineral's elongation (apatite's c: Nesse 2012, apatite, small prisms and needles included in
  // other minerals), seen as its projection on the section: a rectangle size_mm·|c_xy| along
  // c_xy, never shorter than its width (an end-on prism is a small basal section), width_mm
  // across. Its shape follows its orientation, so it goes extinct parallel to its length whatever
  // way it lies.
  struct InclusionSet {
    std::string mineral;
    const Crystal* crystal = nullptr;
    std::vector<glm::dmat3> orientations;  // indicatrix columns in the section frame
    // Needles: per orientation, the unit direction of c's projection on the section (east if c is
    // normal to it) and the needle's projected length, mm. Empty: inclusions along the trails.
    struct Needle {
      glm::dvec2 axis{1.0, 0.0};
      double length_mm = 0.0;
    };
    std::vector<Needle> needles;
    // Wedges ("habit": "wedge"): each inclusion a triangle size_mm long along its trail, width_mm
    // wide at its base, its apex toward the trail's direction: the cuneiform quartz rods of a
    // graphic intergrowth cut across (the runic texture; Fenn 1986, Am. Mineral. 71, 325–330;
    // MacKenzie, Donaldson & Guilford 1982, Atlas of Igneous Rocks and their Textures, graphic
    // texture), all of one host's alike. Its area is ½·size·width (an ellipse's: (π/4)·size·width).
    bool wedges = false;
    double size_mm = 0.0, width_mm = 0.0, spacing_mm = 0.0, trail_spacing_mm = 0.0;
    double fraction = 1.0, within = 1.0, trail_rad = 0.0, rotation_rad = 0.0;
    // A pleochroic halo ("halo" in a section file): the host within radius_mm of an inclusion's
    // centre, radiation-damaged by the alpha particles of its uranium and thorium, absorbs
    // `darkening` times as strongly (its optical density; its own orientation and indices). One
    // darkened crystal per zone.
    struct Halo {
      double radius_mm = 0.0, darkening = 1.0;
      std::vector<std::shared_ptr<const Crystal>> zone_crystals;
    };
    std::optional<Halo> halo;
  };
  std::optional<InclusionSet> inclusions;
  // Syntaxial overgrowth cement ("overgrowth" in a section file; core/texture/overgrowth_cement.h):
  // a detrital ball ("growth" shape "sphere") whose crystal grew on into the pores toward its
  // euhedral form, in lattice continuity: the cement's points are the grain's, in its outermost
  // zone's domains, so the grain and its overgrowth go extinct together. Only the dust line tells
  // them apart: specks of `dust` (fluid inclusions, clay, oxide) that coated the detrital surface
  // when the cement grew over it (McBride 1989; Tucker 2001, §2.9.1), each a disc size_mm across
  // touching the ball's section circle from inside, one site every spacing_mm along it, occupied
  // with probability `fraction` (a hash of grain and site). The grain's other inclusions, which it
  // brought from its source rock, stop at the dust line (s ≤ 1).
  struct Overgrowth {
    double habit_scale = 1.0;
    CrystalPolyhedron form;  // section frame, about the grain's nucleus
    struct Dust {
      std::string mineral;
      const Crystal* crystal = nullptr;  // isotropic or opaque: a speck's orientation does not show
      double size_mm = 0.0, spacing_mm = 0.0, fraction = 1.0;
    };
    std::optional<Dust> dust;
  };
  std::optional<Overgrowth> overgrowth;
  // Myrmekite ("myrmekite" in a section file; core/texture/myrmekite.h): bulbs of this grain (a
  // grown plagioclase) standing on its boundary with grains of the `host` mineral (a K-feldspar,
  // matched without its composition) and bulging into them. Sites lie one every bulb_mm of arc
  // around the grain's centre, each taken with probability `fraction` (a hash of grain and site);
  // a bulb is up to depth_mm deep and bulb_mm wide. Its points are this grain's (its outermost
  // zone, its twins and cracks), except its quartz rods, which are one orientation's domain.
  struct Myrmekite {
    std::string host;
    double depth_mm = 0.0, bulb_mm = 0.0, fraction = 1.0;
    Vermicules rods;
    std::string quartz_mineral;
    const Crystal* quartz = nullptr;
    glm::dmat3 quartz_orientation{1.0};
  };
  std::optional<Myrmekite> myrmekite;
  // Domains first_domain … first_domain + crystal_domain_count() − 1, in the order zone, twin
  // individual, subgrain (the last varying fastest); then the vein's, if any; then one per
  // inclusion orientation; then, with a halo, the crystal domains' again, darkened.
  int first_domain = 2;
  int crystal_domain_count() const { return static_cast<int>(zones.size()) * twin_individuals() * subgrain_count(); }
  int first_inclusion_domain() const { return first_domain + crystal_domain_count() + (vein ? 1 : 0); }
  // A halo's domains, after the inclusions': one per crystal domain, in the same order.
  int first_halo_domain() const {
    return first_inclusion_domain() + (inclusions ? static_cast<int>(inclusions->orientations.size()) : 0);
  }
  bool has_halo() const { return inclusions && inclusions->halo; }
  // The dust line's one domain, after the halo's.
  int dust_domain() const { return first_halo_domain() + (has_halo() ? crystal_domain_count() : 0); }
  bool has_dust() const { return overgrowth && overgrowth->dust; }
  // The myrmekite's quartz domain, after the dust line's.
  int myrmekite_domain() const { return dust_domain() + (has_dust() ? 1 : 0); }
  // An overgrown grain's detrital outline in the section: the circle where the plane cuts its
  // ball, √(r² − z²) about the nucleus (0 where the plane misses the ball).
  double detrital_section_radius_mm() const;
};

// The optical domains of a raster (an EBSD map read as a section, core/microscope/map_section.h):
// each map point owns the step_x × step_y rectangle centred on it (on a hexagonal grid the
// rectangles of every second row are shifted by half a step: a brick pattern of the hexagonal
// cells' area and neighbours), so the domain under a section point is one index computation.
struct DomainRaster {
  bool hexagonal = false;
  int columns_odd = 0, columns_even = 0, rows = 0;
  double step_x_mm = 0.0, step_y_mm = 0.0;
  double first_x_mm = 0.0, first_y_mm = 0.0;  // section position of the first point (top left)
  std::vector<std::int32_t> domain;          // per map point, in the map's order (row by row)

  // The domain under section point p; `outside` beyond the points' rectangles.
  int domain_at(const glm::dvec2& p_mm, int outside) const;
};

// Where a crystal domain lies in its grain (SectionMap::domain_part).
struct DomainPart {
  int grain = -1;  // index into grains; −1 for the slide, the medium and a raster's opaque domain
  int zone = 0, twin = 0, subgrain = 0;
  bool vein = false;  // the grain's vein fill (SectionGrain::vein); zone, twin, subgrain then 0
  int inclusion = -1;  // the orientation of the grain's inclusions (SectionGrain::inclusions); likewise
  bool halo = false;   // the host in an inclusion's pleochroic halo (zone, twin and subgrain as the host's)
  bool dust = false;   // a speck of the grain's dust line (SectionGrain::Overgrowth::Dust)
  bool myrmekite = false;  // a quartz rod of the grain's myrmekite (SectionGrain::Myrmekite)
};

class SectionMap {
 public:
  static constexpr int kSlideDomain = 0;
  static constexpr int kMediumDomain = 1;

  std::string name, source, path;
  double thickness_um = 30.0;
  std::vector<SectionGrain> grains;
  // The section's extent (centred on the origin, mm); beyond it the field shows the slide.
  double width_mm = 4.0, height_mm = 4.0;
  // Width of a cleavage crack (mm): thin dark lines at 40×, sub-pixel at 4×.
  double crack_width_mm = 0.003;

  // Ground-truth label of a domain: 0 for the mounting medium or the slide, k ≥ 1 for grain k
  // (grains[k − 1]: file order, so the same k in every render of the same section).
  int grain_label(int domain) const { return domain < 2 || domain_grain_[domain] < 0 ? 0 : domain_grain_[domain] + 1; }
  const SectionGrain& grain_by_label(int k) const { return grains[k - 1]; }

  // Optical domain under a section point (mm).
  int domain_at(const glm::dvec2& p_mm) const;
  // The crack family (index into grains[grain].cracks) whose open crack covers p (domain_at gives
  // kMediumDomain there); −1 (and grain −1) elsewhere. min_width_mm > crack_width_mm widens the
  // cracks (a grid coarser than a crack samples every crack it crosses, not a dashed subset).
  int crack_family_at(const glm::dvec2& p_mm, int& grain, double min_width_mm = 0.0) const;
  // The domain a crack of grain `grain` shows: its vein fill's, or kMediumDomain (an open crack).
  int crack_domain(int grain) const;
  int domain_count() const { return static_cast<int>(domain_grain_.size()); }
  // Crystal (nullptr for slide and medium), orientation and mineral name of a domain.
  const Crystal* crystal_of_domain(int d) const;
  const glm::dmat3& orientation_of_domain(int d) const;
  const std::string& mineral_of_domain(int d) const;
  DomainPart domain_part(int d) const;

  // A raster section (an EBSD map): domain_at looks points up here, not in the grain tiling; the
  // grains are the map's reconstructed grains and their zones its orientation clusters. Null for
  // the sections of assets/sections.
  std::shared_ptr<const DomainRaster> raster;
  // A raster's opaque domain (non-indexed points shown black, sample.nonindexed=black): set before
  // finish(), which then adds it after the grains' domains; −1 when there is none.
  bool has_opaque_domain = false;
  int opaque_domain() const { return has_opaque_domain ? domain_count() - 1 : -1; }
  bool is_opaque(int d) const { return has_opaque_domain && d == domain_count() - 1; }

  // Assigns the domains of every grain and builds the lookup grid domain_at uses (parsing calls
  // it; call it again after changing grains). Results equal the exhaustive search's.
  void finish();
  // The grain whose cell contains p, by testing every grain (what the grid must reproduce).
  int nearest_grain_exhaustive(const glm::dvec2& p_mm) const;
  // The myrmekite bulbs of the section (SectionGrain::Myrmekite); null without any.
  const MyrmekiteBulbs* myrmekite_bulbs() const { return bulbs_.get(); }

 private:
  int nearest_grain(const glm::dvec2& p_mm) const;
  // Grown sections: the tiling of their crystals, each crystal's grain, and the matrix grain (−1
  // without one).
  std::shared_ptr<const GrownTiling> grown_;
  std::vector<int> grown_grain_;
  // The overgrowths of grown grains (their pore points), and each one's grain.
  std::shared_ptr<const OvergrowthCement> cement_;
  std::vector<int> cement_grain_;
  int grown_owner(int crystal, const glm::dvec2& p_mm, bool exhaustive) const;
  // Myrmekite (SectionGrain::Myrmekite): every bulb, and per grain whether its mineral is some
  // myrmekite's host (only those grains' points are looked up among the bulbs).
  std::shared_ptr<const MyrmekiteBulbs> bulbs_;
  std::vector<char> hosts_bulbs_;
  void place_myrmekite();
  // The bulb of grain gi holding p beyond gi's own tiling cell (in its host), or −1.
  int myrmekite_bulb_of(int gi, const glm::dvec2& p_mm) const;
  int matrix_grain_ = -1;
  int domain_in_grain(int grain, const glm::dvec2& p_mm) const;
  int crack_family_in_grain(int grain, const glm::dvec2& p_mm, double crack_mm) const;

  std::vector<int> domain_grain_;  // per domain: grain index, −1 for slide and medium
  std::vector<glm::dmat3> domain_orientation_;  // per domain (identity without a crystal)
  // Grid over the section's extent; per cell the grains that can be nearest in it, in index order.
  int cells_x_ = 0, cells_y_ = 0;
  double cell_mm_ = 1.0;
  std::vector<int> cell_start_, cell_grains_;
};

// Builds a section from a parsed file (`origin` names it in messages); throws InputError naming
// file, key and value on bad content, an unknown mineral or an unknown twin law.
SectionMap section_from_json(const nlohmann::json& j, const std::string& origin);

// The section of a grown rock (core/texture/rock_growth.h), optionally with its grains turned
// (orientation seed, section_reorient.h): equal to section_from_json of rock_section_json, each
// grain parsed as it is written instead of the whole file held as one JSON value.
SectionMap section_from_grown_rock(const RockRecipe& recipe, const RockGrowth& growth, std::uint64_t seed,
                                   std::optional<std::uint64_t> orientation_seed, const std::string& origin);

// Loads (once, cached by resolved path and seed) a section file; with an orientation seed its
// grains are given new orientations first (sample.orientation_seed, section_reorient.h).
// A rock name with a recipe (assets/rocks, or a recipe file's path) is grown by the texture
// engine from `seed` (its recipe's seed when unset; core/texture/rock_growth.h), once per seed.
std::shared_ptr<const SectionMap> load_section(const std::string& name_or_path,
                                               std::optional<int> orientation_seed = std::nullopt,
                                               std::optional<int> seed = std::nullopt);

}  // namespace pmsim
