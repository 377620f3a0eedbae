#include "core/microscope/section_map.h"

#include <cmath>
#include <fstream>
#include <map>
#include <mutex>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/base/input_error.h"
#include "core/base/json_reader.h"
#include "core/base/units.h"
#include "core/microscope/sample_source.h"

namespace pmsim {

namespace {
// Squared distance of p from grain g's seed in its anisotropic metric, over its weight².
inline double grain_distance(const SectionGrain& g, const glm::dvec2& p) {
  const glm::dvec2 d = p - g.seed;
  const double c = g.cos_elong, s = g.sin_elong;
  const double along = (d.x * c + d.y * s) / g.elongation, across = -d.x * s + d.y * c;
  return (along * along + across * across) / (g.weight * g.weight);
}
}  // namespace

void SectionMap::build_index() {
  const int N = kIndexCells;
  const double cell = 2.0 * kIndexHalf / N;
  cell_start_.assign(1, 0);
  cell_grains_.clear();
  std::vector<double> lower(grains.size());
  for (int cy = 0; cy < N; ++cy)
    for (int cx = 0; cx < N; ++cx) {
      const glm::dvec2 lo{-kIndexHalf + cx * cell, -kIndexHalf + cy * cell}, hi = lo + glm::dvec2(cell);
      // dist is a convex quadratic: its maximum over the cell is at a corner; its minimum is at
      // least min(1, 1/e²)·|p − seed|²/w² ≥ that factor times the cell's squared distance.
      double upper = 1e300;
      for (std::size_t i = 0; i < grains.size(); ++i) {
        const SectionGrain& g = grains[i];
        double u = 0.0;
        for (const glm::dvec2 c : {lo, hi, glm::dvec2(lo.x, hi.y), glm::dvec2(hi.x, lo.y)})
          u = std::max(u, grain_distance(g, c));
        upper = std::min(upper, u * (1.0 + 1e-9));
        const double dx = std::max({lo.x - g.seed.x, 0.0, g.seed.x - hi.x});
        const double dy = std::max({lo.y - g.seed.y, 0.0, g.seed.y - hi.y});
        const double e = g.elongation;
        lower[i] = (dx * dx + dy * dy) * std::min(1.0, 1.0 / (e * e)) / (g.weight * g.weight) * (1.0 - 1e-9);
      }
      for (std::size_t i = 0; i < grains.size(); ++i)
        if (lower[i] <= upper) cell_grains_.push_back(static_cast<int>(i));
      cell_start_.push_back(static_cast<int>(cell_grains_.size()));
    }
  indexed_grains_ = grains.size();
}

int SectionMap::nearest_grain(const glm::dvec2& p) const {
  const int* first = nullptr;
  const int* last = nullptr;
  if (indexed_grains_ == grains.size() && !cell_start_.empty()) {
    const double fx = (p.x + kIndexHalf) / (2.0 * kIndexHalf) * kIndexCells;
    const double fy = (p.y + kIndexHalf) / (2.0 * kIndexHalf) * kIndexCells;
    if (fx >= 0 && fy >= 0 && fx < kIndexCells && fy < kIndexCells) {
      const int c = static_cast<int>(fy) * kIndexCells + static_cast<int>(fx);
      first = cell_grains_.data() + cell_start_[c];
      last = cell_grains_.data() + cell_start_[c + 1];
    }
  }
  int best = 0;
  double best_d = 1e300;
  if (first) {  // candidates in increasing index: the same winner as the full search, ties included
    for (const int* it = first; it != last; ++it) {
      const double dist = grain_distance(grains[*it], p);
      if (dist < best_d) {
        best_d = dist;
        best = *it;
      }
    }
    return best;
  }
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const double dist = grain_distance(grains[i], p);
    if (dist < best_d) {
      best_d = dist;
      best = static_cast<int>(i);
    }
  }
  return best;
}

int SectionMap::domain_at(const glm::dvec2& p) const {
  const int best = nearest_grain(p);
  const SectionGrain& g = grains[best];
  int lamella = 0;
  if (g.twinned) {
    lamella = static_cast<int>(std::floor(glm::dot(p - g.seed, g.twin_normal) / g.twin_width)) & 1;
  }
  return 2 * best + lamella;
}

namespace {

using nlohmann::json;

// Rotation by π about unit axis u: R = 2uuᵀ − I.
glm::dmat3 half_turn(const glm::dvec3& u) {
  glm::dmat3 r(0.0);
  for (int c = 0; c < 3; ++c)
    for (int rr = 0; rr < 3; ++rr) r[c][rr] = 2.0 * u[c] * u[rr] - (c == rr ? 1.0 : 0.0);
  return r;
}

SectionMap parse_section(const std::string& path) {
  const json j = read_json_file(path, "thin-section file");
  if (!j.is_object()) throw InputError(path, "", "", "a thin-section file must hold a JSON object");
  const JsonReader r(j, path);
  SectionMap m;
  m.path = path;
  m.name = r.get_or<std::string>("name", path);
  m.source = r.get_or<std::string>("source", "");
  if (r.has("thickness_um")) m.thickness_um = r.require<double>("thickness_um");
  for (const JsonReader& gr : r.objects("grains", 1)) {
    const json& gj = gr.node();
    const std::string& key = gr.prefix();
    auto vec = [&](const char* k, int n) {
      if (!gj.contains(k) || !gj[k].is_array() || static_cast<int>(gj[k].size()) != n)
        throw InputError(path, key + "." + k, gj.contains(k) ? shown(gj[k]) : "",
                         "expected an array of " + std::to_string(n) + " numbers");
      std::vector<double> v;
      for (const json& x : gj[k]) {
        try {
          v.push_back(number_value(x));
        } catch (const BadValue& b) {
          gr.fail(k, gj[k], b.why);
        }
      }
      return v;
    };
    SectionGrain g;
    g.mineral = gr.get_or<std::string>("mineral", "");
    if (!mineral_known(g.mineral))
      throw InputError(path, key + ".mineral", g.mineral,
                       "unknown mineral (known: " + known_minerals_list() + ")");
    g.crystal = &find_mineral(g.mineral);
    const auto s = vec("seed", 2);
    g.seed = {s[0], s[1]};
    g.elongation = gr.get_or("elongation", 1.0, Range::above(0));
    g.elongation_rad = radians(gr.get_or("elongation_deg", 0.0));
    g.weight = gr.get_or("weight", 1.0, Range::above(0));
    try {
      if (g.crystal->symmetry() == CrystalSymmetry::Biaxial) {
        const auto x = vec("x_axis", 3), z = vec("z_axis", 3);
        g.orientation = biaxial_orientation({x[0], x[1], x[2]}, {z[0], z[1], z[2]});
      } else {
        const auto a = vec("optic_axis", 3);
        g.orientation = uniaxial_orientation({a[0], a[1], a[2]});
      }
    } catch (const std::invalid_argument& e) {
      throw InputError(path, key, gj.dump(), e.what());
    }
    if (const auto t = gr.optional_object("twin")) {
      g.twinned = true;
      g.twin_law = "albite";
      g.twin_trace_rad = radians(t->get_or("trace_deg", 0.0));
      g.twin_width = t->get_or("width", 0.05, Range::above(0));
      const glm::dvec3 axis{-std::sin(g.twin_trace_rad), std::cos(g.twin_trace_rad), 0.0};
      g.twin_orientation = half_turn(axis) * g.orientation;
    } else {
      g.twin_orientation = g.orientation;
    }
    g.cos_elong = std::cos(g.elongation_rad);
    g.sin_elong = std::sin(g.elongation_rad);
    g.twin_normal = {-std::sin(g.twin_trace_rad), std::cos(g.twin_trace_rad)};
    m.grains.push_back(std::move(g));
  }
  m.build_index();
  return m;
}

}  // namespace

std::shared_ptr<const SectionMap> load_section(const std::string& name_or_path) {
  const std::string path = section_path(name_or_path);
  if (path.empty())
    throw InputError("", "sample.section", name_or_path, "no such thin-section file in assets/sections");
  static std::mutex mu;
  static std::map<std::string, std::shared_ptr<const SectionMap>> cache;
  std::lock_guard<std::mutex> lock(mu);
  auto it = cache.find(path);
  if (it != cache.end()) return it->second;
  std::shared_ptr<const SectionMap> m;
  try {
    m = std::make_shared<const SectionMap>(parse_section(path));
  } catch (const nlohmann::json::exception& e) {  // a value of the wrong type somewhere
    throw InputError(path, "", "", std::string("bad thin-section file: ") + e.what());
  }
  cache[path] = m;
  return m;
}

}  // namespace pmsim
