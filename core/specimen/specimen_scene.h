#pragma once
// A specimen in three dimensions as an Embree scene: the slide, a layer of liquid (an immersion
// liquid, or the mounting medium of a thin section) holding solid bodies — mineral fragments, or
// the grains of a section slab (core/specimen/section_slab.h) — and the cover glass. Every
// interface is triangles (the four glass faces are large quads); each triangle carries the media
// on its two sides (per-primitive medium ids into a table of media), so a hit says which medium a
// ray leaves and which it enters without any inside/outside bookkeeping.
//
// Lengths in µm; lab frame (x east, y north, z up toward the objective); z = 0 is the top of the
// slide, the liquid fills 0 < z < liquid_um, the cover glass liquid_um < z < liquid_um + cover_um.
#include <embree3/rtcore.h>

#include <memory>
#include <optional>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "core/crystal/crystal.h"
#include "core/materials/medium.h"
#include "core/specimen/grain_mount.h"
#include "core/specimen/immersion_liquid.h"

namespace pmsim {

// Medium ids: fixed ones, then fragment k (or the k-th crystal medium of a slab) is kFirstFragment + k.
enum SpecimenMediumId : int { kSpecimenAir = 0, kSpecimenGlass = 1, kSpecimenLiquid = 2, kFirstFragment = 3 };

// An isotropic medium of the stack: an immersion liquid of the series, or a library medium whose
// n(λ) is moved by a constant (a mounting medium set to another n_D by sample.medium_index, its
// dispersion kept).
struct IsotropicMedium {
  std::optional<ImmersionLiquid> liquid;
  std::shared_ptr<const Medium> medium;
  double n_offset = 0.0;
  IsotropicMedium(const ImmersionLiquid& l) : liquid(l) {}  // NOLINT: implicit, a liquid is one
  IsotropicMedium(const Medium& m, double offset = 0.0) : medium(std::make_shared<Medium>(m)), n_offset(offset) {}
  double n(double wavelength_nm) const { return liquid ? liquid->n(wavelength_nm) : medium->n(wavelength_nm) + n_offset; }
};

// A medium of the table: isotropic, or a crystal with its indicatrix axes (crystal_to_lab columns
// X, Y, Z in the specimen frame).
struct SpecimenMedium {
  std::optional<IsotropicMedium> isotropic;
  std::shared_ptr<const Crystal> crystal;  // set for crystal media
  glm::dmat3 crystal_to_lab{1.0};
};

// Triangles with the media on their two sides: front on the side of cross(v1 − v0, v2 − v0).
struct SpecimenMesh {
  std::vector<glm::dvec3> vertices;
  std::vector<glm::uvec3> triangles;
  std::vector<int> front, back;
};

struct SpecimenLayers {
  double slide_um = 1000.0;  // a standard 1 mm slide
  double cover_um = 170.0;   // a No. 1.5 cover glass (0.17 mm, the thickness objectives are corrected for)
  double liquid_um = 0.0;    // 0: the tallest fragment plus 5 µm of liquid above it
};

struct SpecimenHit {
  double t = 0.0;                // distance along the unit direction, µm
  glm::dvec3 point{0.0};
  glm::dvec3 normal{0.0, 0.0, 1.0};  // unit, pointing into the `front` medium
  int front = kSpecimenAir, back = kSpecimenAir;
  unsigned prim = 0;
};

// A fragment's horizontal bounding box (µm, lab frame): a ray that stays outside every box while
// it crosses the liquid layer meets only the plane faces of the empty stack.
struct FragmentBox {
  glm::dvec2 lo{0.0}, hi{0.0};
};

class SpecimenScene {
 public:
  // `mineral`: the fragments' crystal; `glass`: slide and cover glass; `air` above and below.
  SpecimenScene(const std::vector<FragmentShape>& fragments, const Crystal& mineral, const IsotropicMedium& liquid,
                const Medium& glass, const Medium& air, SpecimenLayers layers = {});
  // Any partition of the liquid layer into closed or space-partitioning meshes: `media` are the
  // ids kFirstFragment… in order, `mesh` uses them and kSpecimenLiquid (the fill of the layer);
  // layers.liquid_um must be set (> 0) and the mesh must lie within 0 ≤ z ≤ liquid_um.
  // `mineral`: what mineral() answers (e.g. for an empty copy of the stack).
  SpecimenScene(std::vector<SpecimenMedium> media, SpecimenMesh mesh, const Crystal& mineral,
                const IsotropicMedium& fill, const Medium& glass, const Medium& air, SpecimenLayers layers);
  ~SpecimenScene();
  SpecimenScene(const SpecimenScene&) = delete;
  SpecimenScene& operator=(const SpecimenScene&) = delete;

  // Refractive index of medium `id` at λ for light vibrating along unit `vibration` (lab frame):
  // isotropic media ignore it; a fragment uses the radius of its indicatrix along the vibration,
  // vibration_index (core/crystal/vibration_index.h) with axes = crystal_to_lab columns.
  double index(int id, double wavelength_nm, const glm::dvec3& vibration) const;
  // The crystal of medium `id` (nullptr for isotropic media, isotropic minerals included:
  // the polarization-exact tracer splits modes with it) and its crystal_to_lab (columns X, Y,
  // Z in the specimen frame; identity for isotropic media).
  const Crystal* crystal_of(int medium) const;
  glm::dmat3 orientation_of(int medium) const;
  // Intensity absorption μ (per µm, I = I0·e^(−μ·path)) of medium `id` if it is an absorbing
  // isotropic mineral (magnetite): the tracer follows such a grain as an isotropic medium, so
  // its absorption is not a mode's; 0 for every other medium.
  double isotropic_absorption_per_um(int medium, double wavelength_nm) const;
  int medium_count() const { return int(media_.size()); }
  // Nearest interface along o + t·d (d unit), t > tnear.
  bool intersect(const glm::dvec3& o, const glm::dvec3& d, double tnear, SpecimenHit& hit) const;
  // The fragment a vertical line through (x, y) passes through (−1: none): the ground truth of
  // an outline for tests and labels.
  int fragment_under(double x_um, double y_um) const;

  const SpecimenLayers& layers() const { return layers_; }
  double cover_top_z_um() const { return layers_.liquid_um + layers_.cover_um; }
  double mid_plane_z_um() const { return 0.5 * layers_.liquid_um; }
  std::size_t fragment_count() const { return media_.size() - kFirstFragment; }
  const IsotropicMedium& liquid() const { return *media_[kSpecimenLiquid].isotropic; }
  // Horizontal bounds of every solid body (a fragment each; a slab: one box of its whole mesh):
  // pixels whose rays cannot reach one see the empty stack (plane_light_image.cpp).
  const std::vector<FragmentBox>& fragment_boxes() const { return boxes_; }
  std::size_t triangle_count() const { return triangles_.size(); }
  // Triangle p's vertices and media (tests of watertightness).
  const glm::uvec3& triangle(std::size_t p) const { return triangles_[p]; }
  const glm::dvec3& vertex(std::size_t i) const { return vertices_[i]; }
  int front_of(std::size_t p) const { return front_[p]; }
  int back_of(std::size_t p) const { return back_[p]; }
  const Medium& glass() const { return glass_; }
  const Medium& air() const { return air_; }
  const Crystal& mineral() const { return *mineral_; }

 private:
  // The glass faces (quads reaching `extent_um` and far beyond) and the Embree scene.
  // robust: Embree's watertight mode (no ray slips between the triangles of a shared edge).
  void build(double extent_um, bool robust);

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  SpecimenLayers layers_;
  std::shared_ptr<const Crystal> mineral_;
  const Medium& glass_;
  const Medium& air_;
  std::vector<SpecimenMedium> media_;     // by id: air, glass, liquid, then fragments / crystals
  std::vector<FragmentBox> boxes_;        // per fragment, or one for a slab
  std::vector<glm::dvec3> vertices_;      // double copies for exact normals
  std::vector<glm::uvec3> triangles_;
  std::vector<int> front_, back_;         // per triangle: medium on the normal's side, and behind
};

}  // namespace pmsim
