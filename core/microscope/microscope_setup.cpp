#include "core/microscope/microscope_setup.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>

#include <tbb/parallel_for.h>

#include "core/crystal/crystal_cut.h"
#include "core/materials/medium.h"
#include "core/microscope/lens_ghosts.h"
#include "core/microscope/sample_source.h"
#include "core/microscope/scene_check.h"
#include "core/microscope/optical_train.h"
#include "core/microscope/view_geometry.h"

namespace pmsim {

namespace {

glm::dvec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

glm::dmat3 sample_orientation(const Crystal& c, const SampleSettings& s) {
  if (s.cut) return cut_plate_orientation(c, s.cut->plane, s.cut->north);  // checked by check_scene
  if (c.symmetry() == CrystalSymmetry::Biaxial) return biaxial_orientation(vec(s.x_axis), vec(s.z_axis));
  return uniaxial_orientation(vec(s.optic_axis));
}

// Points spread evenly over the disk of radius s_max in the sin θ plane (Vogel's spiral): equal
// areas of the condenser aperture, which a condenser filling its aperture lights evenly.
std::vector<glm::dvec3> cone_directions(int n, double s_max) {
  std::vector<glm::dvec3> d;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double r = s_max * std::sqrt((i + 0.5) / n), a = i * golden;
    d.push_back({r * std::cos(a), r * std::sin(a), std::sqrt(std::max(0.0, 1.0 - r * r))});
  }
  return d;
}

int samples_per_side(int spp) { return std::max(1, static_cast<int>(std::ceil(std::sqrt(spp)))); }

struct RefBuilder {
  std::vector<PixelRef> tmp;
  void add(int unit, float w) {
    for (PixelRef& r : tmp)
      if (r.unit == unit) {
        r.weight += w;
        return;
      }
    tmp.push_back({unit, w});
  }
};

// A uniaxial plate with its optic axis along the stage normal is symmetric about it: at any
// direction its modes vibrate radially (e) and tangentially (o), and Γ and the transmissions depend
// on sin θ alone. A conoscopic figure then needs a table of fits over sin²θ (in which Γ is nearly
// linear: Γ ≈ d·Δn·sin²θ/(2n) near the axis), each turned to its pixel's azimuth, instead of three
// mode solutions per pixel. Linear interpolation error ≈ h²/8·Γ'' ≈ 0.01 nm of Γ for 1 mm calcite
// at NA 0.85 with 1025 entries: 1e-4 rad of interference phase at 400 nm.
class RadialModalTable {
 public:
  static constexpr int kEntries = 1025;

  // False when the fits are not radial/tangential (then the table must not be used).
  bool build(const PreparedPlate anchors[3], double s_max) {
    du_ = std::max(1e-12, s_max * s_max) / (kEntries - 1);
    e_.resize(kEntries);
    std::vector<char> good(kEntries, 0);
    int kind = -1;  // 0: e1 radial, 1: e1 tangential
    auto dir = [&](int i) {
      const double s = std::sqrt(i * du_), c = std::sqrt(std::max(0.0, 1.0 - s * s));
      return glm::dvec3{s, 0.0, c};
    };
    // The fits (the cost: three mode solutions each) over the cores; a restart waits for this.
    std::vector<ModalFit> fits(kEntries);
    tbb::parallel_for(tbb::blocked_range<int>(0, kEntries, 32), [&](const tbb::blocked_range<int>& rg) {
      for (int i = rg.begin(); i != rg.end(); ++i) fits[i].fit(anchors, dir(i));
    });
    for (int i = 0; i < kEntries; ++i) {
      const glm::dvec3 k = dir(i), r{k.z, 0.0, -k.x}, t{0.0, 1.0, 0.0};
      glm::dvec3 a, b;
      transverse_basis(k, a, b);
      const ModalFit& fit = fits[i];
      Entry& E = e_[i];
      bool ok = true;
      for (int q = 0; q < 3; ++q) {
        E.gamma[q] = fit.gamma_at_anchor(q);
        E.t1[q] = fit.t1_at_anchor(q);
        E.t2[q] = fit.t2_at_anchor(q);
        const glm::dvec2 v[2] = {fit.e1_at_anchor(q), fit.e2_at_anchor(q)};
        glm::dvec2* out[2] = {&E.e1[q], &E.e2[q]};
        for (int m = 0; m < 2; ++m) {
          const glm::dvec3 e3 = v[m].x * a + v[m].y * b;
          glm::dvec2 rt{glm::dot(e3, r), glm::dot(e3, t)};
          const double len = glm::length(rt);
          rt = len > 1e-300 ? rt / len : glm::dvec2(1.0, 0.0);
          // Canonical sign: the larger component positive (a mode is defined up to sign).
          if ((std::fabs(rt.x) >= std::fabs(rt.y) ? rt.x : rt.y) < 0) rt = -rt;
          *out[m] = rt;
        }
        const int kq = std::fabs(E.e1[q].x) > 0.9999 ? 0 : (std::fabs(E.e1[q].y) > 0.9999 ? 1 : 2);
        const bool orth = std::fabs(glm::dot(E.e1[q], E.e2[q])) < 1e-4;
        if (kq == 2 || !orth || (kind >= 0 && kq != kind && i > 0 && good[i - 1])) ok = false;
        if (ok && q == 2) kind = kq;
      }
      good[i] = ok;
    }
    // Near the axis the modes are degenerate and their directions arbitrary; there Γ is tiny and
    // the directions are taken from the first radial/tangential entry outwards.
    if (!good[kEntries - 1]) return false;
    for (int i = kEntries - 2; i >= 0; --i) {
      if (good[i]) {
        const int kq = std::fabs(e_[i].e1[0].x) > 0.9999 ? 0 : 1;
        const int kn = std::fabs(e_[i + 1].e1[0].x) > 0.9999 ? 0 : 1;
        if (kq != kn) return false;  // the fast mode changes kind: not a simple uniaxial figure
        continue;
      }
      for (int q = 0; q < 3; ++q)
        if (std::fabs(e_[i].gamma[q]) > 0.5) return false;  // ≥ 0.008 rad at 400 nm: must be right
      for (int q = 0; q < 3; ++q) {
        e_[i].e1[q] = e_[i + 1].e1[q];
        e_[i].e2[q] = e_[i + 1].e2[q];
      }
    }
    return true;
  }

  // The fit at direction k_air (unit, k.z > 0), interpolated in sin²θ and turned to its azimuth.
  ModalFit at(const glm::dvec3& k) const {
    const double s2 = k.x * k.x + k.y * k.y, s = std::sqrt(s2);
    const double pos = s2 / du_;
    const int i0 = std::clamp(static_cast<int>(pos), 0, kEntries - 2);
    const double f = pos - i0, g = 1.0 - f;
    const Entry& A = e_[i0];
    const Entry& B = e_[i0 + 1];
    const double cp = s > 0 ? k.x / s : 1.0, sp = s > 0 ? k.y / s : 0.0;
    const glm::dvec3 r{cp * k.z, sp * k.z, -s}, t{-sp, cp, 0.0};
    glm::dvec3 a, b;
    transverse_basis(k, a, b);
    const double ra = glm::dot(r, a), ta = glm::dot(t, a), rb = glm::dot(r, b), tb = glm::dot(t, b);
    auto turn = [&](const glm::dvec2& p, const glm::dvec2& q) {
      const glm::dvec2 rt = g * p + f * q;
      const glm::dvec2 v{rt.x * ra + rt.y * ta, rt.x * rb + rt.y * tb};
      const double len = glm::length(v);
      return len > 1e-300 ? v / len : glm::dvec2(1.0, 0.0);
    };
    double gamma[3], t1[3], t2[3];
    glm::dvec2 e1[3], e2[3];
    for (int q = 0; q < 3; ++q) {
      gamma[q] = g * A.gamma[q] + f * B.gamma[q];
      t1[q] = g * A.t1[q] + f * B.t1[q];
      t2[q] = g * A.t2[q] + f * B.t2[q];
      e1[q] = turn(A.e1[q], B.e1[q]);
      e2[q] = turn(A.e2[q], B.e2[q]);
    }
    ModalFit fit;
    fit.assign(gamma, e1, e2, t1, t2);
    return fit;
  }

 private:
  struct Entry {
    double gamma[3], t1[3], t2[3];
    glm::dvec2 e1[3], e2[3];  // (radial, tangential) components
  };
  std::vector<Entry> e_;
  double du_ = 1.0;
};

}  // namespace

PreparedPlate MicroscopeSetup::prepare(int domain, double wavelength_nm) const {
  const OpticalDomain& d = domains[domain];
  PlateSpec spec;
  spec.crystal = d.crystal;
  spec.crystal_to_lab = d.crystal_to_lab;
  spec.thickness_um = d.thickness_um > 0 ? d.thickness_um : 1.0;
  spec.n_outside = find_medium(scene.sample.medium).n(wavelength_nm);
  spec.fresnel = true;
  return prepare_plate(spec, wavelength_nm);
}

void MicroscopeSetup::lens_jones(const glm::dvec3& k, glm::dmat2& c, glm::dmat2& o) const {
  // Condenser: lab pupil → the ray's transverse basis (aplanatic mapping), then the physical
  // lens' s/p diattenuation; the objective the reverse. Same profile for both (reciprocity).
  const glm::dmat2 F = aplanatic_frame(k);
  if (!lenses) {
    c = F;
    o = glm::transpose(F);
    return;
  }
  const glm::dmat2 D = lenses->jones(k);
  c = D * F;
  o = glm::transpose(F) * D;
}

JonesMatrix MicroscopeSetup::with_lenses(const JonesMatrix& J, const glm::dvec3& k) const {
  glm::dmat2 c, o;
  lens_jones(k, c, o);
  const JonesMatrix C{c[0][0], c[1][0], c[0][1], c[1][1]}, O{o[0][0], o[1][0], o[0][1], o[1][1]};
  return O * J * C;
}

namespace {
// CIELAB lightness (CIE 15:2004 §8.2.1) of a relative luminance, Y_white = 1.
double lightness(double Y) {
  const double e = 216.0 / 24389.0, k = 24389.0 / 27.0;
  return Y > e ? 116.0 * std::cbrt(Y) - 16.0 : k * Y;
}

// Mean lightness difference at 550 nm between the ideal and the physical lens model over a subset
// of the units: the estimate behind optics.lens_model = auto. The lenses only change polarization
// and transmission (not the spectrum), so the grey-level difference at mid-spectrum is their effect.
double lens_model_difference(const MicroscopeSetup& S, const LensPolarizationTable& table) {
  const TrainState train = make_train(S.scene, S.compensator, 550.0);
  std::vector<PreparedPlate> prepared(S.domains.size());
  for (std::size_t d = 0; d < S.domains.size(); ++d)
    if (S.domains[d].crystal) prepared[d] = S.prepare(static_cast<int>(d), 550.0);
  const std::size_t stride = std::max<std::size_t>(1, S.units.size() / 512);
  double sum = 0.0;
  int n = 0;
  for (std::size_t u = 0; u < S.units.size(); u += stride) {
    const EvalUnit& unit = S.units[u];
    const int D = S.dirs_of(unit);
    for (int d = 0; d < D; d += std::max(1, D / 8)) {
      const glm::dvec3 k = S.dir(unit, d);
      JonesMatrix J = JonesMatrix::identity();
      if (S.domains[unit.domain].crystal && unit.thickness_um > 0) {
        PreparedPlate p = prepared[unit.domain];
        p.thickness_um = unit.thickness_um;
        J = plate_jones(p, k);
      }
      const glm::dmat2 F = aplanatic_frame(k), Ft = glm::transpose(F), m = table.jones(k);
      const glm::dmat2 c = m * F, o = Ft * m;
      const JonesMatrix Ci{F[0][0], F[1][0], F[0][1], F[1][1]}, Oi{Ft[0][0], Ft[1][0], Ft[0][1], Ft[1][1]};
      const JonesMatrix C{c[0][0], c[1][0], c[0][1], c[1][1]}, O{o[0][0], o[1][0], o[0][1], o[1][1]};
      const double ideal = jones_transmission(train, Oi * J * Ci), physical = jones_transmission(train, O * J * C);
      sum += std::fabs(lightness(ideal) - lightness(physical));
      ++n;
    }
  }
  return n ? sum / n : 0.0;
}
}  // namespace

std::shared_ptr<const MicroscopeSetup> build_setup(const Scene& scene,
                                                   const std::atomic<bool>* cancel) {
  check_scene(scene);
  auto S = std::make_shared<MicroscopeSetup>();
  S->scene = scene;
  const int W = scene.render.width, H = scene.render.height;
  const double stage_rad = scene.stage_deg * std::numbers::pi / 180.0;
  const bool cono = scene.mode == ViewMode::Cono;
  const SampleType type = scene.sample.type;

  // Domains.
  if (!scene.sample_in) {
    S->domains.push_back({nullptr, glm::dmat3(1.0), scene.sample.thickness_um, "empty stage"});
  } else if (type == SampleType::Section) {
    S->section = load_section(scene.sample.section);
    for (int d = 0; d < S->section->domain_count(); ++d) {
      const SectionGrain& g = S->section->grain_of_domain(d);
      S->domains.push_back({g.crystal, rotate_stage(S->section->orientation_of_domain(d), stage_rad),
                            scene.sample.thickness_um, g.mineral});
    }
  } else {
    const Crystal* c;
    if (scene.sample.crystal) {
      S->custom_crystal = std::make_shared<Crystal>(crystal_from_indices(*scene.sample.crystal));
      c = S->custom_crystal.get();
    } else {
      c = &find_mineral(scene.sample.mineral);
    }
    S->domains.push_back({c, rotate_stage(sample_orientation(*c, scene.sample), stage_rad),
                          scene.sample.thickness_um, scene.sample.crystal ? "custom crystal" : c->name()});
  }
  S->compensator = make_compensator(scene.compensator, scene.compensator_position);

  // Which domain a sample-frame point shows.
  auto domain_at_sample = [&](const glm::dvec2& p) -> int {
    if (!scene.sample_in || type != SampleType::Section) return 0;
    return S->section->domain_at(p);
  };
  const bool is_wedge = scene.sample_in && type == SampleType::Wedge;

  const int spp_side = samples_per_side(scene.render.spp > 0 ? scene.render.spp
                                        : (scene.sample_in && type != SampleType::Plate ? 4 : 1));
  S->pixel_offset.assign(static_cast<std::size_t>(W) * H + 1, 0);

  // Units in parallel light (or cone-integrated): one per domain, or one per thickness step of a
  // wedge. Created up front so that the per-pixel pass below is read-only and runs in parallel.
  const int wedge_steps = cono ? 256 : 2 * std::max(W, H);
  const bool field_units = !(cono && scene.bertrand_in);
  if (field_units) {
    const int n = is_wedge ? wedge_steps : static_cast<int>(S->domains.size());
    for (int i = 0; i < n; ++i) {
      EvalUnit u;
      u.domain = is_wedge ? 0 : i;
      u.cone = cono;
      u.thickness_um = is_wedge ? scene.sample.thickness_um * i / (wedge_steps - 1.0)
                                : S->domains[i].thickness_um;
      S->units.push_back(u);
    }
  }
  const StageToSample to_sample(scene.stage_deg);
  // Refs of a field point seen in parallel (or cone) light.
  auto add_field_point = [&](RefBuilder& rb, const glm::dvec2& f, float w) {
    const glm::dvec2 p = to_sample(f);
    if (is_wedge) {
      const double pos = wedge_thickness_um(scene, p) / scene.sample.thickness_um * (wedge_steps - 1);
      const int i0 = std::min(static_cast<int>(pos), wedge_steps - 2);
      const float frac = static_cast<float>(pos - i0);
      rb.add(i0, w * (1 - frac));
      rb.add(i0 + 1, w * frac);
    } else {
      rb.add(domain_at_sample(p), w);
    }
  };

  std::ostringstream report;
  if (cono && scene.bertrand_in) {
    // The back focal plane: one unit per lit pixel, the domain under the field centre.
    const glm::dvec2 centre = sample_from_field({0.0, 0.0}, scene.stage_deg);
    const int dom = domain_at_sample(centre);
    const double d = is_wedge ? wedge_thickness_um(scene, centre) : S->domains[dom].thickness_um;
    // Directions per pixel in parallel (rows), then numbered in order.
    std::vector<glm::dvec3> k_px(static_cast<std::size_t>(W) * H);
    std::vector<char> lit_px(k_px.size());
    tbb::parallel_for(tbb::blocked_range<int>(0, H, 16), [&](const tbb::blocked_range<int>& r) {
      if (cancel && *cancel) return;
      for (int y = r.begin(); y != r.end(); ++y)
        for (int x = 0; x < W; ++x) {
          const std::size_t i = static_cast<std::size_t>(y) * W + x;
          lit_px[i] = bfp_direction(scene, field_from_pixel(W, H, x + 0.5, y + 0.5), k_px[i]);
        }
    });
    if (cancel && *cancel) return nullptr;
    const std::size_t n_lit = static_cast<std::size_t>(std::count(lit_px.begin(), lit_px.end(), 1));
    S->units.reserve(S->units.size() + n_lit);
    S->refs.reserve(n_lit);
    for (std::size_t i = 0; i < k_px.size(); ++i) {
      S->pixel_offset[i] = static_cast<int>(S->refs.size());
      if (!lit_px[i]) continue;
      EvalUnit u;
      u.domain = dom;
      u.thickness_um = d;
      u.k_air = k_px[i];
      S->units.push_back(u);
      S->refs.push_back({static_cast<int>(S->units.size()) - 1, 1.0f});
    }
    S->spatial_samples = 1;
    report << "view: conoscopic figure, one evaluation per pixel (" << S->units.size() << ")";
  } else if (!cono && scene.bertrand_in) {
    // Parallel light focuses to a small spot in the back focal plane: the whole field's light.
    RefBuilder field;
    const int n = 8;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        add_field_point(field, field_from_pixel(n, n, i + 0.5, j + 0.5), 1.0f / (n * n));
    const double rho_spot = kParallelBeamSinTheta / scene.objective.na;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * W + x;
        S->pixel_offset[i] = static_cast<int>(S->refs.size());
        const glm::dvec2 f = field_from_pixel(W, H, x + 0.5, y + 0.5);
        if (std::hypot(f.x, f.y) <= rho_spot)
          S->refs.insert(S->refs.end(), field.tmp.begin(), field.tmp.end());
      }
    report << "view: back focal plane in parallel light (spot of sin θ = " << kParallelBeamSinTheta << ")";
  } else {
    const bool cone = cono;  // cono without Bertrand: the image plane lit by the whole cone
    if (cone) {
      const double s_max = std::min(scene.condenser.na, scene.objective.na);
      S->cone_dirs = cone_directions(scene.render.spp > 0 ? std::max(1, scene.render.spp) : 64, s_max);
    }
    const int n = spp_side;
    S->spatial_samples = n * n;
    // Sections: the domain at every pixel centre first; only pixels on a grain or lamella boundary
    // (a 4-neighbour differs) need the sub-pixel samples.
    const bool section_map = scene.sample_in && type == SampleType::Section && n > 1;
    std::vector<int> centre_domain;
    if (section_map) {
      centre_domain.resize(static_cast<std::size_t>(W) * H);
      tbb::parallel_for(tbb::blocked_range<int>(0, H, 8), [&](const tbb::blocked_range<int>& r) {
        if (cancel && *cancel) return;
        for (int y = r.begin(); y != r.end(); ++y)
          for (int x = 0; x < W; ++x)
            centre_domain[static_cast<std::size_t>(y) * W + x] = domain_at_sample(
                to_sample(field_from_pixel(W, H, x + 0.5, y + 0.5)));
      });
      if (cancel && *cancel) return nullptr;
    }
    auto interior = [&](int x, int y) {
      const int d = centre_domain[static_cast<std::size_t>(y) * W + x];
      auto same = [&](int xx, int yy) {
        return xx < 0 || yy < 0 || xx >= W || yy >= H || centre_domain[static_cast<std::size_t>(yy) * W + xx] == d;
      };
      return same(x - 1, y) && same(x + 1, y) && same(x, y - 1) && same(x, y + 1);
    };
    // A uniform sample (one unit, no wedge or section): every pixel shows unit 0 with the summed
    // weight of its sub-samples — filled directly, without per-sample bookkeeping.
    const bool uniform = !is_wedge && !(scene.sample_in && type == SampleType::Section) && S->units.size() == 1;
    if (uniform) {
      float w = 0.0f;
      for (int k = 0; k < n * n; ++k) w += 1.0f / (n * n);  // as RefBuilder sums them
      const std::size_t P = static_cast<std::size_t>(W) * H;
      S->refs.assign(P, PixelRef{0, w});
      for (std::size_t i = 0; i < P; ++i) S->pixel_offset[i] = static_cast<int>(i);
    }
    // Rows in parallel, each into its own list, then concatenated in order.
    std::vector<std::vector<PixelRef>> row_refs(uniform ? 0 : H);
    std::vector<std::vector<int>> row_counts(H);
    tbb::parallel_for(tbb::blocked_range<int>(0, uniform ? 0 : H, 4), [&](const tbb::blocked_range<int>& r) {
      RefBuilder rb;
      for (int y = r.begin(); y != r.end(); ++y) {
        if (cancel && *cancel) return;
        row_counts[y].resize(W);
        for (int x = 0; x < W; ++x) {
          rb.tmp.clear();
          if (section_map && interior(x, y)) {
            rb.tmp.push_back({centre_domain[static_cast<std::size_t>(y) * W + x], 1.0f});
            row_counts[y][x] = 1;
            row_refs[y].push_back(rb.tmp[0]);
            continue;
          }
          for (int sy = 0; sy < n; ++sy)
            for (int sx = 0; sx < n; ++sx)
              add_field_point(rb, field_from_pixel(W, H, x + (sx + 0.5) / n, y + (sy + 0.5) / n),
                              1.0f / (n * n));
          row_counts[y][x] = static_cast<int>(rb.tmp.size());
          row_refs[y].insert(row_refs[y].end(), rb.tmp.begin(), rb.tmp.end());
        }
      }
    });
    if (cancel && *cancel) return nullptr;
    for (int y = 0; y < (uniform ? 0 : H); ++y) {
      int k = 0;
      for (int x = 0; x < W; ++x) {
        S->pixel_offset[static_cast<std::size_t>(y) * W + x] = static_cast<int>(S->refs.size()) + k;
        k += row_counts[y][x];
      }
      S->refs.insert(S->refs.end(), row_refs[y].begin(), row_refs[y].end());
    }
    report << "view: " << (cone ? "image plane in the convergent cone (" + std::to_string(S->cone_dirs.size()) + " directions)"
                                : std::string("orthoscopic, parallel light"))
           << ", " << S->units.size() << " spectral evaluation" << (S->units.size() == 1 ? "" : "s")
           << " for the field";
  }
  S->pixel_offset[static_cast<std::size_t>(W) * H] = static_cast<int>(S->refs.size());

  // Plate model: modal unless the scene asks for the exact Jones matrix per wavelength. The modal
  // fit carries linear eigenmodes only; optical activity makes them elliptical near the optic
  // axis, so there (see the criterion below) units of optically active crystals use the exact
  // Jones matrix per band.
  bool active = false;
  for (const OpticalDomain& d : S->domains)
    if (d.crystal && d.crystal->optically_active()) active = true;
  const RenderStrategy strat = scene.render.strategy;
  const bool single = scene.render.single_wavelength_nm > 0;
  const bool hybrid = strat == RenderStrategy::Auto && active && !single;
  S->plate_model = (strat == RenderStrategy::Exact || single) ? PlateModel::Exact : PlateModel::Modal;
  report << "; plate: "
         << (S->plate_model == PlateModel::Exact
                 ? (single ? "exact Jones matrix (single wavelength)" : "exact Jones matrix per wavelength")
                 : "modal fit (3 mode solutions per direction, band-averaged interference)");
  // Lenses. In parallel light every ray runs along the axis, where the two models agree exactly
  // (the physical one is normalised to its axial transmission), so only oblique light can need
  // the physical model.
  const bool oblique = cono;
  char buf[160];
  if (scene.optics.lens_model == LensModel::Physical) {
    S->lenses = &lens_polarization_table(scene.optics.schlick);
    report << "; condenser, objective: physical SML lenses (Fresnel " << (scene.optics.schlick ? "Schlick" : "exact")
           << ", depth-0 path)";
  } else if (scene.optics.lens_model == LensModel::Auto && oblique) {
    const LensPolarizationTable& table = lens_polarization_table(scene.optics.schlick);
    const double diff = lens_model_difference(*S, table);
    if (diff > scene.render.tolerance_de2000) {
      S->lenses = &table;
      std::snprintf(buf, sizeof buf, "; condenser, objective: physical SML lenses (auto: ideal would differ by ΔL*≈%.2f)", diff);
    } else {
      std::snprintf(buf, sizeof buf, "; condenser, objective: ideal (auto: physical differs by ΔL*≈%.2f)", diff);
    }
    report << buf;
  } else {
    report << "; condenser, objective: ideal (perfect imaging, polarization kept"
           << (scene.optics.lens_model == LensModel::Auto ? "; auto: exact for axial light)" : ")");
  }
  report << "; Bertrand lens: ideal (images the back focal plane)";

  if (S->plate_model == PlateModel::Modal) {
    S->dirs_per_unit = S->cone_dirs.empty() ? 1 : static_cast<int>(S->cone_dirs.size());
    const int D = S->dirs_per_unit;
    S->terms.resize(S->units.size() * D);
    S->unit_exact.assign(S->units.size(), 0);
    const TrainState train = make_train(scene, S->compensator, 550.0);  // its directions only
    // Anchors prepared once per domain.
    std::vector<std::array<PreparedPlate, 3>> anchors(S->domains.size());
    for (std::size_t d = 0; d < S->domains.size(); ++d)
      if (S->domains[d].crystal)
        for (int a = 0; a < 3; ++a) anchors[d][a] = S->prepare(static_cast<int>(d), ModalFit::kAnchorNm[a]);
    // A conoscopic figure of a uniaxial plate cut ⟂ its optic axis: a radial table of fits.
    RadialModalTable radial;
    bool use_radial = false;
    // The table costs kEntries fits plus its checks; the direct way one fit per unit: the table
    // wins from about twice as many units (a 64² glance of a figure has ~3 200).
    if (cono && scene.bertrand_in && S->units.size() > 2 * RadialModalTable::kEntries) {
      const int dom = S->units.front().domain;
      const OpticalDomain& D0 = S->domains[dom];
      bool one_domain = true;
      double s_max = 0.0;
      for (const EvalUnit& u : S->units) {
        one_domain = one_domain && u.domain == dom;
        s_max = std::max(s_max, std::hypot(u.k_air.x, u.k_air.y));
      }
      if (one_domain && D0.crystal && D0.crystal->symmetry() == CrystalSymmetry::Uniaxial &&
          std::fabs(D0.crystal_to_lab[2].z) > 1.0 - 1e-12)
        use_radial = radial.build(anchors[dom].data(), std::min(1.0, s_max * (1.0 + 1e-9)));
      if (use_radial)
        report << "; optic axis ⟂ stage: modal fits from a radial table of "
               << RadialModalTable::kEntries << " directions";
    }
    // Absorbing (pleochroic) crystals: the fit interpolates their transmission from its three
    // anchor wavelengths, which left the biotite grains of the granite at mean ΔE00 0.7 where
    // exact Jones matrices per band reach 0.1. In parallel light a grain is one evaluation for
    // the whole field, so exactness costs nothing worth saving; per-pixel figures keep the fit.
    const bool exact_absorbing = strat == RenderStrategy::Auto && !single && field_units;
    std::atomic<bool> stop{false};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, S->units.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        if (stop || (cancel && *cancel)) {
                          stop = true;
                          return;
                        }
                        for (std::size_t u = r.begin(); u != r.end(); ++u) {
                          const EvalUnit& unit = S->units[u];
                          const OpticalDomain& dom = S->domains[unit.domain];
                          for (int d = 0; d < S->dirs_of(unit); ++d) {
                            glm::dmat2 jc, jo;
                            S->lens_jones(S->dir(unit, d), jc, jo);
                            const glm::dmat2* pc = &jc;
                            const glm::dmat2* po = &jo;
                            if (!dom.crystal || unit.thickness_um <= 0.0) {
                              S->terms[u * D + d] = identity_modal_terms(train, pc, po);
                              continue;
                            }
                            ModalFit fit;
                            if (use_radial)
                              fit = radial.at(S->dir(unit, d));
                            else
                              fit.fit(anchors[unit.domain].data(), S->dir(unit, d));
                            if (exact_absorbing && dom.crystal->absorbing()) S->unit_exact[u] = 1;
                            if (hybrid && dom.crystal->optically_active()) {
                              // Elliptical modes have ellipticity ≈ (rotation)/(linear phase);
                              // the linear model's intensity error is its square: keep it below
                              // ~1e-3 (rotation < linear phase / 30) or go exact.
                              const double rot = std::fabs(dom.crystal->rotatory_power_rad_per_um(400.0)) *
                                                 unit.thickness_um;
                              const double lin = 2.0 * std::numbers::pi * fit.retardation_nm(400.0) *
                                                 unit.thickness_um / dom.thickness_um / 400.0;
                              if (lin < 30.0 * rot) S->unit_exact[u] = 1;
                            }
                            S->terms[u * D + d] = make_modal_terms(
                                fit, train, unit.thickness_um / dom.thickness_um, pc, po);
                          }
                        }
                      });
    if (stop) return nullptr;
    const auto n_exact = std::count(S->unit_exact.begin(), S->unit_exact.end(), 1);
    if (n_exact > 0)
      report << "; exact Jones matrix for " << n_exact << " of " << S->units.size()
             << " evaluations (absorbing crystals in parallel light; optically active ones near the axis)";
  }
  if (S->lenses && scene.optics.lens_depth >= 2 && cono && scene.bertrand_in) {
    LensGhostImage ghosts = lens_ghost_image(*S, cancel);
    if (cancel && *cancel) return nullptr;
    S->ghost_xyz = std::move(ghosts.xyz);
    std::size_t lit = 0;
    for (std::size_t i = 0; i + 1 < S->pixel_offset.size(); ++i) lit += S->pixel_offset[i + 1] > S->pixel_offset[i];
    std::snprintf(buf, sizeof buf,
                  "; lens ghosts (dT = %d): %d paths, objective %.3f %% + condenser %.3f %% of a white field",
                  scene.optics.lens_depth, ghosts.paths, 100.0 * ghosts.objective_energy / std::max<std::size_t>(1, lit),
                  100.0 * ghosts.condenser_energy / std::max<std::size_t>(1, lit));
    report << buf;
  } else if (S->lenses && cono && scene.bertrand_in) {
    report << "; lens ghosts: none (optics.lens_depth < 2: no internal reflection reaches the image)";
  }
  S->model_report = report.str();
  return S;
}

int domain_at_image_point(const MicroscopeSetup& S, double x_frac, double y_frac) {
  const Scene& sc = S.scene;
  const glm::dvec2 f = field_from_pixel(sc.render.width, sc.render.height, x_frac * sc.render.width,
                                        y_frac * sc.render.height);
  if (sc.mode == ViewMode::Cono && sc.bertrand_in) {
    glm::dvec3 k;
    if (!bfp_direction(sc, f, k)) return -1;
    const glm::dvec2 c = sample_from_field({0.0, 0.0}, sc.stage_deg);
    return S.section ? S.section->domain_at(c) : 0;
  }
  const glm::dvec2 p = sample_from_field(f, sc.stage_deg);
  return (S.section && sc.sample_in) ? S.section->domain_at(p) : 0;
}

}  // namespace pmsim
