// Fuzz entries for the lens: the lens JSON of pmsim-trace (load_lens_spec → Lens) and the SML
// tracer (trace_lens) with a fuzzed lens and ray. Oracles: only InputError escapes the parser; an
// accepted lens survives lens_spec_to_json → lens_spec_from_json; every traced bundle is finite,
// unit dir ⟂ unit pol, intensities ≥ 0, and conserves energy:
//     Σ rays + Σ events + absorbed + filtered = incident   (LensBundle::energy_defect).
#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "core/base/input_error.h"
#include "core/base/units.h"
#include "core/lens/lens.h"
#include "core/lens/lens_tracer.h"
#include "tests/fuzz/fuzz_support.h"
#include "tests/fuzz/fuzz_targets.h"

namespace pmsim::fuzz {

namespace {

std::string str(const glm::dvec3& v) {
  std::ostringstream o;
  o.precision(17);
  o << "[" << v.x << "," << v.y << "," << v.z << "]";
  return o.str();
}

// The bundle's invariants. Energy: each interaction conserves energy to a few ulp (the SML's
// contract is 1e-12 relative); 1e-9 leaves room for 10⁴ interactions of rounding.
void check_bundle(const LensBundle& b, const std::string& ctx) {
  for (const PolarizedRay& r : b.rays) {
    check(finite3(r.origin.x, r.origin.y, r.origin.z) && finite3(r.dir.x, r.dir.y, r.dir.z) &&
              finite3(r.pol.x, r.pol.y, r.pol.z) && std::isfinite(r.intensity) &&
              std::isfinite(r.delta_rad) && std::isfinite(r.optical_path_mm),
          "trace: non-finite outgoing ray origin " + str(r.origin) + " dir " + str(r.dir) + " pol " +
              str(r.pol) + "\n" + ctx);
    check(r.intensity >= 0.0, "trace: negative intensity\n" + ctx);
    check(std::abs(glm::length(r.dir) - 1.0) < 1e-9, "trace: dir not unit " + str(r.dir) + "\n" + ctx);
    check(std::abs(glm::length(r.pol) - 1.0) < 1e-9, "trace: pol not unit " + str(r.pol) + "\n" + ctx);
    // pmsim-trace accepts input pol ⟂ dir to 1e-6, so outgoing rays (which may be traced
    // through the next lens) must stay well inside that; ~1e-8 drift after 6 internal
    // reflections in a steep, dense lens was seen (regressions/trace_lens/pol_drift_depth6.bin).
    check(std::abs(glm::dot(r.dir, r.pol)) < 1e-7,
          "trace: pol not ⟂ dir " + str(r.dir) + " " + str(r.pol) + "\n" + ctx);
  }
  for (const LensEvent& e : b.events)
    check(std::isfinite(e.intensity) && e.intensity >= 0.0 && finite3(e.point.x, e.point.y, e.point.z),
          "trace: bad event\n" + ctx);
  check(std::isfinite(b.absorbed) && b.absorbed >= 0.0, "trace: bad absorbed\n" + ctx);
  const double defect = b.energy_defect();
  check(std::isfinite(defect) && std::abs(defect) <= 1e-9 * std::max(b.incident, 1e-300),
        "trace: energy not conserved, defect " + std::to_string(defect) + " of " +
            std::to_string(b.incident) + "\n" + ctx);
}

// Any unit vector ⟂ d, rotated by angle about d: a valid linear polarization.
glm::dvec3 perpendicular_pol(const glm::dvec3& d, double angle_rad) {
  const glm::dvec3 helper = std::abs(d.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(d, helper));
  const glm::dvec3 v = glm::cross(d, u);
  return std::cos(angle_rad) * u + std::sin(angle_rad) * v;
}

std::vector<std::filesystem::path> lens_files(const std::string& asset_dir) {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(asset_dir) / "lenses", ec))
    if (e.path().extension() == ".json") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// Ranges of the binary trace input (ByteReader::number: values in range, 1 in 16 raw doubles).
constexpr double kPos = 100.0, kRadius = 50.0, kCap = 400.0, kThick = 60.0;

}  // namespace

int lens_parser(const std::uint8_t* data, std::size_t size) {
  const std::string path = write_scratch("lens", data, size);
  LensSpec spec;
  try {
    spec = load_lens_spec(path);
    const Lens lens(spec);  // geometry validation and the glass/medium look-up
    // An accepted lens must load back from its own JSON.
    const LensSpec back =
        lens_spec_from_json(nlohmann::json::parse(lens_spec_to_json(spec).dump()), "round-trip");
    const Lens again(back);
    check(again.geometry().thickness_mm() == lens.geometry().thickness_mm(),
          "lens_parser: thickness changes on save → load");
    // The axial ray at 550 nm: on every accepted lens it must trace cleanly.
    PolarizedRay in;
    in.dir = lens.geometry().axis();
    in.origin = lens.geometry().front_vertex() - 10.0 * lens.geometry().size_mm() * in.dir;
    in.pol = perpendicular_pol(in.dir, 0.3);
    LensTraceOptions opt;
    opt.tir = TirMode::Split;
    LensBundle b;
    trace_lens(lens, in, opt, b);
    check_bundle(b, "axial ray through " + lens_spec_to_json(spec).dump());
  } catch (const InputError&) {
    return 0;
  } catch (const std::exception& e) {
    fail(std::string("lens_parser: an exception other than InputError escaped: ") + e.what());
  }
  return 0;
}

int trace_lens(const std::uint8_t* data, std::size_t size) {
  ByteReader r(data, size);
  LensSpec spec;
  spec.center = {r.number(-kPos, kPos), r.number(-kPos, kPos), r.number(-kPos, kPos)};
  spec.axis = {r.number(-1, 1), r.number(-1, 1), r.number(-1, 1)};
  spec.radius_mm = r.number(0, kRadius);
  const std::uint8_t caps = r.byte();
  spec.front_radius_mm = (caps & 1) ? 0.0 : r.number(-kCap, kCap);
  spec.back_radius_mm = (caps & 2) ? 0.0 : r.number(-kCap, kCap);
  if (caps & 4)
    spec.thickness_mm = r.number(0, kThick);
  else
    spec.ledge_mm = r.number(0, kThick);
  LensMedia media;
  media.n_glass = r.number(1.0, 3.0);
  media.n_medium = r.number(1.0, 1.8);
  media.attenuation_per_mm = r.number(0.0, 2.0);
  PolarizedRay in;
  in.origin = {r.number(-kPos, kPos), r.number(-kPos, kPos), r.number(-kPos, kPos)};
  glm::dvec3 dir{r.number(-1, 1), r.number(-1, 1), r.number(-1, 1)};
  const double pol_angle = r.number(0, 2 * kPi);
  in.wavelength_nm = r.number(380, 780);
  in.intensity = r.number(0, 10);
  in.optical_path_mm = r.number(0, 1e6);
  in.delta_rad = r.number(-10, 10);
  LensTraceOptions opt;
  opt.max_depth = r.integer(0, 8);
  const std::uint8_t modes = r.byte();
  opt.tir = (modes & 1) ? TirMode::Split : TirMode::Stop;
  opt.direction = (modes & 2) ? TraceDirection::Backward : TraceDirection::Forward;
  opt.fresnel = (modes & 4) ? FresnelModel::Schlick : FresnelModel::Exact;

  // The preconditions pmsim-trace and the renderers check before tracing: finite numbers,
  // a non-zero direction, media with n ≥ 1, μ ≥ 0.
  if (!finite3(in.origin.x, in.origin.y, in.origin.z) || !finite3(dir.x, dir.y, dir.z) ||
      !(glm::length(dir) > 1e-9) || !std::isfinite(pol_angle) || !std::isfinite(in.wavelength_nm) ||
      !(in.wavelength_nm > 0) || !std::isfinite(in.intensity) || !(in.intensity >= 0) ||
      !std::isfinite(in.optical_path_mm) || !std::isfinite(in.delta_rad) ||
      !(media.n_glass >= 1.0 && media.n_glass <= 5.0) || !(media.n_medium >= 1.0 && media.n_medium <= 5.0) ||
      !(media.attenuation_per_mm >= 0.0 && media.attenuation_per_mm < 1e6))
    return 0;
  in.dir = glm::normalize(dir);
  in.pol = perpendicular_pol(in.dir, pol_angle);
  std::optional<LensGeometry> geometry;
  try {
    geometry.emplace(spec);
  } catch (const InputError&) {
    return 0;
  } catch (const std::exception& e) {
    fail(std::string("trace_lens: LensGeometry threw something other than InputError: ") + e.what());
  }
  LensBundle b;
  try {
    trace_lens(*geometry, media, in, opt, b);
  } catch (const std::exception& e) {
    fail(std::string("trace_lens threw: ") + e.what());
  }
  std::ostringstream ctx;
  ctx.precision(17);
  ctx << "lens " << lens_spec_to_json(spec).dump() << " n_glass " << media.n_glass << " n_medium "
      << media.n_medium << " mu " << media.attenuation_per_mm << " ray origin " << str(in.origin) << " dir "
      << str(in.dir) << " pol " << str(in.pol) << " depth " << opt.max_depth << " modes " << int(modes);
  check_bundle(b, ctx.str());
  return 0;
}

void lens_parser_seeds(const std::string& asset_dir, const std::string& out_dir) {
  for (const auto& p : lens_files(asset_dir)) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    write_file(out_dir + "/asset_" + p.filename().string(), ss.str());
  }
  write_file(out_dir + "/edge_thin.json",
             std::string("{\"glass\":\"N-SF11\",\"radius_mm\":1,\"front\":{\"radius_mm\":1},"
                         "\"back\":{\"radius_mm\":-1},\"ledge_mm\":0}"));
}

void trace_lens_seeds(const std::string& asset_dir, const std::string& out_dir) {
  // Each asset lens, hit by an axial, an off-axis and a steep ray at depths 0, 3 and 8.
  int i = 0;
  for (const auto& p : lens_files(asset_dir)) {
    LensSpec s;
    try {
      s = load_lens_spec(p.string());
    } catch (const std::exception&) {
      continue;
    }
    const double rays[3][6] = {{0, 0, -20, 0, 0, 1},
                               {0.5 * s.radius_mm, 0, -20, 0, 0, 1},
                               {-0.8 * s.radius_mm, 0.3 * s.radius_mm, -5, 0.6, 0.2, 0.8}};
    for (int k = 0; k < 3; ++k) {
      ByteWriter w;
      for (int c = 0; c < 3; ++c) w.number(s.center[c], -kPos, kPos);
      for (int c = 0; c < 3; ++c) w.number(s.axis[c], -1, 1);
      w.number(s.radius_mm, 0, kRadius);
      const bool thick = s.thickness_mm.has_value();
      w.byte(
          std::uint8_t((s.front_radius_mm == 0 ? 1 : 0) | (s.back_radius_mm == 0 ? 2 : 0) | (thick ? 4 : 0)));
      if (s.front_radius_mm != 0) w.number(s.front_radius_mm, -kCap, kCap);
      if (s.back_radius_mm != 0) w.number(s.back_radius_mm, -kCap, kCap);
      w.number(thick ? *s.thickness_mm : s.ledge_mm.value_or(0), 0, kThick);
      w.number(1.5168, 1.0, 3.0);
      w.number(1.0, 1.0, 1.8);
      w.number(0.001, 0.0, 2.0);
      for (int c = 0; c < 6; ++c) w.number(rays[k][c], c < 3 ? -kPos : -1, c < 3 ? kPos : 1);
      w.number(0.7, 0, 2 * kPi);
      w.number(550, 380, 780);
      w.number(1, 0, 10);
      w.number(0, 0, 1e6);
      w.number(0, -10, 10);
      w.integer(k == 0 ? 0 : (k == 1 ? 3 : 8), 0, 8);
      w.byte(std::uint8_t(k));
      write_file(out_dir + "/asset_" + std::to_string(i++) + ".bin", w.bytes());
    }
  }
}

}  // namespace pmsim::fuzz
