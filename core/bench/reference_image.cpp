#include "core/bench/reference_image.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <algorithm>
#include <fstream>
#include <sstream>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/base/units.h"
#include "core/bench/physical_lens_model.h"
#include "core/io/atomic_file.h"
#include "core/io/scene_file.h"
#include "core/microscope/evaluation_plan.h"
#include "core/microscope/modal_fit.h"
#include "core/microscope/optical_train.h"
#include "core/microscope/sample_source.h"
#include "core/render/image_develop.h"
#include "core/render/progressive_renderer.h"
#include "core/render/spectral_level.h"

namespace pmsim {

namespace {

namespace fs = std::filesystem;

// FNV-1a, 64 bit: a cache key, not security.
std::uint64_t fnv1a(const std::string& s, std::uint64_t h = 1469598103934665603ull) {
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::string data_fingerprint() {
  std::string all;
  for (const char* sub : {"minerals", "materials", "sections"}) {
    const fs::path dir = fs::path(asset_dir()) / sub;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir, ec)) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
      std::ifstream in(f, std::ios::binary);
      std::ostringstream ss;
      ss << in.rdbuf();
      all += f.filename().string() + ss.str();
    }
  }
  return all;
}

constexpr char kMagic[8] = {'P', 'M', 'S', 'B', 'R', 'E', 'F', '1'};

bool read_cache(const std::string& path, ReferenceImage& r) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  char magic[8];
  std::int32_t wh[2];
  in.read(magic, 8);
  in.read(reinterpret_cast<char*>(wh), sizeof wh);
  if (!in || std::memcmp(magic, kMagic, 8) != 0 || wh[0] <= 0 || wh[1] <= 0 || wh[0] > 16384 || wh[1] > 16384)
    return false;
  const std::size_t n = static_cast<std::size_t>(wh[0]) * wh[1];
  r.width = wh[0];
  r.height = wh[1];
  r.xyz.resize(3 * n);
  r.xyz_half.resize(3 * n);
  r.lit.resize(n);
  in.read(reinterpret_cast<char*>(r.xyz.data()), static_cast<std::streamsize>(3 * n * sizeof(float)));
  in.read(reinterpret_cast<char*>(r.xyz_half.data()), static_cast<std::streamsize>(3 * n * sizeof(float)));
  in.read(reinterpret_cast<char*>(r.lit.data()), static_cast<std::streamsize>(n));
  return static_cast<bool>(in) && in.peek() == std::char_traits<char>::eof();
}

void write_cache(const std::string& path, const ReferenceImage& r) {
  std::string bytes(kMagic, 8);
  const std::int32_t wh[2] = {r.width, r.height};
  bytes.append(reinterpret_cast<const char*>(wh), sizeof wh);
  bytes.append(reinterpret_cast<const char*>(r.xyz.data()), r.xyz.size() * sizeof(float));
  bytes.append(reinterpret_cast<const char*>(r.xyz_half.data()), r.xyz_half.size() * sizeof(float));
  bytes.append(reinterpret_cast<const char*>(r.lit.data()), r.lit.size());
  write_text_atomically(path, bytes);
}

struct UnitXyz {
  glm::dvec3 full{0.0}, half{0.0};
};

// One unit, one direction: transmissions at every 1 nm band (full) and the 2 nm rule (half).
void evaluate_direction(const EvaluationPlan& plan, const SpectralLevel& L, const EvalUnit& unit,
                        const glm::dvec3& k, std::vector<PlateModes>& modes, UnitXyz& acc) {
  const int N = L.n;
  const double two_pi = 2.0 * kPi;
  const OpticalDomain& dom = plan.domains()[unit.domain];
  if (!dom.crystal || unit.thickness_um <= 0.0) {
    for (int b = 0; b < N; ++b) {
      const double t = jones_transmission(L.train[b], plan.with_lenses(JonesMatrix::identity(), k));
      acc.full += L.weight[b] * t;
      if (b % 2 == 0) acc.half += (L.weight[b] + L.weight[std::min(b + 1, N - 1)]) * t;
    }
    return;
  }
  // Phase step between neighbouring bands, |Δ(2πΓ/λ)| ≈ 2π·Γ/λ²·Δλ, largest at the blue end;
  // estimated from three exact retardations (Γ varies slowly), with a 1.5 safety factor.
  double gamma_max = 0.0;
  for (int b : {0, N / 2, N - 1}) {
    PreparedPlate p = *L.plate(b, unit.domain);
    p.thickness_um = unit.thickness_um;
    gamma_max = std::max(gamma_max, plate_modes(p, k).retardation_nm);
  }
  const double step = 1.5 * two_pi * gamma_max * L.band_nm / (L.nm[0] * L.nm[0]);
  const bool sample_jones = step < 0.25;
  if (!sample_jones) {
    modes.resize(N);
    for (int b = 0; b < N; ++b) {
      PreparedPlate p = *L.plate(b, unit.domain);
      p.thickness_um = unit.thickness_um;
      modes[b] = plate_modes(p, k);
    }
  }
  glm::dmat2 lens_c, lens_o;
  plan.lens_jones(k, lens_c, lens_o);
  const glm::dmat2 lens_oc = lens_o * lens_c;
  for (int b = 0; b < N; ++b) {
    double t, t_half = 0.0;
    if (sample_jones) {
      PreparedPlate p = *L.plate(b, unit.domain);
      p.thickness_um = unit.thickness_um;
      t = jones_transmission(L.train[b], plan.with_lenses(plate_jones(p, k), k));
      t_half = t;
    } else {
      // Lenses (condenser C, objective O; the aplanatic frame for ideal ones): the modes leave
      // as O·e_m, and since the duals of O·e_m are O⁻ᵀ·d̃_m, the polarizer becomes O·C·p.
      ModalPoint m;
      modes_in_basis(modes[b], k, m.e1, m.e2);
      m.e1 = lens_o * m.e1;
      m.e2 = lens_o * m.e2;
      m.t1 = modes[b].t1;
      m.t2 = modes[b].t2;
      m.gamma_nm = modes[b].retardation_nm;
      const int lo = std::max(0, b - 1), hi = std::min(N - 1, b + 1);
      m.dgamma_dnm = (modes[hi].retardation_nm - modes[lo].retardation_nm) / (L.nm[hi] - L.nm[lo]);
      TrainState train = L.train[b];
      train.polarizer = lens_oc * train.polarizer;
      t = modal_transmission(train, m, L.band_nm);
      if (b % 2 == 0) t_half = modal_transmission(train, m, 2.0 * L.band_nm);
    }
    if (!std::isfinite(t)) t = 0.0;
    if (!std::isfinite(t_half)) t_half = 0.0;
    acc.full += L.weight[b] * std::max(0.0, t);
    if (b % 2 == 0) acc.half += (L.weight[b] + L.weight[std::min(b + 1, N - 1)]) * std::max(0.0, t_half);
  }
}

}  // namespace

Scene reference_scene(const Scene& scene) {
  Scene r = scene;
  r.render.strategy = RenderStrategy::Exact;
  r.render.wavelengths = kReferenceBands;
  r.render.single_wavelength_nm = 0.0;
  if (r.sample_in && r.sample.type != SampleType::Plate) r.render.spp = std::max(r.render.spp, 16);
  return r;
}

namespace {

std::string cache_path(const std::string& cache_dir, const std::string& what) {
  if (cache_dir.empty()) return "";
  const std::uint64_t key = fnv1a(data_fingerprint(), fnv1a(what, fnv1a(kReferenceVersion)));
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.ref", static_cast<unsigned long long>(key));
  std::error_code ec;
  fs::create_directories(cache_dir, ec);
  return (fs::path(cache_dir) / name).string();
}

bool try_cache(const std::string& path, const Scene& s, ReferenceImage& out) {
  if (path.empty()) return false;
  ReferenceImage cached;
  if (!read_cache(path, cached) || cached.width != s.render.width || cached.height != s.render.height)
    return false;
  cached.from_cache = true;
  cached.cache_file = path;
  out = std::move(cached);
  return true;
}

std::vector<std::uint8_t> lit_mask(const EvaluationPlan& plan) {
  const std::size_t n = static_cast<std::size_t>(plan.width()) * plan.height();
  std::vector<std::uint8_t> lit(n);
  for (std::size_t i = 0; i < n; ++i) lit[i] = plan.pixel_offset()[i] != plan.pixel_offset()[i + 1];
  return lit;
}

}  // namespace

ReferenceImage converged_reference(const Scene& scene, const std::string& cache_dir) {
  const Scene rs = reference_scene(scene);
  const std::string path = cache_path(cache_dir, scene_to_json(rs).dump());
  ReferenceImage R;
  if (try_cache(path, rs, R)) return R;
  const auto t0 = std::chrono::steady_clock::now();
  const auto plan = compile_evaluation_plan(rs);
  const SpectralLevel L = make_spectral_level(*plan, kReferenceBands);
  std::vector<UnitXyz> units(plan->units().size());
  tbb::enumerable_thread_specific<std::vector<PlateModes>> scratch;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, plan->units().size(), 64),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      auto& modes = scratch.local();
                      for (std::size_t u = r.begin(); u != r.end(); ++u) {
                        const EvalUnit& unit = plan->units()[u];
                        const int D = plan->dirs_of(unit);
                        UnitXyz acc;
                        for (int d = 0; d < D; ++d)
                          evaluate_direction(*plan, L, unit, plan->dir(unit, d), modes, acc);
                        units[u].full = acc.full / static_cast<double>(D);
                        units[u].half = acc.half / static_cast<double>(D);
                      }
                    });
  R.width = plan->width();
  R.height = plan->height();
  std::vector<glm::dvec3> v(units.size());
  RenderImage img;
  for (std::size_t u = 0; u < units.size(); ++u) v[u] = units[u].full;
  develop_image(*plan, v, false, img);
  R.xyz = std::move(img.xyz);
  for (std::size_t u = 0; u < units.size(); ++u) v[u] = units[u].half;
  develop_image(*plan, v, false, img);
  R.xyz_half = std::move(img.xyz);
  R.lit = lit_mask(*plan);
  R.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!path.empty()) {
    write_cache(path, R);
    R.cache_file = path;
  }
  return R;
}

ReferenceImage converged_physical_reference(const Scene& scene, const std::string& cache_dir) {
  Scene rs = scene;
  rs.optics.lens_model = LensModel::Physical;
  rs.optics.lens_depth = 5;
  rs.optics.fresnel = FresnelModel::Exact;
  rs.render.wavelengths = 128;
  rs.render.strategy = RenderStrategy::Modal;
  const std::string path = cache_path(cache_dir, "physical-lens-model:" + scene_to_json(rs).dump());
  ReferenceImage R;
  if (try_cache(path, rs, R)) return R;
  const auto t0 = std::chrono::steady_clock::now();
  StrategyResult full = render_physical_lens_model(rs);
  rs.render.wavelengths = 64;
  StrategyResult half = render_physical_lens_model(rs);
  Scene geo = rs;
  geo.render.strategy = RenderStrategy::Exact;
  R.width = rs.render.width;
  R.height = rs.render.height;
  R.xyz = std::move(full.xyz);
  R.xyz_half = std::move(half.xyz);
  R.lit = lit_mask(*compile_evaluation_plan(geo));
  R.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!path.empty()) {
    write_cache(path, R);
    R.cache_file = path;
  }
  return R;
}

}  // namespace pmsim
