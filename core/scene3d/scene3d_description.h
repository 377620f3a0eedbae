#pragma once
// The description of a general 3-D scene (JSON "type": "scene3d", assets/scenes3d/*.json): a
// pinhole camera with an optional rotatable polarizing filter, point and rectangular area lights
// with a CIE illuminant's spectrum, diffuse and glass materials, and objects (planes, boxes,
// spheres, triangle meshes, SML lenses). Lengths in mm. The loader checks every key and throws
// InputError naming the file, the key path and the value.
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "core/optics/interface_model.h"
#include "core/spectrum/illuminant.h"

namespace pmsim {

struct Scene3dCamera {
  glm::dvec3 position{0.0, 0.0, 100.0};
  glm::dvec3 look_at{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fov_deg = 40.0;  // vertical field of view
  int width = 320, height = 240;
  int samples_per_pixel = 1;  // n×n stratified sub-pixel grid (n = samples_per_pixel)
  // Ideal linear polarizer in front of the lens; transmission axis at this angle from the image's
  // right-hand direction, counter-clockwise as the camera sees it. Absent: no filter.
  std::optional<double> filter_angle_deg;
};

enum class Scene3dMode { Spectral, Rgb };

struct Scene3dRenderSettings {
  Scene3dMode mode = Scene3dMode::Spectral;
  int wavelengths = 81;  // spectral: uniform 380–780 nm (81 = 5 nm steps, the paper's nSp)
  int max_depth = 8;     // Whitted tree depth (surface interactions)
  int lens_depth = 5;    // the paper's dT: internal reflections followed inside a lens
  FresnelModel fresnel = FresnelModel::Exact;  // render.fresnel: exact|schlick
  TirMode tir = TirMode::Stop;                 // the paper's SML mode 1 (stop) or 2 (split into ⟂, ∥)
  double exposure = 1.0;                       // multiplies the linear RGB result
  glm::dvec3 background_rgb{0.0};              // radiance of rays leaving the scene (linear sRGB)
  double ambient = 0.0;                        // Whitted's ambient term, fraction of the diffuse colour
};

struct Scene3dLight {
  enum class Type { Point, Area } type = Type::Point;
  Illuminant emission = Illuminant::D65;
  // Point: radiant intensity (relative units per sr) at position.
  glm::dvec3 position{0.0};
  double intensity = 1.0;
  // Area: a one-sided rectangle emitting along +normal with constant radiance.
  glm::dvec3 center{0.0}, normal{0.0, 0.0, -1.0}, u_axis{1.0, 0.0, 0.0};
  glm::dvec2 size_mm{10.0, 10.0};
  double radiance = 1.0;
  int samples = 4;      // n×n stratified samples for soft shadows
  bool visible = true;  // camera and reflected rays see the emitting rectangle
};

struct Scene3dMaterial {
  enum class Type { Diffuse, Glass } type = Type::Diffuse;
  std::string name;
  // Diffuse: Lambertian, one colour or a pattern of colours (linear sRGB), upsampled to a
  // spectral reflectance with Smits (1999).
  std::vector<glm::dvec3> colors{glm::dvec3(0.8)};
  enum class Pattern { Solid, Stripes, Checker } pattern = Pattern::Solid;
  double period_mm = 10.0;
  // Glass: a medium of the material library.
  std::string medium = "N-BK7";
};

struct Scene3dObject {
  enum class Type { Plane, Box, Sphere, Mesh, Lens } type = Type::Plane;
  std::string key;    // "objects[3]" for messages
  int material = -1;  // index into Scene3dDescription::materials (not used by lenses)
  glm::dvec3 center{0.0};
  // Plane: a finite rectangle.
  glm::dvec3 normal{0.0, 1.0, 0.0}, u_axis{1.0, 0.0, 0.0};
  glm::dvec2 size_mm{100.0, 100.0};
  // Box: full edge lengths, rotated by rotation_deg (x, then y, then z) about its centre.
  glm::dvec3 box_size_mm{10.0}, rotation_deg{0.0};
  double radius_mm = 5.0;             // sphere
  std::vector<glm::dvec3> vertices;   // mesh
  std::vector<glm::ivec3> triangles;  // mesh
  nlohmann::json lens;                // lens: the LensSpec keys, parsed by the lens module
};

struct Scene3dDescription {
  std::string file;
  Scene3dCamera camera;
  Scene3dRenderSettings render;
  std::vector<Scene3dLight> lights;
  std::vector<Scene3dMaterial> materials;
  std::vector<Scene3dObject> objects;
};

// Validates and converts. `file` names the source in error messages (may be "").
Scene3dDescription parse_scene3d(const nlohmann::json& j, const std::string& file);
// Reads and parses a scene file; relative mesh "file" paths are resolved against its folder.
Scene3dDescription load_scene3d_file(const std::string& path);

}  // namespace pmsim
