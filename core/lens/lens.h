#pragma once
// The geometry of a lens (the paper's SML, §5, §8): a solid of revolution about `axis`, bounded by
// two spherical or plane caps cut at the aperture radius and the cylinder joining them (the
// ledge). `center` is the midpoint between the two vertices. `front` is the cap met first going
// along +axis; a cap radius is positive when its centre of curvature lies on the +axis side
// (so a biconvex lens has front > 0, back < 0); 0 or a missing radius means a plane.
// Give ledge_mm or thickness_mm (vertex to vertex); both must then agree to 1e-9 mm.
#include <glm/vec3.hpp>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

namespace pmsim {

class Medium;

// Mirrors the lens JSON of pmsim-trace key by key.
struct LensSpec {
  std::string glass = "N-BK7";
  glm::dvec3 center{0.0};
  glm::dvec3 axis{0.0, 0.0, 1.0};
  double radius_mm = 0.0;        // aperture (ledge cylinder) radius
  double front_radius_mm = 0.0;  // "front": {"radius_mm": ...}; 0 = plane
  double back_radius_mm = 0.0;   // "back":  {"radius_mm": ...}; 0 = plane
  std::optional<double> ledge_mm, thickness_mm;
  std::string medium = "air";
  std::string file;  // where it was read from, for error messages ("" = built in code)
};

// Throws InputError naming file, key and value. Keys: glass, center, axis, radius_mm,
// front.radius_mm, back.radius_mm, ledge_mm, thickness_mm, medium (+ free text "source", "name",
// "description"); any other key is rejected so that typos do not pass silently.
LensSpec lens_spec_from_json(const nlohmann::json& j, const std::string& file = "");
LensSpec load_lens_spec(const std::string& path);
nlohmann::json lens_spec_to_json(const LensSpec& spec);

enum class LensSurface : int { None = -1, Front = 0, Back = 1, Ledge = 2 };

struct LensHit {
  double t = 0.0;  // distance along the (unit) direction
  glm::dvec3 point{0.0};
  glm::dvec3 normal{0.0};  // unit, pointing out of the glass
  LensSurface surface = LensSurface::None;
};

// Sag of a spherical cap of signed radius R at distance r from the axis, along +axis from the
// vertex: z = R − sgn(R)·√(R² − r²) (0 for a plane).
double cap_sag_mm(double radius_mm, double r_mm);

class LensGeometry {
 public:
  // Validates (InputError with spec.file and the key): aperture > 0, |R| ≥ aperture for curved
  // caps, ledge ≥ 0 and thickness > 0 (the cap distance is monotonic in r, so these two ends
  // guarantee the caps do not cross inside the aperture), unit-able axis, finite numbers.
  explicit LensGeometry(const LensSpec& spec);

  // Nearest hit with 0 < t < t_max. `from` is the surface the origin lies on (None for a ray
  // from elsewhere): its root at t ≈ 0 is skipped analytically rather than by an epsilon.
  bool intersect(const glm::dvec3& origin, const glm::dvec3& dir, double t_max, LensSurface from,
                 LensHit& hit) const;

  // Axis-aligned box enclosing the lens.
  void bounds(glm::dvec3& lo, glm::dvec3& hi) const;

  const glm::dvec3& center() const { return center_; }
  const glm::dvec3& axis() const { return axis_; }
  double aperture_radius_mm() const { return rho_; }
  double thickness_mm() const { return thickness_; }
  double ledge_mm() const { return ledge_; }
  double front_radius_mm() const { return R_[0]; }
  double back_radius_mm() const { return R_[1]; }
  glm::dvec3 front_vertex() const { return center_ - 0.5 * thickness_ * axis_; }
  glm::dvec3 back_vertex() const { return center_ + 0.5 * thickness_ * axis_; }
  double size_mm() const { return scale_; }  // a length of the order of the lens' size

 private:
  bool cap_hit(int k, const glm::dvec3& o, const glm::dvec3& d, bool from_here, double t_eps, double& best,
               LensHit& hit) const;
  bool ledge_hit(const glm::dvec3& o, const glm::dvec3& d, bool from_here, double t_eps, double& best,
                 LensHit& hit) const;
  glm::dvec3 center_, axis_;
  double rho_ = 0, thickness_ = 0, ledge_ = 0, scale_ = 1;
  double R_[2] = {0, 0};         // front, back signed radii
  glm::dvec3 vertex_[2];         // front, back vertices
  glm::dvec3 sphere_center_[2];  // vertex + R·axis
  double z_edge_[2] = {0, 0};    // axial coordinate (from center) of each cap's rim
};

// Optical constants of a lens at one wavelength, looked up once per traced ray.
struct LensMedia {
  double n_glass = 1.5;
  double n_medium = 1.0;
  double attenuation_per_mm = 0.0;  // μ of the glass (Beer–Lambert)
};

class Lens {
 public:
  // Looks the media up in the material library; InputError names key "glass" or "medium".
  explicit Lens(const LensSpec& spec);
  Lens(const LensSpec& spec, const Medium& glass, const Medium& medium);
  const LensGeometry& geometry() const { return geometry_; }
  const LensSpec& spec() const { return spec_; }
  LensMedia media(double wavelength_nm) const;

 private:
  LensSpec spec_;
  LensGeometry geometry_;
  const Medium* glass_;
  const Medium* medium_;
};

}  // namespace pmsim
