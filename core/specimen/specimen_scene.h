#pragma once
// A specimen in three dimensions as an Embree scene: the slide, a layer of liquid with mineral
// fragments in it, the cover glass. Every interface is triangles (the four glass faces are large
// quads); each triangle carries the media on its two sides (per-primitive medium ids), so a hit
// says which medium a ray leaves and which it enters without any inside/outside bookkeeping.
//
// Lengths in µm; lab frame (x east, y north, z up toward the objective); z = 0 is the top of the
// slide, the liquid fills 0 < z < liquid_um, the cover glass liquid_um < z < liquid_um + cover_um.
#include <embree3/rtcore.h>

#include <memory>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "core/crystal/crystal.h"
#include "core/materials/medium.h"
#include "core/specimen/grain_mount.h"
#include "core/specimen/immersion_liquid.h"

namespace pmsim {

// Medium ids: fixed ones, then fragment k is kFirstFragment + k.
enum SpecimenMediumId : int { kSpecimenAir = 0, kSpecimenGlass = 1, kSpecimenLiquid = 2, kFirstFragment = 3 };

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
  SpecimenScene(const std::vector<FragmentShape>& fragments, const Crystal& mineral, const ImmersionLiquid& liquid,
                const Medium& glass, const Medium& air, SpecimenLayers layers = {});
  ~SpecimenScene();
  SpecimenScene(const SpecimenScene&) = delete;
  SpecimenScene& operator=(const SpecimenScene&) = delete;

  // Refractive index of medium `id` at λ for light vibrating along unit `vibration` (lab frame):
  // isotropic media ignore it; a fragment uses the radius of its indicatrix along the vibration,
  // 1/n'² = Σ (v·axis_i)²/n_i² (Nesse 2012 §7, the indicatrix), with axes = crystal_to_lab columns.
  double index(int id, double wavelength_nm, const glm::dvec3& vibration) const;
  // The crystal of medium `id` (nullptr for an isotropic medium: air, glass, liquid, or a fragment
  // of an isotropic mineral) and its indicatrix axes in the lab frame (columns X, Y, Z; the
  // identity for isotropic media): what the polarization-exact tracer splits modes with.
  const Crystal* crystal_of(int medium) const;
  glm::dmat3 orientation_of(int medium) const;
  // Nearest interface along o + t·d (d unit), t > tnear.
  bool intersect(const glm::dvec3& o, const glm::dvec3& d, double tnear, SpecimenHit& hit) const;
  // The fragment a vertical line through (x, y) passes through (−1: none): the ground truth of
  // an outline for tests and labels.
  int fragment_under(double x_um, double y_um) const;

  const SpecimenLayers& layers() const { return layers_; }
  double cover_top_z_um() const { return layers_.liquid_um + layers_.cover_um; }
  double mid_plane_z_um() const { return 0.5 * layers_.liquid_um; }
  std::size_t fragment_count() const { return orientations_.size(); }
  const std::vector<FragmentBox>& fragment_boxes() const { return boxes_; }
  const ImmersionLiquid& liquid() const { return liquid_; }
  const Medium& glass() const { return glass_; }
  const Medium& air() const { return air_; }
  const Crystal& mineral() const { return mineral_; }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  SpecimenLayers layers_;
  Crystal mineral_;
  ImmersionLiquid liquid_;
  const Medium& glass_;
  const Medium& air_;
  std::vector<glm::dmat3> orientations_;  // per fragment, crystal_to_lab
  std::vector<FragmentBox> boxes_;        // per fragment
  std::vector<glm::dvec3> vertices_;      // double copies for exact normals
  std::vector<glm::uvec3> triangles_;
  std::vector<int> front_, back_;         // per triangle: medium on the normal's side, and behind
};

}  // namespace pmsim
