#include "core/scene3d/vignetting.h"

#include <cmath>
#include <memory>

#include <glm/geometric.hpp>

#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/lens/lens_tracer.h"

namespace pmsim {

Objective objective_from_json(const nlohmann::json& j, const std::string& file) {
  if (!j.is_object()) throw InputError(file, "", "", "an objective must be a JSON object");
  const JsonReader r(j, file);
  r.refuse_unknown_keys(
      {"type", "source", "name", "lenses", "object_z_mm", "na", "field_max_mm", "wavelength_nm"});
  if (!j.contains("type") || j.at("type") != "objective")
    throw InputError(file, "type", j.contains("type") ? shown(j.at("type")) : "", "must be \"objective\"");
  Objective o;
  o.name = r.get_or<std::string>("name", "objective");
  o.object_z_mm = r.get_or("object_z_mm", 0.0, Range::closed(-1e6, 1e6));
  o.na = r.get_or("na", 0.25, Range::closed(1e-6, 0.999));
  o.field_max_mm = r.get_or("field_max_mm", 1.0, Range::closed(0.0, 1e6));
  o.wavelength_nm = r.get_or("wavelength_nm", 587.5618, Range::closed(380.0, 780.0));
  if (!j.contains("lenses") || !j.at("lenses").is_array() || j.at("lenses").empty())
    throw InputError(file, "lenses", j.contains("lenses") ? j.at("lenses").dump().substr(0, 60) : "",
                     "must be a non-empty array of lenses");
  const auto& ls = j.at("lenses");
  for (std::size_t i = 0; i < ls.size(); ++i) {
    try {
      o.lenses.push_back(lens_spec_from_json(ls[i], file));
      (void)Lens(o.lenses.back());  // validates geometry and glass now, with the key at hand
    } catch (const InputError& e) {
      throw InputError(file, "lenses[" + std::to_string(i) + "]" + (e.key.empty() ? "" : "." + e.key),
                       e.value, std::string("invalid lens: ") + e.what());
    }
  }
  return o;
}

namespace {

// The direction through cell (a, b) of a grid over the disk of sinθ ≤ NA; false outside.
// Uniform cells in the projected (sinθ) disk are uniform in projected solid angle, the measure
// of a Lambertian object point's emitted power.
bool cell_direction(int a, int b, int grid, double na, glm::dvec3& d) {
  const double x = ((a + 0.5) / grid * 2.0 - 1.0) * na;
  const double y = ((b + 0.5) / grid * 2.0 - 1.0) * na;
  const double s2 = x * x + y * y;
  if (s2 > na * na) return false;
  d = glm::dvec3(x, y, std::sqrt(1.0 - s2));
  return true;
}

// Follows the main (never internally reflected) ray through every lens; returns the power left
// of an initial 1 (natural light) or 0 when vignetted.
double through_objective(const std::vector<std::unique_ptr<Lens>>& lenses, double lambda_nm,
                         const glm::dvec3& origin, const glm::dvec3& dir) {
  LensTraceOptions opt;
  opt.max_depth = 0;  // the direct ray only: internal reflections are ghosts, not the image
  opt.tir = TirMode::Stop;
  opt.direction = TraceDirection::Forward;
  double power = 0.0;
  const glm::dvec3 s =
      glm::normalize(glm::cross(dir, std::abs(dir.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  for (const glm::dvec3& pol : {s, glm::normalize(glm::cross(dir, s))}) {
    PolarizedRay r;
    r.origin = origin;
    r.dir = dir;
    r.pol = pol;
    r.intensity = 0.5;
    r.wavelength_nm = lambda_nm;
    bool alive = true;
    LensBundle b;
    for (const auto& lens : lenses) {
      b.clear();
      trace_lens(lens->geometry(), lens->media(lambda_nm), r, opt, b);
      const PolarizedRay* out = nullptr;
      for (const PolarizedRay& o : b.rays)
        if (o.depth == 0 && glm::dot(o.dir, lens->geometry().axis()) > 0.0 &&
            glm::dot(o.origin - lens->geometry().center(), lens->geometry().axis()) > 0.0)
          out = &o;  // leaves through the far cap, onward
      if (!out) {
        alive = false;
        break;
      }
      r = *out;
    }
    if (alive) power += r.intensity;
  }
  return power;
}

std::vector<std::unique_ptr<Lens>> make_lenses(const Objective& obj) {
  std::vector<std::unique_ptr<Lens>> v;
  for (const LensSpec& s : obj.lenses) v.push_back(std::make_unique<Lens>(s));
  return v;
}

}  // namespace

std::vector<VignettingPoint> vignetting(const Objective& obj, int field_steps, int grid) {
  const auto lenses = make_lenses(obj);
  std::vector<VignettingPoint> out;
  for (int f = 0; f < field_steps; ++f) {
    VignettingPoint p;
    p.field_mm = field_steps > 1 ? obj.field_max_mm * f / (field_steps - 1) : 0.0;
    const glm::dvec3 origin(p.field_mm, 0.0, obj.object_z_mm);
    int n = 0, passed = 0;
    double power = 0.0;
    for (int a = 0; a < grid; ++a)
      for (int b = 0; b < grid; ++b) {
        glm::dvec3 d;
        if (!cell_direction(a, b, grid, obj.na, d)) continue;
        ++n;
        const double t = through_objective(lenses, obj.wavelength_nm, origin, d);
        if (t > 0.0) ++passed;
        power += t;
      }
    p.passed = n ? static_cast<double>(passed) / n : 0.0;
    p.transmitted = n ? power / n : 0.0;
    out.push_back(p);
  }
  return out;
}

std::vector<int> vignetting_map(const Objective& obj, double field_mm, int grid) {
  const auto lenses = make_lenses(obj);
  std::vector<int> map(static_cast<std::size_t>(grid) * grid, -1);
  const glm::dvec3 origin(field_mm, 0.0, obj.object_z_mm);
  for (int a = 0; a < grid; ++a)
    for (int b = 0; b < grid; ++b) {
      glm::dvec3 d;
      if (!cell_direction(a, b, grid, obj.na, d)) continue;
      map[static_cast<std::size_t>(b) * grid + a] =
          through_objective(lenses, obj.wavelength_nm, origin, d) > 0.0 ? 1 : 0;
    }
  return map;
}

}  // namespace pmsim
