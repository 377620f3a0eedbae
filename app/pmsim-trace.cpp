// pmsim-trace: trace one polarized ray through one lens (the SML) and print the bundle as JSON.
// The interface is a contract others script against (issue #2); run() lists the options (--help).
// Bad input: a message naming the key on stderr, exit code 2, nothing on stdout.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <glm/geometric.hpp>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/cli_policy.h"
#include "core/base/input_error.h"
#include "core/lens/lens.h"
#include "core/lens/lens_tracer.h"

namespace {

constexpr const char* kProgram = "pmsim-trace";

using pmsim::InputError;

double parse_double(const std::string& key, const std::string& v) {
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0' || !std::isfinite(x))
    throw InputError("", key, v, "expected a finite number");
  return x;
}

long parse_int(const std::string& key, const std::string& v) {
  char* end = nullptr;
  const long x = std::strtol(v.c_str(), &end, 10);
  if (v.empty() || *end != '\0') throw InputError("", key, v, "expected an integer");
  return x;
}

glm::dvec3 parse_vec3(const std::string& key, const std::string& v) {
  std::vector<double> c;
  std::stringstream ss(v);
  std::string item;
  while (std::getline(ss, item, ',')) c.push_back(parse_double(key, item));
  if (c.size() != 3) throw InputError("", key, v, "expected three comma-separated numbers x,y,z");
  return {c[0], c[1], c[2]};
}

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}
std::string vec(const glm::dvec3& v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "[%.17g,%.17g,%.17g]", v.x, v.y, v.z);
  return buf;
}

int run(int argc, char** argv) {
  std::map<std::string, std::string> a;
  CLI::App app{
      "Traces one linearly polarized ray through the lens and prints {rays, events, absorbed} as "
      "JSON.",
      kProgram};
  // Every value is read as text and checked below, so that a bad one is an InputError naming
  // the option and the value; an option given twice is a usage error.
  auto option = [&](const std::string& name, const std::string& help) {
    return app.add_option(name, a[name], help);
  };
  option("--lens", "lens file (JSON)")->type_name("FILE.json")->required();
  option("--origin", "ray origin (mm)")->type_name("x,y,z")->required();
  option("--dir", "ray direction")->type_name("x,y,z")->required();
  option("--pol", "polarization direction, perpendicular to --dir")->type_name("x,y,z")->required();
  option("--wavelength-nm", "wavelength in 380-780 nm")->type_name("L")->required();
  option("--intensity", "ray intensity (default 1)")->type_name("I");
  option("--source", "coherence id, passed through to every ray (default 0)")->type_name("ch");
  option("--delta-rad", "jump-wise phase δ of the ray in rad (default 0)")->type_name("d");
  option("--optical-path-mm", "optical path O_p so far in mm (default 0)")->type_name("O");
  option("--depth", "tracing depth in 0..64 (default 3)")->type_name("dT");
  option("--tir", "total internal reflection ends the ray or splits it (default stop)")
      ->type_name("stop|split");
  option("--ledge", "rays hitting the ledge end there (the only mode)")->type_name("stop");
  pmsim::cli::parse_or_exit(app, argc, argv);
  auto given = [&](const std::string& name) { return app.count(name) > 0; };

  pmsim::PolarizedRay in;
  in.origin = parse_vec3("--origin", a["--origin"]);
  const glm::dvec3 dir = parse_vec3("--dir", a["--dir"]);
  if (!(glm::length(dir) > 0.0)) throw InputError("", "--dir", a["--dir"], "must be a non-zero vector");
  in.dir = glm::normalize(dir);
  const glm::dvec3 pol = parse_vec3("--pol", a["--pol"]);
  if (!(glm::length(pol) > 0.0)) throw InputError("", "--pol", a["--pol"], "must be a non-zero vector");
  in.pol = glm::normalize(pol);
  if (std::abs(glm::dot(in.pol, in.dir)) > 1e-6)
    throw InputError("", "--pol", a["--pol"], "must be perpendicular to --dir (to 1e-6)");
  in.wavelength_nm = parse_double("--wavelength-nm", a["--wavelength-nm"]);
  if (!(in.wavelength_nm > 0.0)) throw InputError("", "--wavelength-nm", a["--wavelength-nm"], "must be > 0");
  if (given("--intensity")) {
    in.intensity = parse_double("--intensity", a["--intensity"]);
    if (in.intensity < 0.0) throw InputError("", "--intensity", a["--intensity"], "must be ≥ 0");
  }
  if (given("--source")) {
    const long s = parse_int("--source", a["--source"]);
    if (s < INT32_MIN || s > INT32_MAX) throw InputError("", "--source", a["--source"], "out of range");
    in.source = int(s);
  }
  if (given("--delta-rad")) in.delta_rad = parse_double("--delta-rad", a["--delta-rad"]);
  if (given("--optical-path-mm"))
    in.optical_path_mm = parse_double("--optical-path-mm", a["--optical-path-mm"]);

  pmsim::LensTraceOptions opt;
  if (given("--depth")) {
    const long d = parse_int("--depth", a["--depth"]);
    if (d < 0 || d > 64) throw InputError("", "--depth", a["--depth"], "must be in 0..64");
    opt.max_depth = int(d);
  }
  if (given("--tir")) {
    const std::string& t = a["--tir"];
    if (t == "stop")
      opt.tir = pmsim::TirMode::Stop;
    else if (t == "split")
      opt.tir = pmsim::TirMode::Split;
    else
      throw InputError("", "--tir", t, "expected stop or split");
  }
  if (given("--ledge") && a["--ledge"] != "stop")
    throw InputError("", "--ledge", a["--ledge"], "expected stop");

  const pmsim::Lens lens(pmsim::load_lens_spec(a["--lens"]));
  // The model covers the visible range only (the paper's 380–780 nm); outside it the glass data
  // may also be missing, which Medium::n reports as std::out_of_range.
  if (in.wavelength_nm < 380.0 || in.wavelength_nm > 780.0)
    throw InputError("", "--wavelength-nm", a["--wavelength-nm"], "must lie in 380-780 nm");
  pmsim::LensMedia media;
  try {
    media = lens.media(in.wavelength_nm);
  } catch (const std::out_of_range& e) {
    throw InputError("", "--wavelength-nm", a["--wavelength-nm"], e.what());
  }
  if (!std::isfinite(media.n_glass) || !(media.n_glass > 0) || !std::isfinite(media.n_medium))
    throw InputError("", "--wavelength-nm", a["--wavelength-nm"], "no refractive index there");
  pmsim::LensBundle b;
  pmsim::trace_lens(lens.geometry(), media, in, opt, b);

  std::string out = "{\"rays\":[";
  for (size_t i = 0; i < b.rays.size(); ++i) {
    const pmsim::PolarizedRay& r = b.rays[i];
    if (i) out += ",";
    out += "{\"origin\":" + vec(r.origin) + ",\"dir\":" + vec(r.dir) + ",\"pol\":" + vec(r.pol) +
           ",\"intensity\":" + num(r.intensity) + ",\"delta_rad\":" + num(r.delta_rad) +
           ",\"optical_path_mm\":" + num(r.optical_path_mm) + ",\"depth\":" + std::to_string(r.depth) +
           ",\"source\":" + std::to_string(r.source) + ",\"wavelength_nm\":" + num(r.wavelength_nm) + "}";
  }
  out += "],\"events\":[";
  for (size_t i = 0; i < b.events.size(); ++i) {
    const pmsim::LensEvent& e = b.events[i];
    if (i) out += ",";
    out += std::string("{\"type\":\"") + pmsim::to_string(e.type) +
           "\",\"depth\":" + std::to_string(e.depth) + ",\"intensity\":" + num(e.intensity) +
           ",\"point\":" + vec(e.point) + "}";
  }
  out += "],\"absorbed\":" + num(b.absorbed) + "}\n";
  std::cout << out << std::flush;
  return std::cout ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const InputError& e) {
    std::cerr << kProgram << ": " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << "\n";
    return 1;
  }
}
