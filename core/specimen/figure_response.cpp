#include "core/specimen/figure_response.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/base/conventions.h"
#include "core/microscope/view_geometry.h"
#include "core/render/progressive_renderer.h"
#include "core/spectrum/color.h"

namespace pmsim {

bool figure_response_applies(const Scene& scene) {
  return scene.bertrand_in && scene.mode == ViewMode::Cono && scene.compensator == Compensator::None;
}

namespace {

constexpr int kProbeFloats = 27;  // 9 probes × XYZ

// Weights c of p(ψ) = Σ_j c_j p(kFigureProbeDeg[j]), p(ψ) = (1, cos 2ψ, sin 2ψ) (the header).
std::array<double, 3> probe_weights(double angle_rad) {
  const double c = std::cos(2.0 * angle_rad), s = std::sin(2.0 * angle_rad);
  return {0.5 * (1.0 - s + c), s, 0.5 * (1.0 - s - c)};
}

// The disc the figure lights: bfp_lit at each pixel centre, as the conoscopic pixel view's.
std::vector<unsigned char> figure_disc(const Scene& scene) {
  const int W = scene.render.width, H = scene.render.height;
  std::vector<unsigned char> lit(static_cast<std::size_t>(W) * H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const glm::dvec2 f = field_from_pixel(W, H, x + 0.5, y + 0.5);
      lit[static_cast<std::size_t>(y) * W + x] = bfp_lit(scene, std::hypot(f.x, f.y)) ? 1 : 0;
    }
  return lit;
}

// Unlit pixels within the cubic's reach (3 pixels) of the disc take the probes of the lit pixel
// nearest inward along their radius: a continuation of the figure, so that taps across the rim
// read the figure's own values and not the black around it.
void fill_rim(FigureResponse& r, double lit_radius) {
  const int W = r.width, H = r.height;
  const double half = 0.5 * std::min(W, H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * W + x;
      if (r.lit[i]) continue;
      const glm::dvec2 f = field_from_pixel(W, H, x + 0.5, y + 0.5);
      const double rho = std::hypot(f.x, f.y);
      if (rho <= 0.0 || (rho - lit_radius) * half > 3.0) continue;
      for (double back = 0.5; back < 6.0; back += 0.5) {
        const double t = std::max(0.0, lit_radius - back / half) / rho;
        const int sx = static_cast<int>(std::floor(f.x * t * half + 0.5 * W));
        const int sy = static_cast<int>(std::floor(0.5 * H - f.y * t * half));
        if (sx < 0 || sy < 0 || sx >= W || sy >= H) continue;
        const std::size_t j = static_cast<std::size_t>(sy) * W + sx;
        if (!r.lit[j]) continue;
        std::copy_n(&r.probes[j * kProbeFloats], kProbeFloats, &r.probes[i * kProbeFloats]);
        break;
      }
    }
}

// Keys' cubic convolution kernel, a = −0.5 (Keys 1981, IEEE TASSP 29(6), eq. 15).
double keys(double t) {
  t = std::abs(t);
  if (t <= 1.0) return (1.5 * t - 2.5) * t * t + 1.0;
  if (t < 2.0) return ((-0.5 * t + 2.5) * t - 4.0) * t + 2.0;
  return 0.0;
}

}  // namespace

std::optional<FigureResponse> render_figure_response(const Scene& scene, int threads,
                                                     const std::function<void(const RenderImage&)>& progress,
                                                     const std::atomic<bool>* cancel) {
  const auto t0 = std::chrono::steady_clock::now();
  // The figure at the scene's own settings, as a fresh render: the level it converges at is the
  // level every probe is rendered at.
  const RenderImage own =
      ProgressiveRenderer::render(scene, threads, progress ? progress : [](const RenderImage&) {});
  if (cancel && cancel->load()) return std::nullopt;
  std::optional<FigureResponse> r = render_figure_probes(scene, own, threads, cancel);
  if (r) r->time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::optional<FigureResponse> render_figure_probes(const Scene& scene, const RenderImage& own, int threads,
                                                   const std::atomic<bool>* cancel) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto cancelled = [&] { return cancel && cancel->load(); };
  FigureResponse r;
  r.width = scene.render.width;
  r.height = scene.render.height;
  r.monochromatic = scene.render.single_wavelength_nm > 0;
  r.wavelengths = own.wavelengths;
  r.progress = own;
  r.progress.rgb.clear();
  r.progress.xyz.clear();
  const std::size_t n = static_cast<std::size_t>(r.width) * r.height;
  r.probes.assign(n * kProbeFloats, 0.0f);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Scene s = scene;
      s.stage_deg = 0.0;
      s.analyzer_in = true;
      s.analyzer_deg = kFigureProbeDeg[i];
      s.polarizer_deg = kFigureProbeDeg[j];
      if (!r.monochromatic) s.render.wavelengths = own.wavelengths;
      const RenderImage probe = ProgressiveRenderer::render(s, threads);
      if (cancelled()) return std::nullopt;
      const int k = 3 * i + j;
      for (std::size_t p = 0; p < n; ++p)
        for (int c = 0; c < 3; ++c) r.probes[p * kProbeFloats + 3 * k + c] = probe.xyz[3 * p + c];
    }
  r.lit = figure_disc(scene);
  bool light_outside = false;
  for (std::size_t p = 0; p < n && !light_outside; ++p)
    if (!r.lit[p])
      for (int k = 0; k < kProbeFloats; ++k) light_outside = light_outside || r.probes[p * kProbeFloats + k] != 0.0f;
  if (light_outside) r.outside = r.probes;
  fill_rim(r, std::min(1.0, scene.condenser.na / scene.objective.na));
  r.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

RenderImage compose_figure(const FigureResponse& r, const InstrumentSettings& in) {
  const int W = r.width, H = r.height;
  const double theta = in.stage_rad;
  const std::array<double, 3> c = probe_weights(in.polarizer_rad - theta);
  // The analyzer out passes a(0°) + a(90°) = (2, 0, 0): the whole intensity (the header).
  const std::array<double, 3> d = in.analyzer_in ? probe_weights(in.analyzer_rad - theta) : std::array<double, 3>{1, 0, 1};
  std::array<float, 9> w{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w[3 * i + j] = static_cast<float>(d[i] * c[j]);
  const auto contract = [&](const std::vector<float>& probes, std::size_t p) {
    const float* q = &probes[p * kProbeFloats];
    glm::dvec3 v(0.0);
    for (int k = 0; k < 9; ++k) v += static_cast<double>(w[k]) * glm::dvec3(q[3 * k], q[3 * k + 1], q[3 * k + 2]);
    return v;
  };
  const std::size_t n = static_cast<std::size_t>(W) * H;
  // The figure at these polars, stage 0°, at every grid point; then read turned by the stage.
  std::vector<glm::dvec3> grid(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& b) {
    for (std::size_t p = b.begin(); p != b.end(); ++p) grid[p] = contract(r.probes, p);
  });
  RenderImage img = r.progress;
  img.width = W;
  img.height = H;
  img.rgb.assign(n * 3, 0.0f);
  img.xyz.assign(n * 3, 0.0f);
  const StageToSample turn(degrees(theta));
  const double half = 0.5 * std::min(W, H);
  tbb::parallel_for(tbb::blocked_range<int>(0, H, 8), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y)
      for (int x = 0; x < W; ++x) {
        const std::size_t o = static_cast<std::size_t>(y) * W + x;
        const glm::dvec2 g = turn(field_from_pixel(W, H, x + 0.5, y + 0.5));
        const double gx = g.x * half + 0.5 * W - 0.5, gy = 0.5 * H - g.y * half - 0.5;  // grid coordinates
        glm::dvec3 v(0.0);
        if (r.lit[o]) {
          const int x0 = static_cast<int>(std::floor(gx)), y0 = static_cast<int>(std::floor(gy));
          double wx[4], wy[4];
          for (int t = 0; t < 4; ++t) {
            wx[t] = keys(gx - (x0 - 1 + t));
            wy[t] = keys(gy - (y0 - 1 + t));
          }
          for (int ty = 0; ty < 4; ++ty) {
            const int yy = std::clamp(y0 - 1 + ty, 0, H - 1);
            glm::dvec3 row(0.0);
            for (int tx = 0; tx < 4; ++tx) row += wx[tx] * grid[static_cast<std::size_t>(yy) * W + std::clamp(x0 - 1 + tx, 0, W - 1)];
            v += wy[ty] * row;
          }
          v = glm::max(v, glm::dvec3(0.0));  // the cubic's overshoot at an isogyre's edge: no negative light
        } else if (!r.outside.empty()) {
          const int sx = static_cast<int>(std::lround(gx)), sy = static_cast<int>(std::lround(gy));
          if (sx >= 0 && sy >= 0 && sx < W && sy < H) v = contract(r.outside, static_cast<std::size_t>(sy) * W + sx);
        }
        const glm::dvec3 rgb = r.monochromatic ? glm::dvec3(v.y) : xyz_to_linear_srgb(v);
        for (int k = 0; k < 3; ++k) {
          img.xyz[3 * o + k] = std::isfinite(v[k]) ? static_cast<float>(v[k]) : 0.0f;
          img.rgb[3 * o + k] = std::isfinite(rgb[k]) ? static_cast<float>(rgb[k]) : 0.0f;
        }
      }
  });
  return img;
}

}  // namespace pmsim
