#include "core/scene3d/scene3d_description.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/materials/medium.h"

namespace pmsim {
namespace {

// One JSON object of a 3-D scene: the shared JsonReader (core/base/json_reader.h), so that a
// wrong type or an out-of-range number reads as in every other file type, plus the scene's own
// value kinds (sizes, colours). A misspelt key is an error, not a silent default.
class Reader {
 public:
  Reader(const nlohmann::json& j, std::string file, std::string path)
      : r_(j, std::move(file), std::move(path)) {
    if (!j.is_object()) r_.fail("", j, "expected an object");
  }

  [[noreturn]] void fail(const std::string& key, const nlohmann::json& v, const std::string& why) const {
    r_.fail(key, v, why);
  }
  std::string key_path(const std::string& key) const { return r_.path(key); }
  const std::string& file() const { return r_.file(); }
  bool has(const std::string& key) const { return r_.node().contains(key); }
  const nlohmann::json& at(const std::string& key) const { return r_.node().at(key); }

  void only(std::initializer_list<const char*> allowed) const {
    for (auto it = r_.node().begin(); it != r_.node().end(); ++it) {
      bool ok = false;
      for (const char* k : allowed) ok = ok || it.key() == k;
      if (!ok) fail(it.key(), it.value(), "unknown key");
    }
  }
  void need(const std::string& key) const {
    if (!has(key)) throw InputError(file(), key_path(key), "", "missing required key");
  }

  double number(const std::string& key, double def, double lo, double hi) const {
    if (!has(key)) return def;
    const double x = r_.checked(key, at(key), number_value);
    if (!Range::closed(lo, hi).contains(x)) fail(key, at(key), Range::closed(lo, hi).message());
    return x;
  }
  int integer(const std::string& key, int def, int lo, int hi) const {
    if (!has(key)) return def;
    const int x = r_.checked(key, at(key), integer_value);
    if (x < lo || x > hi) fail(key, at(key), Range::closed(lo, hi).message());
    return x;
  }
  bool boolean(const std::string& key, bool def) const {
    return has(key) ? r_.checked(key, at(key), bool_value) : def;
  }
  std::string string(const std::string& key, const std::string& def) const {
    return has(key) ? r_.checked(key, at(key), string_value) : def;
  }
  template <class E>
  E choice(const std::string& key, E def, const NameTable<E>& names) const {
    if (!has(key)) return def;
    return r_.checked(key, at(key), [&](const nlohmann::json& v) { return enum_value(v, names); });
  }
  glm::dvec3 vec3(const std::string& key, const glm::dvec3& def, double max_abs = 1e6) const {
    if (!has(key)) return def;
    return vec3_value(key, at(key), max_abs);
  }
  glm::dvec3 vec3_value(const std::string& key, const nlohmann::json& v, double max_abs) const {
    const auto a = r_.checked(key, v, vector3_value);
    for (double c : a)
      if (std::abs(c) > max_abs)
        fail(key, v, "components must be at most " + number_text(max_abs) + " in size");
    return {a[0], a[1], a[2]};
  }
  glm::dvec3 direction(const std::string& key, const glm::dvec3& def) const {
    const glm::dvec3 d = vec3(key, def);
    const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    if (!(len > 1e-12)) fail(key, at(key), "a direction cannot be the zero vector");
    return d / len;
  }
  glm::dvec2 size2(const std::string& key, const glm::dvec2& def) const {
    if (!has(key)) return def;
    const auto& v = at(key);
    if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
      fail(key, v, "expected an array of 2 positive numbers");
    const glm::dvec2 s{v[0].get<double>(), v[1].get<double>()};
    if (!(s.x > 0.0 && s.y > 0.0 && s.x < 1e7 && s.y < 1e7))
      fail(key, v, "expected an array of 2 positive numbers");
    return s;
  }
  glm::dvec3 rgb_value(const std::string& key, const nlohmann::json& v) const {
    const glm::dvec3 c = vec3_value(key, v, 1e6);
    if (c.x < 0.0 || c.y < 0.0 || c.z < 0.0 || c.x > 1.0 || c.y > 1.0 || c.z > 1.0)
      fail(key, v, "colour components must be in [0, 1] (linear sRGB)");
    return c;
  }

 private:
  JsonReader r_;
};

const NameTable<Scene3dMode> kModes = {{"spectral", Scene3dMode::Spectral}, {"rgb", Scene3dMode::Rgb}};
const NameTable<FresnelModel> kFresnelModels = {{"exact", FresnelModel::Exact},
                                                {"schlick", FresnelModel::Schlick}};
const NameTable<TirMode> kTirModes = {{"stop", TirMode::Stop}, {"split", TirMode::Split}};

Illuminant read_illuminant(const Reader& r, const std::string& key) {
  if (!r.has(key)) return Illuminant::D65;
  Illuminant ill;
  if (!parse_illuminant(r.string(key, ""), ill)) r.fail(key, r.at(key), "must be \"D65\" or \"A\"");
  return ill;
}

// Orthogonalises u against n; the rectangle of a plane or area light is spanned by u and n × u.
glm::dvec3 tangent(const Reader& r, const std::string& key, const glm::dvec3& n, const glm::dvec3& def) {
  glm::dvec3 u = r.has(key) ? r.direction(key, def) : def;
  u = u - (u.x * n.x + u.y * n.y + u.z * n.z) * n;
  const double len = std::sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
  if (!(len > 1e-6)) {
    if (r.has(key)) r.fail(key, r.at(key), "must not be parallel to the normal");
    // Default u parallel to n: take any perpendicular axis.
    u = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    u = u - (u.x * n.x + u.y * n.y + u.z * n.z) * n;
    return u / std::sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
  }
  return u / len;
}

Scene3dCamera parse_camera(const Reader& r) {
  r.only({"position", "look_at", "up", "fov_deg", "width", "height", "samples_per_pixel", "filter"});
  Scene3dCamera c;
  c.position = r.vec3("position", c.position);
  c.look_at = r.vec3("look_at", c.look_at);
  const glm::dvec3 d = c.look_at - c.position;
  if (!(d.x * d.x + d.y * d.y + d.z * d.z > 1e-18))
    r.fail("look_at", r.has("look_at") ? r.at("look_at") : nlohmann::json(), "must differ from position");
  c.up = r.direction("up", c.up);
  const glm::dvec3 cr{d.y * c.up.z - d.z * c.up.y, d.z * c.up.x - d.x * c.up.z, d.x * c.up.y - d.y * c.up.x};
  if (!(cr.x * cr.x + cr.y * cr.y + cr.z * cr.z > 1e-18 * (d.x * d.x + d.y * d.y + d.z * d.z)))
    r.fail("up", r.has("up") ? r.at("up") : nlohmann::json(), "must not be parallel to the view");
  c.fov_deg = r.number("fov_deg", c.fov_deg, 0.1, 170.0);
  c.width = r.integer("width", c.width, 1, 8192);
  c.height = r.integer("height", c.height, 1, 8192);
  c.samples_per_pixel = r.integer("samples_per_pixel", c.samples_per_pixel, 1, 16);
  if (r.has("filter")) {
    const Reader f(r.at("filter"), r.file(), r.key_path("filter"));
    f.only({"angle_deg"});
    f.need("angle_deg");
    c.filter_angle_deg = f.number("angle_deg", 0.0, -360.0, 360.0);
  }
  return c;
}

Scene3dRenderSettings parse_render(const Reader& r) {
  r.only({"mode", "wavelengths", "max_depth", "lens_depth", "fresnel", "tir", "exposure", "background",
          "ambient"});
  Scene3dRenderSettings s;
  s.mode = r.choice("mode", Scene3dMode::Spectral, kModes);
  s.wavelengths = r.integer("wavelengths", s.wavelengths, 2, 81);
  s.max_depth = r.integer("max_depth", s.max_depth, 1, 64);
  s.lens_depth = r.integer("lens_depth", s.lens_depth, 0, 64);
  s.fresnel = r.choice("fresnel", FresnelModel::Exact, kFresnelModels);
  s.tir = r.choice("tir", TirMode::Stop, kTirModes);
  s.exposure = r.number("exposure", s.exposure, 0.0, 1e9);
  if (r.has("background")) s.background_rgb = r.vec3("background", s.background_rgb);
  if (s.background_rgb.x < 0 || s.background_rgb.y < 0 || s.background_rgb.z < 0)
    r.fail("background", r.at("background"), "must not be negative");
  s.ambient = r.number("ambient", s.ambient, 0.0, 1.0);
  return s;
}

Scene3dLight parse_light(const Reader& r) {
  Scene3dLight l;
  r.need("type");
  using LightType = Scene3dLight::Type;
  static const NameTable<LightType> kTypes = {{"point", LightType::Point}, {"area", LightType::Area}};
  if (r.choice("type", LightType::Point, kTypes) == LightType::Point) {
    r.only({"type", "position", "intensity", "emission"});
    r.need("position");
    l.type = Scene3dLight::Type::Point;
    l.position = r.vec3("position", l.position);
    l.intensity = r.number("intensity", l.intensity, 0.0, 1e15);
  } else {
    r.only({"type", "center", "normal", "u_axis", "size_mm", "radiance", "emission", "samples", "visible"});
    r.need("center");
    l.type = Scene3dLight::Type::Area;
    l.center = r.vec3("center", l.center);
    l.normal = r.direction("normal", l.normal);
    l.u_axis = tangent(r, "u_axis", l.normal, l.u_axis);
    l.size_mm = r.size2("size_mm", l.size_mm);
    l.radiance = r.number("radiance", l.radiance, 0.0, 1e15);
    l.samples = r.integer("samples", l.samples, 1, 32);
    l.visible = r.boolean("visible", l.visible);
  }
  l.emission = read_illuminant(r, "emission");
  return l;
}

Scene3dMaterial parse_material(const Reader& r, const std::string& name) {
  Scene3dMaterial m;
  m.name = name;
  r.need("type");
  using Type = Scene3dMaterial::Type;
  using Pattern = Scene3dMaterial::Pattern;
  static const NameTable<Type> kTypes = {{"diffuse", Type::Diffuse}, {"glass", Type::Glass}};
  static const NameTable<Pattern> kPatterns = {
      {"solid", Pattern::Solid}, {"stripes", Pattern::Stripes}, {"checker", Pattern::Checker}};
  if (r.choice("type", Type::Diffuse, kTypes) == Type::Diffuse) {
    r.only({"type", "rgb", "pattern", "colors", "period_mm"});
    m.type = Scene3dMaterial::Type::Diffuse;
    m.pattern = r.choice("pattern", Pattern::Solid, kPatterns);
    if (m.pattern == Scene3dMaterial::Pattern::Solid) {
      if (r.has("colors")) r.fail("colors", r.at("colors"), "only with a stripes/checker pattern");
      r.need("rgb");
      m.colors = {r.rgb_value("rgb", r.at("rgb"))};
    } else {
      if (r.has("rgb")) r.fail("rgb", r.at("rgb"), "a pattern takes \"colors\", not \"rgb\"");
      r.need("colors");
      const auto& c = r.at("colors");
      if (!c.is_array() || c.size() < 2 || c.size() > 64)
        r.fail("colors", c, "must be an array of 2 to 64 [r, g, b] colours");
      m.colors.clear();
      for (std::size_t i = 0; i < c.size(); ++i)
        m.colors.push_back(r.rgb_value("colors[" + std::to_string(i) + "]", c[i]));
      m.period_mm = r.number("period_mm", m.period_mm, 1e-6, 1e7);
    }
  } else {
    r.only({"type", "medium"});
    m.type = Scene3dMaterial::Type::Glass;
    r.need("medium");
    m.medium = r.string("medium", m.medium);
    try {
      (void)find_medium(m.medium);
    } catch (const InputError& e) {
      r.fail("medium", r.at("medium"), std::string("unknown medium (") + e.what() + ")");
    }
  }
  return m;
}

// Minimal Wavefront OBJ: "v x y z" and "f a b c ..." (1-based or negative indices, "a/b/c"
// forms; polygons fanned into triangles).
void load_obj(const Reader& r, const std::string& key, const std::string& path, Scene3dObject& o) {
  std::ifstream in(path);
  if (!in) r.fail(key, r.at(key), "cannot open the mesh file");
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      glm::dvec3 v;
      if (!(ls >> v.x >> v.y >> v.z) || !std::isfinite(v.x + v.y + v.z))
        r.fail(key, r.at(key), "bad vertex on line " + std::to_string(line_no));
      o.vertices.push_back(v);
    } else if (tag == "f") {
      std::vector<int> idx;
      std::string tok;
      while (ls >> tok) {
        int k = 0;
        try {
          k = std::stoi(tok.substr(0, tok.find('/')));
        } catch (...) {
          r.fail(key, r.at(key), "bad face on line " + std::to_string(line_no));
        }
        const int n = static_cast<int>(o.vertices.size());
        k = k < 0 ? n + k : k - 1;
        if (k < 0 || k >= n)
          r.fail(key, r.at(key), "face index out of range on line " + std::to_string(line_no));
        idx.push_back(k);
      }
      for (std::size_t i = 2; i < idx.size(); ++i) o.triangles.push_back({idx[0], idx[i - 1], idx[i]});
    }
  }
}

Scene3dObject parse_object(const Reader& r, const std::vector<Scene3dMaterial>& materials,
                           const std::string& scene_dir) {
  Scene3dObject o;
  r.need("type");
  using Type = Scene3dObject::Type;
  static const NameTable<Type> kTypes = {{"plane", Type::Plane},
                                         {"box", Type::Box},
                                         {"sphere", Type::Sphere},
                                         {"mesh", Type::Mesh},
                                         {"lens", Type::Lens}};
  o.type = r.choice("type", Type::Plane, kTypes);
  auto material = [&] {
    r.need("material");
    const std::string name = r.string("material", "");
    for (std::size_t i = 0; i < materials.size(); ++i)
      if (materials[i].name == name) return static_cast<int>(i);
    r.fail("material", r.at("material"), "no such material in \"materials\"");
  };
  switch (o.type) {
    case Scene3dObject::Type::Plane:
      r.only({"type", "material", "center", "normal", "u_axis", "size_mm"});
      o.material = material();
      o.center = r.vec3("center", o.center);
      o.normal = r.direction("normal", o.normal);
      o.u_axis = tangent(r, "u_axis", o.normal, o.u_axis);
      o.size_mm = r.size2("size_mm", o.size_mm);
      break;
    case Scene3dObject::Type::Box: {
      r.only({"type", "material", "center", "size_mm", "rotation_deg"});
      o.material = material();
      o.center = r.vec3("center", o.center);
      o.box_size_mm = r.vec3("size_mm", o.box_size_mm);
      if (!(o.box_size_mm.x > 0 && o.box_size_mm.y > 0 && o.box_size_mm.z > 0))
        r.fail("size_mm", r.at("size_mm"), "edge lengths must be positive");
      o.rotation_deg = r.vec3("rotation_deg", o.rotation_deg, 360.0);
      break;
    }
    case Scene3dObject::Type::Sphere:
      r.only({"type", "material", "center", "radius_mm"});
      o.material = material();
      o.center = r.vec3("center", o.center);
      o.radius_mm = r.number("radius_mm", o.radius_mm, 1e-6, 1e7);
      break;
    case Scene3dObject::Type::Mesh: {
      r.only({"type", "material", "vertices", "triangles", "file"});
      o.material = material();
      if (r.has("file")) {
        if (r.has("vertices") || r.has("triangles"))
          r.fail("file", r.at("file"), "give either \"file\" or \"vertices\"+\"triangles\"");
        std::filesystem::path p = r.string("file", "");
        if (p.is_relative()) p = std::filesystem::path(scene_dir) / p;
        load_obj(r, "file", p.string(), o);
      } else {
        r.need("vertices");
        r.need("triangles");
        const auto& v = r.at("vertices");
        const auto& t = r.at("triangles");
        if (!v.is_array() || v.empty()) r.fail("vertices", v, "must be an array of [x, y, z]");
        for (std::size_t i = 0; i < v.size(); ++i)
          o.vertices.push_back(r.vec3_value("vertices[" + std::to_string(i) + "]", v[i], 1e7));
        if (!t.is_array() || t.empty()) r.fail("triangles", t, "must be an array of [i, j, k]");
        for (std::size_t i = 0; i < t.size(); ++i) {
          const auto& tri = t[i];
          const std::string k = "triangles[" + std::to_string(i) + "]";
          if (!tri.is_array() || tri.size() != 3) r.fail(k, tri, "must be [i, j, k]");
          glm::ivec3 ids;
          for (int c = 0; c < 3; ++c) {
            if (!tri[c].is_number_integer()) r.fail(k, tri, "indices must be integers");
            const long long x = tri[c].get<long long>();
            if (x < 0 || x >= static_cast<long long>(o.vertices.size()))
              r.fail(k, tri, "vertex index out of range");
            ids[c] = static_cast<int>(x);
          }
          o.triangles.push_back(ids);
        }
      }
      if (o.triangles.empty()) r.fail("type", r.at("type"), "mesh has no triangles");
      break;
    }
    case Scene3dObject::Type::Lens:
      // The lens keys are the lens module's (LensSpec), validated when the geometry is built.
      break;
  }
  return o;
}

}  // namespace

Scene3dDescription parse_scene3d(const nlohmann::json& j, const std::string& file) {
  const Reader r(j, file, "");
  r.only({"type", "source", "description", "camera", "render", "lights", "materials", "objects"});
  r.need("type");
  if (r.string("type", "") != "scene3d") r.fail("type", r.at("type"), "must be \"scene3d\"");
  Scene3dDescription d;
  d.file = file;
  const std::string scene_dir =
      file.empty() ? std::string(".") : std::filesystem::path(file).parent_path().string();
  r.need("camera");
  d.camera = parse_camera(Reader(r.at("camera"), file, "camera"));
  if (r.has("render")) d.render = parse_render(Reader(r.at("render"), file, "render"));

  r.need("lights");
  const auto& lights = r.at("lights");
  if (!lights.is_array() || lights.empty()) r.fail("lights", lights, "must be a non-empty array");
  for (std::size_t i = 0; i < lights.size(); ++i)
    d.lights.push_back(parse_light(Reader(lights[i], file, "lights[" + std::to_string(i) + "]")));

  if (r.has("materials")) {
    const auto& mats = r.at("materials");
    if (!mats.is_object()) r.fail("materials", mats, "must be an object of named materials");
    for (auto it = mats.begin(); it != mats.end(); ++it)
      d.materials.push_back(parse_material(Reader(it.value(), file, "materials." + it.key()), it.key()));
  }

  r.need("objects");
  const auto& objs = r.at("objects");
  if (!objs.is_array() || objs.empty()) r.fail("objects", objs, "must be a non-empty array");
  for (std::size_t i = 0; i < objs.size(); ++i) {
    const std::string key = "objects[" + std::to_string(i) + "]";
    Scene3dObject o = parse_object(Reader(objs[i], file, key), d.materials, scene_dir);
    o.key = key;
    if (o.type == Scene3dObject::Type::Lens) {
      o.lens = objs[i];
      o.lens.erase("type");
    }
    d.objects.push_back(std::move(o));
  }
  return d;
}

Scene3dDescription load_scene3d_file(const std::string& path) {
  return parse_scene3d(read_json_file(path, "scene file"), path);
}

}  // namespace pmsim
