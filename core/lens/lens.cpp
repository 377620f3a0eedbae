#include "core/lens/lens.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/materials/medium.h"

namespace pmsim {

namespace {

using json = nlohmann::json;

std::string show(const json& v) { return v.dump(); }

glm::dvec3 get_vec3(const JsonReader& r, const char* key) {
  const auto a = r.require<std::array<double, 3>>(key);
  return {a[0], a[1], a[2]};
}

// front/back: {"radius_mm": R}, null or absent (a plane).
double get_cap(const JsonReader& r, const char* key) {
  if (!r.has(key) || r.find(key)->is_null()) return 0.0;
  const JsonReader cap = r.object(key);
  cap.refuse_unknown_keys({"radius_mm"});
  if (!cap.has("radius_mm") || cap.find("radius_mm")->is_null()) return 0.0;
  return cap.require<double>("radius_mm");
}

// Distance between the two cap rims along the axis when the vertices are `thickness` apart.
double ledge_from_thickness(double thickness, double R1, double R2, double rho) {
  return thickness + cap_sag_mm(R2, rho) - cap_sag_mm(R1, rho);
}

}  // namespace

double cap_sag_mm(double R, double r) {
  if (R == 0.0) return 0.0;
  // R − sgn(R)√(R² − r²) written as r²/(R + sgn(R)√(R² − r²)) to avoid cancellation for R ≫ r.
  const double root = std::sqrt(std::max(0.0, (R - r) * (R + r)));
  return r * r / (R + std::copysign(root, R));
}

LensSpec lens_spec_from_json(const json& j, const std::string& file) {
  if (!j.is_object()) throw InputError(file, "", show(j).substr(0, 60), "a lens must be a JSON object");
  const JsonReader r(j, file);
  r.refuse_unknown_keys({"glass", "center", "axis", "radius_mm", "front", "back", "ledge_mm", "thickness_mm",
                         "medium", "source", "name", "description"});
  LensSpec s;
  s.file = file;
  s.glass = r.require<std::string>("glass");
  s.medium = r.get_or<std::string>("medium", s.medium);
  if (r.has("center")) s.center = get_vec3(r, "center");
  if (r.has("axis")) s.axis = get_vec3(r, "axis");
  s.radius_mm = r.require<double>("radius_mm");
  s.front_radius_mm = get_cap(r, "front");
  s.back_radius_mm = get_cap(r, "back");
  s.ledge_mm = r.optional<double>("ledge_mm");
  s.thickness_mm = r.optional<double>("thickness_mm");
  if (!s.ledge_mm && !s.thickness_mm) throw InputError(file, "ledge_mm", "", "give ledge_mm or thickness_mm");
  return s;
}

LensSpec load_lens_spec(const std::string& path) {
  return lens_spec_from_json(read_json_file(path, "lens file"), path);
}

json lens_spec_to_json(const LensSpec& s) {
  json j;
  j["glass"] = s.glass;
  j["center"] = {s.center.x, s.center.y, s.center.z};
  j["axis"] = {s.axis.x, s.axis.y, s.axis.z};
  j["radius_mm"] = s.radius_mm;
  j["front"] = {{"radius_mm", s.front_radius_mm}};
  j["back"] = {{"radius_mm", s.back_radius_mm}};
  if (s.ledge_mm) j["ledge_mm"] = *s.ledge_mm;
  if (s.thickness_mm) j["thickness_mm"] = *s.thickness_mm;
  j["medium"] = s.medium;
  return j;
}

LensGeometry::LensGeometry(const LensSpec& s) {
  const std::string& f = s.file;
  auto num = [](double x) {
    std::ostringstream o;
    o.precision(17);
    o << x;
    return o.str();
  };
  const double alen = glm::length(s.axis);
  if (!(alen > 1e-12) || !std::isfinite(alen))
    throw InputError(f, "axis", "[" + num(s.axis.x) + "," + num(s.axis.y) + "," + num(s.axis.z) + "]",
                     "axis must be a non-zero vector");
  axis_ = s.axis / alen;
  center_ = s.center;
  // Every length within a kilometre: far beyond any microscope or camera, and inside the range
  // where the ray–sphere algebra (squares of distances, products with radii) stays finite and
  // resolves a micrometre. A centre at 3e105 mm once turned a traced ray into NaN (fuzz finding
  // regressions/trace_lens/T1_*).
  constexpr double kMaxLength_mm = 1e6;
  const char* ckey[3] = {"center[0]", "center[1]", "center[2]"};
  for (int k = 0; k < 3; ++k)
    if (!(std::abs(center_[k]) <= kMaxLength_mm))
      throw InputError(f, ckey[k], num(center_[k]), "must be within ±1e6 mm");
  rho_ = s.radius_mm;
  if (!(rho_ > 0.0) || !std::isfinite(rho_))
    throw InputError(f, "radius_mm", num(rho_), "aperture radius must be > 0");
  if (!(rho_ <= kMaxLength_mm)) throw InputError(f, "radius_mm", num(rho_), "must be at most 1e6 mm");
  R_[0] = s.front_radius_mm;
  R_[1] = s.back_radius_mm;
  const char* rkey[2] = {"front.radius_mm", "back.radius_mm"};
  for (int k = 0; k < 2; ++k) {
    if (!std::isfinite(R_[k])) throw InputError(f, rkey[k], num(R_[k]), "must be finite");
    if (std::abs(R_[k]) > 1e3 * kMaxLength_mm)  // 1e9 mm: already a plane to 1e-13 over 1 km
      throw InputError(f, rkey[k], num(R_[k]), "|radius| must be at most 1e9 mm (0 for a plane)");
    if (R_[k] != 0.0 && std::abs(R_[k]) < rho_)
      throw InputError(f, rkey[k], num(R_[k]),
                       "|radius| must be at least the aperture radius_mm " + num(rho_));
  }
  const double sag1 = cap_sag_mm(R_[0], rho_), sag2 = cap_sag_mm(R_[1], rho_);
  if (s.thickness_mm) {
    thickness_ = *s.thickness_mm;
    ledge_ = ledge_from_thickness(thickness_, R_[0], R_[1], rho_);
    if (s.ledge_mm && std::abs(*s.ledge_mm - ledge_) > 1e-9)
      throw InputError(
          f, "ledge_mm", num(*s.ledge_mm),
          "disagrees with thickness_mm " + num(thickness_) + " (implies ledge_mm " + num(ledge_) + ")");
  } else {
    ledge_ = *s.ledge_mm;
    thickness_ = ledge_ - sag2 + sag1;
  }
  if (!(thickness_ <= kMaxLength_mm))
    throw InputError(f, s.thickness_mm ? "thickness_mm" : "ledge_mm",
                     num(s.thickness_mm ? *s.thickness_mm : *s.ledge_mm), "must be at most 1e6 mm");
  if (!(thickness_ > 0.0))
    throw InputError(
        f, s.thickness_mm ? "thickness_mm" : "ledge_mm", num(s.thickness_mm ? *s.thickness_mm : *s.ledge_mm),
        "the caps cross on the axis (vertex-to-vertex thickness " + num(thickness_) + " mm must be > 0)");
  if (!(ledge_ >= 0.0))
    throw InputError(f, s.ledge_mm ? "ledge_mm" : "thickness_mm",
                     num(s.ledge_mm ? *s.ledge_mm : *s.thickness_mm),
                     "the caps cross inside the aperture (ledge height " + num(ledge_) + " mm must be ≥ 0)");
  vertex_[0] = center_ - 0.5 * thickness_ * axis_;
  vertex_[1] = center_ + 0.5 * thickness_ * axis_;
  for (int k = 0; k < 2; ++k) sphere_center_[k] = vertex_[k] + R_[k] * axis_;
  z_edge_[0] = -0.5 * thickness_ + sag1;
  z_edge_[1] = 0.5 * thickness_ + sag2;
  scale_ = std::max({rho_, thickness_, ledge_});
}

bool LensGeometry::cap_hit(int k, const glm::dvec3& o, const glm::dvec3& d, bool from_here, double t_eps,
                           double& best, LensHit& hit) const {
  const double R = R_[k];
  double ts[2];
  int nt = 0;
  if (R == 0.0) {
    if (from_here) return false;  // a straight ray cannot meet its own plane again
    const double dn = glm::dot(d, axis_);
    if (dn == 0.0) return false;
    ts[nt++] = glm::dot(vertex_[k] - o, axis_) / dn;
  } else {
    // |o + t d − C|² = R², stable form (Haines et al., Ray Tracing Gems ch. 7): h = w − b·d.
    const glm::dvec3 w = o - sphere_center_[k];
    const double b = glm::dot(w, d);
    const glm::dvec3 h = w - b * d;
    const double disc = R * R - glm::dot(h, h);
    if (disc < 0.0) return false;
    const double q = -b - std::copysign(std::sqrt(disc), b);
    if (from_here) {
      ts[nt++] = q;  // the other root, c/q, is the origin itself (c ≈ 0)
    } else {
      const double c = glm::dot(w, w) - R * R;
      ts[nt++] = q;
      if (q != 0.0) ts[nt++] = c / q;
    }
  }
  bool found = false;
  for (int i = 0; i < nt; ++i) {
    const double t = ts[i];
    if (!(t > t_eps) || !(t < best)) continue;
    const glm::dvec3 p = o + t * d;
    const glm::dvec3 w = p - center_;
    const double z = glm::dot(w, axis_);
    const glm::dvec3 rv = w - z * axis_;
    if (glm::dot(rv, rv) > rho_ * rho_ * (1.0 + 1e-12)) continue;
    glm::dvec3 n;
    if (R == 0.0) {
      n = k == 0 ? -axis_ : axis_;
    } else {
      const glm::dvec3 ws = p - sphere_center_[k];
      // Only the cap on the vertex side of the sphere centre belongs to the lens.
      if (glm::dot(ws, axis_) * R > 1e-12 * R * R) continue;
      n = (k == 0 ? 1.0 / R : -1.0 / R) * ws;
      n = glm::normalize(n);
    }
    best = t;
    hit = {t, p, n, k == 0 ? LensSurface::Front : LensSurface::Back};
    found = true;
  }
  return found;
}

bool LensGeometry::ledge_hit(const glm::dvec3& o, const glm::dvec3& d, bool from_here, double t_eps,
                             double& best, LensHit& hit) const {
  if (ledge_ <= 0.0) return false;
  const glm::dvec3 w = o - center_;
  const glm::dvec3 wp = w - glm::dot(w, axis_) * axis_;
  const glm::dvec3 dp = d - glm::dot(d, axis_) * axis_;
  const double A = glm::dot(dp, dp);
  if (A < 1e-300) return false;  // parallel to the axis: never meets the cylinder wall
  const double B = glm::dot(wp, dp);
  // Stable quadratic with the same h trick: |wp − (B/A)dp|² is the squared closest distance.
  const glm::dvec3 h = wp - (B / A) * dp;
  const double disc = A * (rho_ * rho_ - glm::dot(h, h));
  if (disc < 0.0) return false;
  const double q = -B - std::copysign(std::sqrt(disc), B);
  double ts[2];
  int nt = 0;
  ts[nt++] = q / A;
  if (!from_here && q != 0.0) ts[nt++] = (glm::dot(wp, wp) - rho_ * rho_) / q;
  bool found = false;
  for (int i = 0; i < nt; ++i) {
    const double t = ts[i];
    if (!(t > t_eps) || !(t < best)) continue;
    const glm::dvec3 p = o + t * d;
    const glm::dvec3 pw = p - center_;
    const double z = glm::dot(pw, axis_);
    const double tol = 1e-12 * scale_;
    if (z < z_edge_[0] - tol || z > z_edge_[1] + tol) continue;
    best = t;
    hit = {t, p, glm::normalize(pw - z * axis_), LensSurface::Ledge};
    found = true;
  }
  return found;
}

bool LensGeometry::intersect(const glm::dvec3& o, const glm::dvec3& d, double t_max, LensSurface from,
                             LensHit& hit) const {
  double best = t_max;
  // Rays starting on the lens skip their own surface analytically; the tiny t_eps only guards
  // the rim, where a ray leaving one surface starts on another as well.
  const double t_eps = from == LensSurface::None ? 0.0 : 1e-10 * scale_;
  bool found = cap_hit(0, o, d, from == LensSurface::Front, t_eps, best, hit);
  found |= cap_hit(1, o, d, from == LensSurface::Back, t_eps, best, hit);
  found |= ledge_hit(o, d, from == LensSurface::Ledge, t_eps, best, hit);
  return found;
}

void LensGeometry::bounds(glm::dvec3& lo, glm::dvec3& hi) const {
  const double z0 = std::min(-0.5 * thickness_, z_edge_[0]);
  const double z1 = std::max(0.5 * thickness_, z_edge_[1]);
  const glm::dvec3 a = center_ + z0 * axis_, b = center_ + z1 * axis_;
  // A disc of radius ρ ⟂ axis reaches ρ·√(1 − a_i²) along world axis i.
  const glm::dvec3 ext = rho_ * glm::sqrt(glm::max(glm::dvec3(0.0), 1.0 - axis_ * axis_));
  lo = glm::min(a, b) - ext;
  hi = glm::max(a, b) + ext;
}

namespace {
const Medium& lookup(const std::string& name, const char* key, const std::string& file) {
  try {
    return find_medium(name);
  } catch (const InputError& e) {
    throw InputError(file, key, name, std::string("unknown material (") + e.what() + ")");
  }
}
}  // namespace

Lens::Lens(const LensSpec& spec)
    : Lens(spec, lookup(spec.glass, "glass", spec.file), lookup(spec.medium, "medium", spec.file)) {}

Lens::Lens(const LensSpec& spec, const Medium& glass, const Medium& medium)
    : spec_(spec), geometry_(spec), glass_(&glass), medium_(&medium) {}

LensMedia Lens::media(double wavelength_nm) const {
  return {glass_->n(wavelength_nm), medium_->n(wavelength_nm), glass_->attenuation_per_mm(wavelength_nm)};
}

}  // namespace pmsim
