#include "core/specimen/specimen_response.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/base/units.h"
#include "core/microscope/compensator.h"
#include "core/render/cubic_sample.h"
#include "core/spectrum/color.h"
#include "core/specimen/plane_light_passes.h"

namespace pmsim {

namespace {

using namespace cubic;  // v4, load4, store4, transpose and Keys' cubic reads

using Stokes = std::array<double, 4>;
using Vec4 = std::array<double, 4>;

// ½·Cᵀ·s: the analyzer's state seen through the accessory (I = ½ sᵀ C M t = (½ Cᵀ s)ᵀ M t).
Vec4 through(const Mueller4& c, const Stokes& s) {
  Vec4 v{};
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 4; ++i) v[std::size_t(k)] += 0.5 * c[std::size_t(4 * i + k)] * s[std::size_t(i)];
  return v;
}

// The accessory's cos δ and sin δ averaged over a band (8 points across it): a band of 12.5 nm
// is narrow against the period λ²/Γ of the accessory's own oscillation (≥ 60 nm for the wedge's
// four orders at 380 nm), so the average is what the band's λ points would give.
void band_retardance(const CompensatorPlate& plate, double lo_nm, double width_nm, double& c, double& s) {
  constexpr int kPoints = 8;
  c = s = 0.0;
  for (int k = 0; k < kPoints; ++k) {
    const double lambda = lo_nm + width_nm * (k + 0.5) / kPoints;
    const double delta = 2.0 * kPi * compensator_retardation_nm(plate, lambda) / lambda;
    c += std::cos(delta) / kPoints;
    s += std::sin(delta) / kPoints;
  }
}

// A buffer kept between frames for one role (the contracted grid, the contracted nodes): a fresh
// 2–9 MB buffer a frame costs its page faults and zero-filling. One buffer a role, the largest
// asked for; a frame composed while another holds it takes a fresh one.
class ScratchSlot {
 public:
  std::vector<float> take(std::size_t n) {
    std::vector<float> v;
    {
      std::lock_guard<std::mutex> lock(mu_);
      v.swap(kept_);
    }
    if (v.size() < n) v.resize(n);
#ifndef NDEBUG
    std::fill(v.begin(), v.end(), std::numeric_limits<float>::quiet_NaN());  // a read outside the spans shows
#endif
    return v;
  }
  void give(std::vector<float>&& v) {
    std::lock_guard<std::mutex> lock(mu_);
    if (v.size() > kept_.size()) kept_.swap(v);
  }

 private:
  std::mutex mu_;
  std::vector<float> kept_;
};
ScratchSlot& grid_slot() {
  static ScratchSlot s;
  return s;
}
ScratchSlot& node_slot() {
  static ScratchSlot s;
  return s;
}

// Per row of a field of points, the columns [lo, hi] a frame's samples read (lo > hi: none).
struct Spans {
  std::vector<int> lo, hi;
};

// The columns of each row of a w × h field that samples anywhere in the convex quad `q` (the
// image's pixel centres in point units) read with a kernel of points floor(x) − before …
// floor(x) + after, with one point more on each side for the rounding of the positions. Where the
// quad leaves the field the samples are clamped: every point then counts as read.
Spans read_spans(const std::array<glm::dvec2, 4>& q, int w, int h, int before, int after) {
  Spans sp;
  sp.lo.assign(std::size_t(h), 0);
  sp.hi.assign(std::size_t(h), w - 1);
  for (const glm::dvec2& p : q)
    if (!(p.x >= 0.0 && p.x <= w - 1 && p.y >= 0.0 && p.y <= h - 1)) return sp;
  for (int j = 0; j < h; ++j) {
    // Samples with j among their rows lie in y ∈ [j − after, j + before + 1), widened by one.
    const double ylo = j - after - 1.0, yhi = j + before + 2.0;
    double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin;
    for (std::size_t e = 0; e < 4; ++e) {
      const glm::dvec2 a = q[e], b = q[(e + 1) % 4];
      double t0 = 0.0, t1 = 1.0;
      if (a.y == b.y) {
        if (a.y < ylo || a.y > yhi) continue;
      } else {
        double ta = (ylo - a.y) / (b.y - a.y), tb = (yhi - a.y) / (b.y - a.y);
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) continue;
      }
      for (const double t : {t0, t1}) {
        const double x = a.x + t * (b.x - a.x);
        xmin = std::min(xmin, x);
        xmax = std::max(xmax, x);
      }
    }
    if (xmin > xmax) {
      sp.lo[std::size_t(j)] = 1;
      sp.hi[std::size_t(j)] = 0;
      continue;
    }
    sp.lo[std::size_t(j)] = std::clamp(int(std::floor(xmin)) - before - 1, 0, w - 1);
    sp.hi[std::size_t(j)] = std::clamp(int(std::floor(xmax)) + after + 1, 0, w - 1);
  }
  return sp;
}

// Where the image's pixel centres fall on the grid (in grid points) at a frame: the map the
// sampling uses, and the corners of the field it covers.
struct FieldMap {
  int w = 0, h = 0;
  double c = 1.0, s = 0.0, scale = 1.0, cx = 0.0, cy = 0.0;
  bool aligned = false;
  glm::dvec2 at(double x, double y) const {
    // The image offset (pixels, y up) turned back by the stage's turn from the frame: R(−Δ).
    const double fx = (x - 0.5 * (w - 1)) * scale, fy = (0.5 * (h - 1) - y) * scale;
    return {(aligned ? fx : c * fx + s * fy) + cx, cy - (aligned ? fy : -s * fx + c * fy)};
  }
  // The inverse: the image position (pixels, y down) of grid point (gx, gy), R(Δ).
  glm::dvec2 pixel_of(double gx, double gy) const {
    const double dx = gx - cx, dy = cy - gy;
    const double fx = aligned ? dx : c * dx - s * dy, fy = aligned ? dy : s * dx + c * dy;
    return {fx / scale + 0.5 * (w - 1), 0.5 * (h - 1) - fy / scale};
  }
  std::array<glm::dvec2, 4> corners(double over) const {
    return {at(0, 0) / over, at(w - 1, 0) / over, at(w - 1, h - 1) / over, at(0, h - 1) / over};
  }
};

FieldMap field_map(const SpecimenResponse& r, const InstrumentSettings& in) {
  FieldMap m;
  m.w = r.image_width;
  m.h = r.image_height;
  const double rel = in.stage_rad - r.frame_stage_rad;
  m.c = std::cos(rel);
  m.s = std::sin(rel);
  m.aligned = rel == 0.0 && r.nx == m.w && r.ny == m.h && r.grid_um == r.um_per_px;
  m.scale = r.um_per_px / r.grid_um;  // image pixels → grid points
  m.cx = 0.5 * (r.nx - 1);
  m.cy = 0.5 * (r.ny - 1);
  return m;
}

// What a frame reads from the response: per grid point and per chroma node, the X, Y, Z (or the
// grey) its block passes at the frame's settings, before resampling; only at the points the
// frame's samples read (read_spans), the rest of the buffers unspecified.
struct FrameFields {
  std::vector<float> grid;   // nx·ny × 1 (one channel) or × 4 (X, Y, Z, 0)
  std::vector<float> nodes;  // cnx·cny × 4: X, Y, Z, 0 (empty: no colour nodes)
  int channels = 1;
  glm::dvec3 grid_scale{1.0};  // one channel: XYZ = grid_scale × value
  FrameFields() = default;
  FrameFields(const FrameFields&) = delete;
  FrameFields& operator=(const FrameFields&) = delete;
  FrameFields(FrameFields&&) = default;
  ~FrameFields() {
    grid_slot().give(std::move(grid));
    node_slot().give(std::move(nodes));
  }
};


// The 12 weights u = v ⊗ t of a block for an analyzer-side v and an input t: vᵀ·B·t = u·B.
using Weights12 = std::array<float, 12>;
Weights12 weights(const Vec4& v, const Stokes& t) {
  Weights12 u{};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) u[std::size_t(3 * i + k)] = float(v[std::size_t(i)] * t[std::size_t(k)]);
  return u;
}
inline float dot12(const Weights12& u, const float* b) {
  float sum = 0.0f;
  for (std::size_t j = 0; j < 12; ++j) sum += u[j] * b[j];
  return sum;
}

// The frame's settings as weights of the stored blocks: vᵀ·B·t = u·B for each block B.
struct FrameWeights {
  bool accessory = false;
  int channels = 1;            // 1: X, Y, Z of the reference block are grid_scale × one sum
  glm::dvec3 grid_scale{1.0};
  std::array<Weights12, 3> ref{};  // the reference block's, per channel
  Weights12 plain{};               // the colour-weighted blocks' (no accessory)
  // With an accessory: per band, the analyzer through the accessory at the band (unweighted),
  // and the band's weights W_b (X, Y, Z, 0).
  std::vector<Weights12> band;
  std::vector<v4> band_xyz;
};

FrameWeights frame_weights(const SpecimenResponse& r, const InstrumentSettings& in) {
  // The blocks' vibrations are the specimen's own x and y (the tracer's frame): a lab angle ψ is
  // ψ − θ there.
  const double rel = in.stage_rad;
  const Stokes t = linear_stokes(in.polarizer_rad - rel);
  // Analyzer out: the whole intensity, I = (M t)_0 = ½·(2, 0, 0, 0)·M·t.
  const Stokes s = in.analyzer_in ? linear_stokes(in.analyzer_rad - rel) : Stokes{2.0, 0.0, 0.0, 0.0};
  const bool mono = r.single_wavelength_nm > 0.0;
  const int nb = r.bands.count();
  const CompensatorPlate plate = make_compensator(in.compensator, in.compensator_position);
  FrameWeights fw;
  fw.accessory = in.analyzer_in && plate.present;
  // Per channel, the analyzer's state through the accessory summed over the bands with their
  // weights: the reference block's analyzer side.
  std::array<Vec4, 3> v_ref{};
  if (mono) {
    Mueller4 c = retarder_mueller(0.25 * kPi - rel, 0.0);
    if (fw.accessory)
      c = retarder_mueller(0.25 * kPi - rel, 2.0 * kPi * compensator_retardation_nm(plate, r.single_wavelength_nm) /
                                                 r.single_wavelength_nm);
    v_ref[0] = through(c, s);
  } else {
    const RetarderTerms terms = retarder_terms(0.25 * kPi - rel);
    for (int b = 0; b < nb; ++b) {
      double cb = 1.0, sb = 0.0;
      if (fw.accessory) band_retardance(plate, r.bands.lo_nm[std::size_t(b)], r.bands.width_nm[std::size_t(b)], cb, sb);
      Mueller4 c{};
      for (std::size_t i = 0; i < 16; ++i) c[i] = terms.c0[i] + cb * terms.c1[i] + sb * terms.c2[i];
      const Vec4 v = through(c, s);
      const glm::dvec3& w = r.bands.weight[std::size_t(b)];
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 4; ++i) v_ref[std::size_t(k)][std::size_t(i)] += w[k] * v[std::size_t(i)];
      if (fw.accessory) {
        fw.band.push_back(weights(v, t));
        fw.band_xyz.push_back(v4{float(w.x), float(w.y), float(w.z), 0.0f});
      }
    }
  }
  // Without an accessory (or in monochromatic light) every band sees the same analyzer, so X, Y
  // and Z of the reference block are one contraction times the bands' white: one number a point.
  const bool one = mono || !fw.accessory;
  fw.channels = one ? 1 : 3;
  const Vec4 v_plain = {0.5 * s[0], 0.5 * s[1], 0.5 * s[2], 0.5 * s[3]};
  fw.plain = weights(v_plain, t);
  if (one) {
    fw.ref[0] = weights(mono ? v_ref[0] : v_plain, t);
    fw.grid_scale = mono ? r.white : r.bands.sum;
  } else {
    for (std::size_t k = 0; k < 3; ++k) fw.ref[k] = weights(v_ref[k], t);
  }
  return fw;
}

// The reference blocks contracted at the grid points `spans` lists: one number a point, or X, Y,
// Z, 0 (each the same sum as dot12's, side by side in the lanes of one vector).
void contract_grid(const SpecimenResponse& r, const FrameWeights& fw, const Spans& spans, std::vector<float>& grid) {
  std::array<v4, 12> u_lanes{};
  for (std::size_t j = 0; j < 12; ++j) u_lanes[j] = v4{fw.ref[0][j], fw.ref[1][j], fw.ref[2][j], 0.0f};
  tbb::parallel_for(tbb::blocked_range<int>(0, r.ny, 16), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j < rows.end(); ++j) {
      const std::size_t row = std::size_t(j) * std::size_t(r.nx);
      const std::size_t g0 = row + std::size_t(spans.lo[std::size_t(j)]);
      const std::size_t g1 = row + std::size_t(spans.hi[std::size_t(j)]) + 1;
      if (fw.channels == 1) {
        for (std::size_t g = g0; g < g1; ++g) grid[g] = dot12(fw.ref[0], &r.ref[g * 12]);
      } else {
        for (std::size_t g = g0; g < g1; ++g) {
          const float* b = &r.ref[g * 12];
          v4 sum = u_lanes[0] * b[0];
          for (std::size_t k = 1; k < 12; ++k) sum += u_lanes[k] * b[k];
          store4(&grid[g * 4], sum);
        }
      }
    }
  });
}

// The colour nodes `spans` lists contracted to X, Y, Z, 0. Without an accessory the
// colour-weighted blocks (3 sums of 12 a node); with one each band's difference block, the sum
// for its analyzer (12 products) times the band's W_b, four bands at a time.
void contract_nodes(const SpecimenResponse& r, const FrameWeights& fw, const Spans& spans, std::vector<float>& nodes) {
  const std::size_t nb = fw.band.size();
  std::vector<std::array<v4, 3>> u(nb);
  for (std::size_t b = 0; b < nb; ++b)
    for (std::size_t k = 0; k < 3; ++k) u[b][k] = load4(&fw.band[b][4 * k]);
  tbb::parallel_for(tbb::blocked_range<int>(0, r.cny, 2), [&](const tbb::blocked_range<int>& rows) {
    for (int J = rows.begin(); J < rows.end(); ++J) {
      const std::size_t row = std::size_t(J) * std::size_t(r.cnx);
      const std::size_t q0 = row + std::size_t(spans.lo[std::size_t(J)]);
      const std::size_t q1 = row + std::size_t(spans.hi[std::size_t(J)]) + 1;
      for (std::size_t q = q0; q < q1; ++q) {
        v4 sum{};
        if (!fw.accessory) {
          const float* d = &r.delta_xyz[q * 36];
          sum = v4{dot12(fw.plain, d), dot12(fw.plain, d + 12), dot12(fw.plain, d + 24), 0.0f};
        } else {
          const float* d = &r.delta[q * nb * 12];
          std::size_t b = 0;
          for (; b + 4 <= nb; b += 4) {
            v4 e[4];  // lane i: band b + p's products i, i + 4, i + 8, summed
            for (std::size_t p = 0; p < 4; ++p) {
              const float* db = d + (b + p) * 12;
              e[p] = u[b + p][0] * load4(db) + u[b + p][1] * load4(db + 4) + u[b + p][2] * load4(db + 8);
            }
            transpose(e);
            const v4 band_sums = (e[0] + e[1]) + (e[2] + e[3]);  // lane p: band b + p's sum
            for (std::size_t p = 0; p < 4; ++p) sum += fw.band_xyz[b + p] * band_sums[p];
          }
          for (; b < nb; ++b) {
            const float* db = d + b * 12;
            const v4 e = u[b][0] * load4(db) + u[b][1] * load4(db + 4) + u[b][2] * load4(db + 8);
            sum += fw.band_xyz[b] * ((e[0] + e[1]) + (e[2] + e[3]));
          }
        }
        store4(&nodes[q * 4], sum);
      }
    }
  });
}

// The guide of the colour reconstruction at the nodes `spans` lists, into their fourth lane: the
// luminance Y of the contracted reference at the node's own grid point (I·P, J·P), ≥ 0; −1 (no
// guide: range weight and scale 1, guided_chroma4) where that point is off the grid, not
// contracted, or images outside the image's pixel rectangle. The last rule makes a Field response
// (whose grid ends at the image) and a Disc response at its own stage angle give one image: the
// Field has no reference beyond its image to guide its outer nodes with.
void node_guides(const SpecimenResponse& r, const FieldMap& map, const FrameFields& f, const Spans& grid_spans,
                 const Spans& spans, std::vector<float>& nodes) {
  const int P = r.chroma_period;
  const float y_scale = float(f.grid_scale.y);
  constexpr double kTol = 1e-6;  // pixels: a node on the image's edge is inside it
  tbb::parallel_for(tbb::blocked_range<int>(0, r.cny, 4), [&](const tbb::blocked_range<int>& rows) {
    for (int J = rows.begin(); J < rows.end(); ++J) {
      const int gj = J * P;
      for (int I = spans.lo[std::size_t(J)]; I <= spans.hi[std::size_t(J)]; ++I) {
        const int gi = I * P;
        float guide = -1.0f;
        if (gi < r.nx && gj < r.ny && gi >= grid_spans.lo[std::size_t(gj)] && gi <= grid_spans.hi[std::size_t(gj)]) {
          const glm::dvec2 px = map.pixel_of(gi, gj);
          if (px.x >= -kTol && px.x <= map.w - 1 + kTol && px.y >= -kTol && px.y <= map.h - 1 + kTol) {
            const std::size_t g = std::size_t(gj) * std::size_t(r.nx) + std::size_t(gi);
            guide = std::max(0.0f, f.channels == 1 ? y_scale * f.grid[g] : f.grid[g * 4 + 1]);
          }
        }
        nodes[(std::size_t(J) * std::size_t(r.cnx) + std::size_t(I)) * 4 + 3] = guide;
      }
    }
  });
}

FrameFields contract_response(const SpecimenResponse& r, const InstrumentSettings& in, const FieldMap& map) {
  const FrameWeights fw = frame_weights(r, in);
  FrameFields f;
  f.channels = fw.channels;
  f.grid_scale = fw.grid_scale;
  f.grid = grid_slot().take(std::size_t(r.nx) * std::size_t(r.ny) * (fw.channels == 1 ? 1 : 4));
  const bool colour = !(r.single_wavelength_nm > 0.0 || r.delta.empty());
  // The cubic's 4 × 4 points, and with colour nodes their own grid points (the guide): a sample's
  // nodes lie within P − 1 points before and P after it.
  const int P = r.chroma_period;
  const Spans grid_spans =
      read_spans(map.corners(1.0), r.nx, r.ny, colour ? std::max(1, P - 1) : 1, colour ? std::max(2, P) : 2);
  contract_grid(r, fw, grid_spans, f.grid);
  if (!colour) return f;
  f.nodes = node_slot().take(std::size_t(r.cnx) * std::size_t(r.cny) * 4);
  const Spans spans = read_spans(map.corners(double(P)), r.cnx, r.cny, 0, 1);  // bilinear
  contract_nodes(r, fw, spans, f.nodes);
  node_guides(r, map, f, grid_spans, spans, f.nodes);
  return f;
}

// The colour nodes' X, Y, Z at four pixels, guided by the reference's full-resolution luminance
// (`guide`, Y: lane p pixel p's; a node's in its fourth lane, < 0: none, see node_guides):
// - Joint bilateral upsampling (Kopf, Cohen, Lischinski & Uyttendaele 2007, "Joint bilateral
//   upsampling", ACM TOG 26(3), eq. 2): each of a pixel's four nodes weighted by its bilinear
//   weight times a range weight, the similarity of the guide at the pixel and at the node, the
//   sum normalised by the weights' sum. The range kernel is a Cauchy (Lorentzian) one of the
//   guide's relative difference, 1 / (1 + (d/σ)²) with d = (g_p − g_n)/(g_p + g_n + ε): 1 where
//   the two are equal (a flat region, and a pixel on its node, keep the plain bilinear colour),
//   falling off across a grain boundary or a crack whatever the field's brightness.
// - Each node's colour difference scaled by (g_p + ε_r)/(g_n + ε_r): the colour follows the
//   luminance between the nodes, as chroma-from-luma prediction does (Trudeau, Egge & Barr 2018,
//   "Predicting chroma from luma in AV1", Data Compression Conference): a crack, a Becke line or
//   a lamella's edge dims every band alike, so the colour's ratio to the luminance varies more
//   slowly than the colour. The floor ε_r keeps a node dark at the reference wavelength but not in
//   other bands (first-order red, the gypsum plate's tint) from being scaled up without bound.
// A node without a guide has range weight and scale 1. Four pixels at once, in the lanes:
// out[k] is channel k (X, Y, Z) of the four.
[[gnu::always_inline]] inline void guided_chroma4(const float* v, int w, const Cell4& c, const v4& guide, v4 out[3]) {
  const v4 bil[4] = {(1 - c.fx) * (1 - c.fy), c.fx * (1 - c.fy), (1 - c.fx) * c.fy, c.fx * c.fy};
  const float eps = float(kChromaGuideEps), inv_s2 = float(1.0 / (kChromaGuideSigma * kChromaGuideSigma)),
              eps_r = float(kChromaRatioEps);
  const v4 zero{}, one = zero + 1.0f, tiny = zero + 1e-30f;
  v4 node[4][4];  // node[k][p]: pixel p's corner k (X, Y, Z, guide); transposed below
  for (int p = 0; p < 4; ++p) {
    const float* q = v + 4 * (std::size_t(c.y0[p]) * std::size_t(w) + std::size_t(c.x0[p]));
    const std::size_t dx = c.x0[p] + 1 < w ? 4 : 0, dy = 4 * std::size_t(w);
    node[0][p] = load4(q);
    node[1][p] = load4(q + dx);
    node[2][p] = load4(q + dy);
    node[3][p] = load4(q + dy + dx);
  }
  v4 total = zero;
  out[0] = out[1] = out[2] = zero;
  for (int k = 0; k < 4; ++k) {
    transpose(node[k]);  // node[k][ch]: channel ch of corner k (lanes: the four pixels)
    const v4 gn = node[k][3], sum = guide + gn + eps, d = guide - gn;
    const v4 wt = bil[k] * (gn < zero ? one : sum * sum / (sum * sum + inv_s2 * d * d));
    const v4 ws = wt * (gn < zero ? one : (guide + eps_r) / (gn + eps_r));
    total += wt;
    for (int ch = 0; ch < 3; ++ch) out[ch] += ws * node[k][ch];
  }
  // Every bilinear set has a weight ≥ ¼ and every range weight is > 0 (sum ≥ ε > 0): the guard
  // only keeps a degenerate cell from dividing by zero.
  const v4 inv = one / (total > tiny ? total : tiny);
  for (int ch = 0; ch < 3; ++ch) out[ch] *= inv;
}

// Rows [y0, y1) of the image, four pixels at a time: each pixel's grid value (cubic, or the point
// itself when the grid is the pixels) and colour nodes' (guided_chroma4), their XYZ and linear sRGB.
template <int Stride>
void compose_rows(const SpecimenResponse& r, const FieldMap& map, const FrameFields& f, int y0, int y1,
                  RenderImage& img) {
  const bool mono = r.single_wavelength_nm > 0.0;
  const double per_node = 1.0 / r.chroma_period;  // exact for the period 4 (and 2, 1)
  // XYZ → linear sRGB as its matrix's columns (in float: the image's own precision).
  const glm::dvec3 m0 = xyz_to_linear_srgb({1.0, 0.0, 0.0}), m1 = xyz_to_linear_srgb({0.0, 1.0, 0.0}),
                   m2 = xyz_to_linear_srgb({0.0, 0.0, 1.0});
  const float* grid = f.grid.data();
  const float* nodes = f.nodes.empty() ? nullptr : f.nodes.data();
  const int w = map.w;
  const float scale[3] = {float(f.grid_scale.x), float(f.grid_scale.y), float(f.grid_scale.z)};
  const float inv_white_y = float(1.0 / r.white.y);
  float mf[3][3];
  for (int k = 0; k < 3; ++k) {
    mf[0][k] = float(m0[k]);
    mf[1][k] = float(m1[k]);
    mf[2][k] = float(m2[k]);
  }
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < w; x += 4) {
      const int np = std::min(4, w - x);  // the last lanes of a row's end repeat its last pixel
      double gx[4], gy[4], nx[4], ny[4];
      for (int p = 0; p < 4; ++p) {
        const glm::dvec2 at = map.at(std::min(x + p, w - 1), y);
        gx[p] = at.x;
        gy[p] = at.y;
        nx[p] = at.x * per_node;
        ny[p] = at.y * per_node;
      }
      const std::size_t pix = std::size_t(y) * std::size_t(w) + std::size_t(x);
      v4 g[4];  // lanes: pixels; g[k] channel k (Stride 4), g[0] the one channel
      if (map.aligned) {
        for (int p = 0; p < 4; ++p)
          g[p] = Stride == 1 ? v4{grid[pix + std::size_t(std::min(p, np - 1))], 0.0f, 0.0f, 0.0f}
                             : load4(grid + 4 * (pix + std::size_t(std::min(p, np - 1))));
        transpose(g);
      } else if constexpr (Stride == 1) {
        g[0] = cubic1(grid, r.nx, r.ny, cells(gx, gy, r.nx, r.ny, r.nx - 1, r.ny - 1));
      } else {
        cubic4(grid, r.nx, r.ny, cells(gx, gy, r.nx, r.ny, r.nx - 1, r.ny - 1), g);
        transpose(g);
      }
      v4 n[4] = {};
      if (nodes) {
        const v4 zero4{}, lum = Stride == 1 ? scale[1] * g[0] : g[1];
        const v4 guide = zero4 < lum ? lum : zero4;  // as the nodes' guides: ≥ 0
        guided_chroma4(nodes, r.cnx, cells(nx, ny, r.cnx, r.cny, std::max(r.cnx - 2, 0), std::max(r.cny - 2, 0)),
                       guide, n);  // n[k]: channel k (lanes: the four pixels)
      }
      v4 xyz[3], rgb[3];  // lanes: the four pixels
      const v4 zero4{};
      for (int k = 0; k < 3; ++k) {
        const v4 sum = (Stride == 1 ? scale[k] * g[0] : g[k]) + n[k];
        xyz[k] = zero4 < sum ? sum : zero4;  // std::max(0, sum)
      }
      for (int k = 0; k < 3; ++k)
        rgb[k] = mono ? xyz[1] * inv_white_y : mf[0][k] * xyz[0] + mf[1][k] * xyz[1] + mf[2][k] * xyz[2];
      for (int p = 0; p < np; ++p) {
        const std::size_t at = (pix + std::size_t(p)) * 3;
        for (int k = 0; k < 3; ++k) {
          img.xyz[at + std::size_t(k)] = xyz[k][p];
          img.rgb[at + std::size_t(k)] = rgb[k][p];
        }
      }
    }
}

RenderImage compose_isolated(const SpecimenResponse& r, const InstrumentSettings& in) {
  RenderImage img;
  const int w = r.image_width, h = r.image_height;
  img.width = w;
  img.height = h;
  img.rgb.assign(std::size_t(w) * h * 3, 0.0f);
  img.xyz.assign(std::size_t(w) * h * 3, 0.0f);
  img.passes = r.passes;
  img.samples_per_pixel = r.samples_per_pixel;
  img.wavelengths = r.bands.count();
  img.time_ms = r.time_ms;
  img.model_report = r.model_report;
  if (r.nx <= 0 || r.ny <= 0 || r.ref.empty()) return img;
  const FieldMap map = field_map(r, in);
  const FrameFields f = contract_response(r, in, map);
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 8), [&](const tbb::blocked_range<int>& rows) {
    if (f.channels == 1)
      compose_rows<1>(r, map, f, rows.begin(), rows.end(), img);
    else
      compose_rows<4>(r, map, f, rows.begin(), rows.end(), img);
  });
  return img;
}

}  // namespace

InstrumentSettings instrument_settings(const Scene& scene) {
  InstrumentSettings in;
  in.stage_rad = radians(scene.stage_deg);
  in.polarizer_rad = radians(scene.polarizer_deg);
  in.analyzer_in = scene.analyzer_in;
  in.analyzer_rad = radians(scene.analyzer_deg);
  in.compensator = scene.compensator;
  in.compensator_position = scene.compensator_position;
  return in;
}

RenderImage compose_response(const SpecimenResponse& r, const InstrumentSettings& in) {
  // Isolated: a UI thread composing while the tracer's passes run in the same arena must not pick
  // up a tracer task (tens of ms) while it waits for its own.
  RenderImage img;
  tbb::this_task_arena::isolate([&] { img = compose_isolated(r, in); });
  return img;
}

double response_difference_de2000(const SpecimenResponse& a, const SpecimenResponse& b,
                                  const InstrumentSettings& instrument) {
  const RenderImage ia = compose_response(a, instrument), ib = compose_response(b, instrument);
  const std::size_t n = std::size_t(ia.width) * std::size_t(ia.height);
  return split_half_de2000(
      n,
      [&](std::size_t i, int half) {
        const std::vector<float>& v = half == 0 ? ia.xyz : ib.xyz;
        return glm::dvec3(v[i * 3], v[i * 3 + 1], v[i * 3 + 2]);
      },
      a.white);
}

}  // namespace pmsim
