#include "core/specimen/specimen_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/crystal/vibration_index.h"

namespace pmsim {

SpecimenScene::SpecimenScene(const std::vector<FragmentShape>& fragments, const Crystal& mineral,
                             const IsotropicMedium& liquid, const Medium& glass, const Medium& air,
                             SpecimenLayers layers)
    : layers_(layers), mineral_(std::make_shared<Crystal>(mineral)), glass_(glass), air_(air) {
  media_.push_back({IsotropicMedium(air), nullptr, glm::dmat3(1.0)});
  media_.push_back({IsotropicMedium(glass), nullptr, glm::dmat3(1.0)});
  media_.push_back({liquid, nullptr, glm::dmat3(1.0)});
  double top = 0.0;
  double extent = 0.0;  // horizontal reach of the fragments, for the size of the glass quads
  for (std::size_t k = 0; k < fragments.size(); ++k) {
    const FragmentMesh m = fragment_mesh(fragments[k]);
    const unsigned base = unsigned(vertices_.size());
    vertices_.insert(vertices_.end(), m.vertices.begin(), m.vertices.end());
    for (const glm::uvec3& t : m.triangles) {
      triangles_.push_back(t + glm::uvec3(base));
      front_.push_back(kSpecimenLiquid);  // outward normal: the liquid outside
      back_.push_back(kFirstFragment + int(k));
    }
    media_.push_back({std::nullopt, mineral_, fragments[k].crystal_to_lab});
    FragmentBox box{glm::dvec2(1e300), glm::dvec2(-1e300)};
    for (const glm::dvec3& v : m.vertices) box.lo = glm::min(box.lo, glm::dvec2(v)), box.hi = glm::max(box.hi, glm::dvec2(v));
    boxes_.push_back(box);
    top = std::max(top, m.z_max_um);
    extent = std::max(extent, glm::length(fragments[k].centre_um) + fragments[k].size_um);
  }
  if (!(layers_.liquid_um > 0.0)) layers_.liquid_um = top + 5.0;
  if (top >= layers_.liquid_um) throw std::invalid_argument("a fragment is taller than the liquid layer");
  build(extent, false);
}

SpecimenScene::SpecimenScene(std::vector<SpecimenMedium> media, SpecimenMesh mesh, const Crystal& mineral,
                             const IsotropicMedium& fill, const Medium& glass, const Medium& air,
                             SpecimenLayers layers)
    : layers_(layers), mineral_(std::make_shared<Crystal>(mineral)), glass_(glass), air_(air) {
  if (!(layers_.liquid_um > 0.0)) throw std::invalid_argument("a specimen slab needs its layer thickness");
  const std::size_t nt = mesh.triangles.size();
  if (mesh.front.size() != nt || mesh.back.size() != nt)
    throw std::invalid_argument("a specimen mesh needs the media on both sides of every triangle");
  media_.push_back({IsotropicMedium(air), nullptr, glm::dmat3(1.0)});
  media_.push_back({IsotropicMedium(glass), nullptr, glm::dmat3(1.0)});
  media_.push_back({fill, nullptr, glm::dmat3(1.0)});
  for (SpecimenMedium& m : media) {
    if (!m.crystal && !m.isotropic) throw std::invalid_argument("a specimen medium is neither a crystal nor isotropic");
    media_.push_back(std::move(m));
  }
  const int n_media = int(media_.size());
  for (std::size_t p = 0; p < nt; ++p)
    if (mesh.front[p] < kSpecimenLiquid || mesh.front[p] >= n_media || mesh.back[p] < kSpecimenLiquid ||
        mesh.back[p] >= n_media)
      throw std::invalid_argument("a specimen mesh names a medium outside its layer's table");
  double extent = 0.0;
  for (const glm::dvec3& v : mesh.vertices) {
    extent = std::max(extent, std::max(std::abs(v.x), std::abs(v.y)));
    if (v.z < 0.0 || v.z > layers_.liquid_um) throw std::invalid_argument("a specimen mesh leaves its layer");
  }
  if (!mesh.vertices.empty()) {
    FragmentBox box{glm::dvec2(1e300), glm::dvec2(-1e300)};
    for (const glm::dvec3& v : mesh.vertices) box.lo = glm::min(box.lo, glm::dvec2(v)), box.hi = glm::max(box.hi, glm::dvec2(v));
    boxes_.push_back(box);
  }
  vertices_ = std::move(mesh.vertices);
  triangles_ = std::move(mesh.triangles);
  front_ = std::move(mesh.front);
  back_ = std::move(mesh.back);
  // A slab's walls, top and bottom faces meet along edges that rays cross at every boundary.
  build(extent, true);
}

void SpecimenScene::build(double extent, bool robust) {
  // The glass faces: quads far beyond any ray of the field (a ray leaves the stack within a few
  // slide thicknesses of where it entered), normal +z, air/glass/liquid on their sides.
  const double L = extent + 10.0 * (layers_.slide_um + layers_.cover_um + layers_.liquid_um) + 1e4;
  auto quad = [&](double z, int above, int below) {
    const unsigned b = unsigned(vertices_.size());
    vertices_.push_back({-L, -L, z});
    vertices_.push_back({L, -L, z});
    vertices_.push_back({L, L, z});
    vertices_.push_back({-L, L, z});
    triangles_.push_back({b, b + 1, b + 2});
    triangles_.push_back({b, b + 2, b + 3});
    for (int i = 0; i < 2; ++i) {
      front_.push_back(above);
      back_.push_back(below);
    }
  };
  quad(-layers_.slide_um, kSpecimenGlass, kSpecimenAir);
  quad(0.0, kSpecimenLiquid, kSpecimenGlass);
  quad(layers_.liquid_um, kSpecimenGlass, kSpecimenLiquid);
  quad(cover_top_z_um(), kSpecimenAir, kSpecimenGlass);

  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree device could not be created");
  scene_ = rtcNewScene(device_);
  // A section slab has up to ~2 M triangles: a medium-quality BVH builds several times faster
  // and traces nearly as fast; fragment meshes are small, built as before.
  if (robust) rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, triangles_.size() > 200000 ? RTC_BUILD_QUALITY_MEDIUM : RTC_BUILD_QUALITY_HIGH);
  RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vb = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices_.size()));
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    vb[3 * i] = float(vertices_[i].x);
    vb[3 * i + 1] = float(vertices_[i].y);
    vb[3 * i + 2] = float(vertices_[i].z);
  }
  auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                            3 * sizeof(unsigned), triangles_.size()));
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    ib[3 * i] = triangles_[i].x;
    ib[3 * i + 1] = triangles_[i].y;
    ib[3 * i + 2] = triangles_[i].z;
  }
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene_, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(scene_);
}

SpecimenScene::~SpecimenScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

double SpecimenScene::index(int id, double wavelength_nm, const glm::dvec3& vibration) const {
  switch (id) {
    case kSpecimenAir: return air_.n(wavelength_nm);
    case kSpecimenGlass: return glass_.n(wavelength_nm);
    default: break;
  }
  const SpecimenMedium& m = media_.at(std::size_t(id));
  if (!m.crystal) return m.isotropic->n(wavelength_nm);
  return vibration_index(*m.crystal, m.crystal_to_lab, wavelength_nm, vibration);
}

// Isotropic minerals are no crystal to the tracer: their light does not split into modes.
const Crystal* SpecimenScene::crystal_of(int medium) const {
  const Crystal* c = media_.at(std::size_t(medium)).crystal.get();
  return c && c->symmetry() != CrystalSymmetry::Isotropic ? c : nullptr;
}

double SpecimenScene::isotropic_absorption_per_um(int medium, double wavelength_nm) const {
  const Crystal* c = media_.at(std::size_t(medium)).crystal.get();
  if (!c || c->symmetry() != CrystalSymmetry::Isotropic || !c->absorbing()) return 0.0;
  return c->principal_absorption_per_um(wavelength_nm).x;
}

glm::dmat3 SpecimenScene::orientation_of(int medium) const {
  const SpecimenMedium& m = media_.at(std::size_t(medium));
  return m.crystal ? m.crystal_to_lab : glm::dmat3(1.0);
}

bool SpecimenScene::intersect(const glm::dvec3& o, const glm::dvec3& d, double tnear, SpecimenHit& hit) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh{};
  rh.ray.org_x = float(o.x);
  rh.ray.org_y = float(o.y);
  rh.ray.org_z = float(o.z);
  rh.ray.dir_x = float(d.x);
  rh.ray.dir_y = float(d.y);
  rh.ray.dir_z = float(d.z);
  rh.ray.tnear = float(tnear);
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  const unsigned p = rh.hit.primID;
  const glm::uvec3 t = triangles_[p];
  const glm::dvec3 n = glm::normalize(glm::cross(vertices_[t.y] - vertices_[t.x], vertices_[t.z] - vertices_[t.x]));
  // The hit point in double on the triangle's plane: the float t moved onto the plane along d,
  // so the next segment starts on the surface, not a float rounding away from it.
  const double tf = rh.ray.tfar;
  const double dn = glm::dot(d, n);
  const double t_plane = std::abs(dn) > 1e-12 ? glm::dot(vertices_[t.x] - o, n) / dn : tf;
  hit.t = std::abs(t_plane - tf) < 1e-2 ? t_plane : tf;
  hit.point = o + hit.t * d;
  hit.normal = n;
  hit.front = front_[p];
  hit.back = back_[p];
  hit.prim = p;
  return true;
}

int SpecimenScene::fragment_under(double x_um, double y_um) const {
  glm::dvec3 o{x_um, y_um, layers_.liquid_um - 1e-3};
  const glm::dvec3 d{0.0, 0.0, -1.0};
  SpecimenHit h;
  // Walk down through the liquid: the first fragment face met, if above the slide, is it.
  for (int i = 0; i < 8 && intersect(o, d, 1e-4, h); ++i) {
    if (h.back >= kFirstFragment) return h.back - kFirstFragment;
    if (h.front >= kFirstFragment) return h.front - kFirstFragment;
    if (h.point.z <= 1e-6) return -1;
    o = h.point;
  }
  return -1;
}

}  // namespace pmsim
