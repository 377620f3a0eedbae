#pragma once
// The geometry of a scene3d description in ONE Embree 3 scene: planes, boxes and meshes as Embree
// triangles, spheres as Embree sphere points, visible area lights as triangles, and SML lenses as
// Embree user geometry. Embree works in float; every hit is handed back with the object it
// belongs to, and the shading normal is recomputed in double from the description.
#include <memory>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

#include "core/lens/lens.h"
#include "core/scene3d/scene3d_description.h"

namespace pmsim {

enum class Scene3dSurfaceKind { Diffuse, Glass, Lens, Emitter };

struct Scene3dHit {
  double t = 0.0;
  glm::dvec3 point{0.0};
  glm::dvec3 normal{0.0};  // unit; outward for closed solids, the plane's normal for planes
  Scene3dSurfaceKind kind = Scene3dSurfaceKind::Diffuse;
  int object = -1;    // index into description.objects (-1 for an area light)
  int material = -1;  // index into description.materials (diffuse and glass)
  int lens = -1;      // index into Scene3dWorld::lenses()
  int light = -1;     // index into description.lights (emitter)
};

class Scene3dWorld {
 public:
  // Builds and commits the Embree scene. Lens keys are validated here (InputError naming
  // "objects[i].<key>").
  explicit Scene3dWorld(const Scene3dDescription& desc);
  ~Scene3dWorld();
  Scene3dWorld(const Scene3dWorld&) = delete;
  Scene3dWorld& operator=(const Scene3dWorld&) = delete;

  // Nearest hit with t in (t_min, t_max). Thread-safe.
  bool intersect(const glm::dvec3& origin, const glm::dvec3& dir, double t_min, double t_max,
                 Scene3dHit& hit) const;
  // True if an opaque (diffuse) surface lies on the open segment; glass, lenses and emitters let
  // shadow rays through (backward Whitted tracing cannot find refracted paths to a point light,
  // and a black shadow behind clear glass would be the larger error).
  bool opaque_between(const glm::dvec3& from, const glm::dvec3& to) const;

  const std::vector<std::unique_ptr<Lens>>& lenses() const { return lenses_; }
  const Scene3dDescription& description() const { return desc_; }
  double scene_size_mm() const { return scene_size_mm_; }

 private:
  struct GeometryInfo {
    Scene3dSurfaceKind kind;
    int object, material, lens, light;
    std::vector<glm::dvec3> tri_normals;  // per triangle, double precision
    glm::dvec3 sphere_center{0.0};
  };
  void add_triangles(const std::vector<glm::dvec3>& v, const std::vector<glm::ivec3>& t, GeometryInfo info);
  void build();
  void add_lens(const Scene3dObject& o, int object_index);

  const Scene3dDescription& desc_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<GeometryInfo> geometry_;  // by Embree geometry id
  std::vector<std::unique_ptr<Lens>> lenses_;
  double scene_size_mm_ = 1.0;
  std::string embree_message_;  // first error reported by the device
};

}  // namespace pmsim
