#include "core/specimen/figure_response.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <glm/mat3x3.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/base/conventions.h"
#include "core/microscope/compensator.h"
#include "core/microscope/evaluation_plan.h"
#include "core/microscope/scene_limits.h"
#include "core/microscope/view_geometry.h"
#include "core/render/cubic_sample.h"
#include "core/render/image_develop.h"
#include "core/render/progressive_renderer.h"
#include "core/render/spectral_level.h"
#include "core/spectrum/cie.h"
#include "core/spectrum/color.h"

namespace pmsim {

bool figure_response_applies(const Scene& scene) {
  if (!scene.bertrand_in || scene.mode != ViewMode::Cono) return false;
  // Ghost light is reckoned per train in the plan: an accessory frame could not evaluate it.
  return scene.compensator == Compensator::None || scene.optics.lens_depth < 2;
}

namespace {

// The side of a flat view's canvas in view pixels: the view's circumscribed circle plus two
// pixels each side (a turned corner pixel's sub-samples stay on it), of the parity of the view's
// width (at stage 0° each view pixel is then k × k canvas pixels, read exactly).
int flat_canvas_side(int width, int height) {
  int side = static_cast<int>(std::ceil(std::hypot(width, height))) + 4;
  if ((side - width) % 2 != 0) ++side;
  return side;
}

// The flat view's canvas scene: the same specimen and centre over the larger square, k canvas
// pixels to a view pixel (the field number scaled: mm_per_pixel = field of view / the shorter side).
Scene flat_canvas_scene(const Scene& scene) {
  const int side = flat_canvas_side(scene.render.width, scene.render.height);
  const int k = flat_canvas_scale(scene.render.width, scene.render.height);
  Scene s = scene;
  s.eyepiece.field_number_mm *= static_cast<double>(side) / std::min(scene.render.width, scene.render.height);
  s.render.width = s.render.height = side * k;
  return s;
}

}  // namespace

int flat_canvas_scale(int width, int height) {
  const int side = flat_canvas_side(width, height);
  return std::clamp((kFlatCanvasMinSide + side - 1) / side, 1, kMaxFlatCanvasScale);
}

bool flat_response_applies(const Scene& scene) {
  if (scene.mode != ViewMode::Ortho || scene.bertrand_in) return false;
  // Sections only: a plate or the empty stage is one evaluation for the whole field (a render of
  // a few ms, no cheaper composed), and a wedge's thickness runs across the rendered field.
  if (!scene.sample_in || scene.sample.type != SampleType::Section) return false;
  const int side = flat_canvas_side(scene.render.width, scene.render.height);
  const long long canvas = static_cast<long long>(side) * flat_canvas_scale(scene.render.width, scene.render.height);
  const double fn = scene.eyepiece.field_number_mm * side / std::min(scene.render.width, scene.render.height);
  return canvas * canvas <= kMaxFlatCanvasPixels && fn <= kMaxFieldNumberMm;
}

namespace {

constexpr int kProbeFloats = 27;  // 9 probes × XYZ: planes of FigureResponse::probes

// Weights d of (1, x, y) = Σ_i d_i p(kFigureProbeDeg[i]), p(ψ) = (1, cos 2ψ, sin 2ψ) (the header).
std::array<double, 3> analyzer_weights(double x, double y) { return {0.5 * (1.0 - y + x), y, 0.5 * (1.0 - y - x)}; }

// Weights c of p(ψ) = Σ_j c_j p(kFigureProbeDeg[j]).
std::array<double, 3> probe_weights(double angle_rad) {
  return analyzer_weights(std::cos(2.0 * angle_rad), std::sin(2.0 * angle_rad));
}

// The analyzer at α seen through an accessory whose eigen-axis is at β, both in the specimen's
// frame: u the analyzer side of the accessory's C0, (v1, v2) of C1 (against cos δ) and w3 of C2
// (against sin δ) (the header).
struct AccessoryWeights {
  double u1, u2, v1, v2, w3;
};
AccessoryWeights accessory_weights(double alpha_rad, double beta_rad) {
  const double a1 = std::cos(2.0 * alpha_rad), a2 = std::sin(2.0 * alpha_rad);
  const double c = std::cos(2.0 * beta_rad), s = std::sin(2.0 * beta_rad);
  return {a1 * c * c + a2 * c * s, a1 * c * s + a2 * s * s, a1 * s * s - a2 * c * s, a2 * c * c - a1 * c * s,
          a2 * c - a1 * s};
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

// Unlit pixels within the cubic's reach (3 pixels) of the disc take the value of the lit pixel
// nearest inward along their radius: a continuation of the figure, so that taps across the rim
// read the figure's own values and not the black around it. The pairs (unlit, lit).
std::vector<std::pair<std::size_t, std::size_t>> rim_sources(const FigureResponse& r, double lit_radius) {
  const int W = r.width, H = r.height;
  const double half = 0.5 * std::min(W, H);
  std::vector<std::pair<std::size_t, std::size_t>> rim;
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
        rim.emplace_back(i, j);
        break;
      }
    }
  return rim;
}

void fill_rim(FigureResponse& r) {
  const std::size_t n = static_cast<std::size_t>(r.width) * r.height;
  for (const auto& [i, j] : r.rim)
    for (int k = 0; k < kProbeFloats; ++k) r.probes[k * n + i] = r.probes[k * n + j];
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

namespace {

// Probe k = 3·i + j: stage 0°, the analyzer at kFigureProbeDeg[i], the polarizer at kFigureProbeDeg[j],
// at the figure's converged spectral level, no accessory (a flat view's frames with one evaluate
// the canvas's plan instead).
Scene probe_scene(const Scene& scene, int k, int wavelengths) {
  Scene s = scene;
  s.stage_deg = 0.0;
  s.compensator = Compensator::None;
  s.analyzer_in = true;
  s.analyzer_deg = kFigureProbeDeg[k / 3];
  s.polarizer_deg = kFigureProbeDeg[k % 3];
  if (s.render.single_wavelength_nm <= 0) s.render.wavelengths = wavelengths;
  return s;
}

void store_probe(FigureResponse& r, int k, const std::vector<float>& xyz) {
  const std::size_t n = static_cast<std::size_t>(r.width) * r.height;
  for (std::size_t p = 0; p < n; ++p)
    for (int c = 0; c < 3; ++c) r.probes[(3 * k + c) * n + p] = xyz[3 * p + c];
}

// The nine probes from one plan: its fits kept, reduced in the nine probes' trains, and one band
// loop a direction for all nine (evaluate_unit_in_trains); exact units band by band in each
// probe's train. Each probe is developed as its own render's image is. False where that does not
// hold — the exact plate model, one spectral line, ghost light (reckoned per train), more than
// 256 bands — or when cancelled.
bool shared_probes(const Scene& scene, FigureResponse& r, const std::atomic<bool>* cancel) {
  std::vector<TrainState> trains;
  const Scene base = probe_scene(scene, 0, r.wavelengths);
  for (int k = 0; k < 9; ++k)
    trains.push_back(make_train(probe_scene(scene, k, r.wavelengths),
                                make_compensator(base.compensator, base.compensator_position), 550.0));
  const std::shared_ptr<const EvaluationPlan> plan = compile_evaluation_plan(base, cancel, true);
  if (!plan || plan->plate_model() != PlateModel::Modal || plan->modal_fits().size() != plan->modal_terms().size() ||
      !plan->ghost_xyz().empty())
    return false;
  const SpectralLevel level = make_spectral_level(*plan, r.wavelengths);
  const int units = static_cast<int>(plan->units().size());
  for (int u = 0; u < units; ++u)
    if (!plan->needs_exact(u) && !shares_band_loop(*plan, level, u)) return false;
  // Exact units (absorbing, or optically active near the axis) go band by band in each probe's
  // train, as each probe's render would take them.
  std::vector<SpectralLevel> exact_levels;
  if (plan->any_exact())
    for (int k = 0; k < 9; ++k)
      exact_levels.push_back(level_in_train(level, probe_scene(scene, k, r.wavelengths), plan->compensator()));
  std::vector<std::vector<glm::dvec3>> xyz(9, std::vector<glm::dvec3>(units));
  tbb::parallel_for(tbb::blocked_range<int>(0, units, 256), [&](const tbb::blocked_range<int>& b) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    glm::dvec3 v[9];
    for (int u = b.begin(); u != b.end(); ++u) {
      if (plan->needs_exact(u)) {
        for (int k = 0; k < 9; ++k) xyz[k][u] = evaluate_unit(*plan, exact_levels[k], u);
        continue;
      }
      evaluate_unit_in_trains(*plan, level, u, trains, v);
      for (int k = 0; k < 9; ++k) xyz[k][u] = v[k];
    }
  });
  RenderImage img;
  for (int k = 0; k < 9; ++k) {
    if (cancel && cancel->load()) return false;
    develop_image(*plan, xyz[k], false, img, cancel);
    store_probe(r, k, img.xyz);
  }
  r.plan = plan;
  r.level = std::make_shared<const SpectralLevel>(level);
  return !(cancel && cancel->load());
}

// A figure's plan for its accessory frames where the probes did not come from one (one spectral
// line, the exact plate model, more than 256 bands): compiled at the first probe's scene, fits
// kept. None with ghost light (figure_response_applies). False when cancelled.
bool keep_figure_plan(const Scene& grid, FigureResponse& r, const std::atomic<bool>* cancel) {
  if (r.plan || grid.optics.lens_depth >= 2) return true;
  r.plan = compile_evaluation_plan(probe_scene(grid, 0, r.wavelengths), cancel, true);
  if (!r.plan) return false;
  r.level = std::make_shared<const SpectralLevel>(make_spectral_level(*r.plan, r.wavelengths));
  return !(cancel && cancel->load());
}

// A flat view's probes, per unit: the canvas's plan compiled once with its fits kept, and every
// unit evaluated in the nine probes' trains (evaluate_unit_in_train: exact units band by band, one
// spectral line as the renderer takes it). A section has few units — one per grain or lamella,
// boundary pixels' sub-samples as weights on them — so 27 floats a unit replace 27 a canvas pixel,
// and a frame develops the canvas from them (develop_grid). False when cancelled.
bool flat_unit_probes(const Scene& grid, FigureResponse& r, const std::atomic<bool>* cancel) {
  r.plan = compile_evaluation_plan(probe_scene(grid, 0, r.wavelengths), cancel, true);
  if (!r.plan) return false;
  const SpectralLevel level = make_spectral_level(*r.plan, r.wavelengths);
  const CompensatorPlate none = make_compensator(Compensator::None, 0.0);
  std::vector<SpectralLevel> levels;
  std::vector<TrainState> trains;
  for (int k = 0; k < 9; ++k) {
    const Scene s = probe_scene(grid, k, r.wavelengths);
    levels.push_back(level_in_train(level, s, none));
    trains.push_back(make_train(s, none, 550.0));
  }
  const int units = static_cast<int>(r.plan->units().size());
  r.unit_probes.assign(static_cast<std::size_t>(units) * kProbeFloats, 0.0f);
  tbb::parallel_for(tbb::blocked_range<int>(0, units, 16), [&](const tbb::blocked_range<int>& b) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    for (int u = b.begin(); u != b.end(); ++u)
      for (int k = 0; k < 9; ++k) {
        const glm::dvec3 v = evaluate_unit_in_train(*r.plan, levels[k], trains[k], u);
        for (int c = 0; c < 3; ++c) r.unit_probes[static_cast<std::size_t>(u) * kProbeFloats + 3 * k + c] = static_cast<float>(v[c]);
      }
  });
  r.level = std::make_shared<const SpectralLevel>(level);
  return !(cancel && cancel->load());
}

// The canvas as the units its pixels' sub-samples show (FigureResponse::canvas_label). A canvas
// pixel the plan gives one unit at full weight shows it at every sub-sample (field_view sampled it
// at its centre or found all its sub-samples alike), one without units shows nothing; the rest
// straddle a boundary or an opaque point, and their sub-samples are looked up again where
// field_view took them. A section's field view numbers its units as its domains.
void flat_canvas_labels(FigureResponse& r, const std::atomic<bool>* cancel) {
  const EvaluationPlan& plan = *r.plan;
  if (!plan.section()) throw std::logic_error("flat_canvas_labels: a flat view without a section");
  const int n = std::max(1, static_cast<int>(std::lround(std::sqrt(plan.spatial_samples()))));
  const int GW = r.width, GH = r.height, ls = n * kFlatLabelsPerSample, nn = ls * ls;
  r.samples_per_side = n;
  const std::vector<int>& offset = plan.pixel_offset();
  const std::vector<PixelRef>& refs = plan.refs();
  const float full = 1.0f - 0.5f / static_cast<float>(nn);
  std::vector<std::size_t> mixed;
  r.canvas_label.assign(static_cast<std::size_t>(GW) * GH, -1);
  for (std::size_t i = 0; i < r.canvas_label.size(); ++i) {
    const int count = offset[i + 1] - offset[i];
    if (count == 0) continue;
    if (count == 1 && refs[offset[i]].weight > full) {
      r.canvas_label[i] = refs[offset[i]].unit;
    } else {
      r.canvas_label[i] = -2 - static_cast<int>(mixed.size());
      mixed.push_back(i);
    }
  }
  r.mixed_labels.assign(mixed.size() * nn, -1);
  const FieldToSection to_section(plan.scene());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mixed.size(), 256), [&](const tbb::blocked_range<std::size_t>& b) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    for (std::size_t m = b.begin(); m != b.end(); ++m) {
      const double x = static_cast<double>(mixed[m] % GW), y = static_cast<double>(mixed[m] / GW);
      for (int sy = 0; sy < ls; ++sy)
        for (int sx = 0; sx < ls; ++sx) {
          const int d = plan.section()->domain_at(to_section(field_from_pixel(GW, GH, x + (sx + 0.5) / ls, y + (sy + 0.5) / ls)));
          r.mixed_labels[m * nn + sy * ls + sx] = plan.domains()[d].opaque ? -1 : d;
        }
    }
  });
  r.canvas_uniform.assign(r.canvas_label.size(), -1);
  for (int y = 1; y + 1 < GH; ++y)
    for (int x = 1; x + 1 < GW; ++x) {
      const int unit = r.canvas_label[static_cast<std::size_t>(y) * GW + x];
      bool alike = unit >= 0;
      for (int dy = -1; dy <= 1 && alike; ++dy)
        for (int dx = -1; dx <= 1 && alike; ++dx) alike = r.canvas_label[static_cast<std::size_t>(y + dy) * GW + x + dx] == unit;
      if (alike) r.canvas_uniform[static_cast<std::size_t>(y) * GW + x] = unit;
    }
}

}  // namespace

std::optional<FigureResponse> render_figure_probes(const Scene& scene, const RenderImage& own, int threads,
                                                   const std::atomic<bool>* cancel) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto cancelled = [&] { return cancel && cancel->load(); };
  FigureResponse r;
  r.flat = !figure_response_applies(scene);
  if (r.flat && !flat_response_applies(scene))
    throw std::invalid_argument("render_figure_probes: neither a figure nor a flat view the probes serve");
  r.image_width = scene.render.width;
  r.image_height = scene.render.height;
  r.scale = r.flat ? flat_canvas_scale(scene.render.width, scene.render.height) : 1;
  const Scene grid = r.flat ? flat_canvas_scene(scene) : scene;
  r.width = grid.render.width;
  r.height = grid.render.height;
  r.monochromatic = scene.render.single_wavelength_nm > 0;
  r.wavelengths = own.wavelengths;
  r.progress = own;
  r.progress.rgb.clear();
  r.progress.xyz.clear();
  tbb::task_arena arena(threads > 0 ? threads : static_cast<int>(tbb::task_arena::automatic));
  if (r.flat) {  // the canvas covers the view at every angle: nothing unlit, no rim to fill
    bool ok = false;
    arena.execute([&] {
      ok = flat_unit_probes(grid, r, cancel);
      if (ok) flat_canvas_labels(r, cancel);
    });
    if (!ok || cancelled()) return std::nullopt;
    r.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return r;
  }
  const std::size_t n = static_cast<std::size_t>(r.width) * r.height;
  r.probes.assign(n * kProbeFloats, 0.0f);
  bool shared = false;
  if (!r.monochromatic) arena.execute([&] { shared = shared_probes(grid, r, cancel); });
  if (cancelled()) return std::nullopt;
  for (int k = 0; k < 9 && !shared; ++k) {
    store_probe(r, k, ProgressiveRenderer::render(probe_scene(grid, k, r.wavelengths), threads).xyz);
    if (cancelled()) return std::nullopt;
  }
  bool kept = false;
  arena.execute([&] { kept = keep_figure_plan(grid, r, cancel); });
  if (!kept || cancelled()) return std::nullopt;
  r.lit = figure_disc(scene);
  bool light_outside = false;
  for (std::size_t p = 0; p < n && !light_outside; ++p)
    if (!r.lit[p])
      for (int k = 0; k < kProbeFloats; ++k) light_outside = light_outside || r.probes[k * n + p] != 0.0f;
  if (light_outside) r.outside = r.probes;
  r.rim = rim_sources(r, std::min(1.0, scene.condenser.na / scene.objective.na));
  fill_rim(r);
  r.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

namespace {

// The probes contracted with the frame's nine weights: the view at these polars, stage 0°, as
// X, Y, Z, 0 at every grid point (the layout cubic::cubic4 reads). Per block, each channel is nine
// multiply-adds over contiguous planes (they vectorise), then interleaved.
std::vector<float> contract_grid(const FigureResponse& r, const std::array<float, 9>& w,
                                 const std::vector<float>* extra = nullptr, const std::array<float, 9>& we = {}) {
  const std::size_t n = static_cast<std::size_t>(r.width) * r.height;
  constexpr int kBlock = 2048;
  std::vector<float> grid(4 * n);
  tbb::parallel_for(tbb::blocked_range<int>(0, r.height, 4), [&](const tbb::blocked_range<int>& rows) {
    float sum[3][kBlock];
    for (int y = rows.begin(); y != rows.end(); ++y)
      for (int x = 0; x < r.width; x += kBlock) {
        const std::size_t begin = static_cast<std::size_t>(y) * r.width + x;
        const int m = std::min(kBlock, r.width - x);
        for (int c = 0; c < 3; ++c) {
          std::fill_n(sum[c], m, 0.0f);
          for (int k = 0; k < 9; ++k) {
            const float* plane = &r.probes[(3 * k + c) * n + begin];
            const float wk = w[k];
            for (int p = 0; p < m; ++p) sum[c][p] += wk * plane[p];
          }
          for (int k = 0; extra && k < 9; ++k) {  // an accessory's planes (FigureResponse::Accessory)
            const float* plane = &(*extra)[(3 * k + c) * n + begin];
            const float wk = we[k];
            for (int p = 0; p < m; ++p) sum[c][p] += wk * plane[p];
          }
        }
        for (int p = 0; p < m; ++p) {
          float* g = &grid[4 * (begin + p)];
          g[0] = sum[0][p];
          g[1] = sum[1][p];
          g[2] = sum[2][p];
          g[3] = 0.0f;
        }
      }
  });
  return grid;
}

// The plan's units in the train of `lab` (the plan's scene with other polars and accessory) turned
// into the specimen's frame by θ, from the accessory's sums, developed as the renderer's units are.
std::vector<glm::vec3> units_in_train(const FigureResponse& r, const Scene& lab, const CompensatorSums& sums,
                                      double theta) {
  const EvaluationPlan& plan = *r.plan;
  const int units = static_cast<int>(plan.units().size());
  const CompensatorPlate comp = make_compensator(lab.compensator, lab.compensator_position);
  SpectralLevel level = level_in_train(*r.level, lab, comp);
  for (TrainState& t : level.train) t = train_in_specimen_frame(t, theta);
  const TrainState train = train_in_specimen_frame(make_train(lab, comp, 550.0), theta);
  const glm::dvec3 white = illuminant_white_xyz(plan.scene().illuminant);
  std::vector<glm::vec3> unit_xyz(units);
  tbb::parallel_for(tbb::blocked_range<int>(0, units, 32), [&](const tbb::blocked_range<int>& b) {
    for (int u = b.begin(); u != b.end(); ++u) {
      const glm::dvec3 v = evaluate_unit_from_sums(plan, level, train, sums, u);
      unit_xyz[u] = glm::vec3(r.monochromatic ? white * v.y : v);  // as develop_image
    }
  });
  return unit_xyz;
}

// The plan's scene with the frame's accessory in the slot.
Scene in_slot(Scene s, const InstrumentSettings& in) {
  s.compensator = in.compensator;
  s.compensator_position = in.compensator_position;
  return s;
}

// The angle of the accessory's eigen-axis (its slow direction) in the lab.
double slot_axis_rad(const Scene& lab) {
  const TrainState t = make_train(lab, make_compensator(lab.compensator, lab.compensator_position), 550.0);
  return std::atan2(t.comp_dir[1].y, t.comp_dir[1].x);
}

// A figure's accessory planes (the header): per polarizer probe j, the units evaluated in three
// accessory trains — eigen-axis and analyzer at (β, α) = (0°, 45°), (90°, 45°), (45°, 0°) in the
// specimen's frame, each the lab train turned by θ = β_lab − β — developed, less the probes' part
// ½[X0 + u1·X1 + u2·X2], leave v1·Y1 + v2·Y2 + w3·Z3; the three configurations' (v1, v2, w3),
// (0, 1, 1), (0, 1, −1) and (1, 0, −1), are independent (det −2), so Y1, Y2, Z3 follow.
std::vector<float> figure_accessory_planes(const FigureResponse& r, const Scene& lab, const CompensatorSums& sums) {
  constexpr double kConfigDeg[3][2] = {{0.0, 45.0}, {90.0, 45.0}, {45.0, 0.0}};  // β, α
  const std::size_t n = static_cast<std::size_t>(r.width) * r.height;
  const double beta_lab = slot_axis_rad(lab);
  glm::dmat3 coeff;  // rows k: (v1, v2, w3) of configuration k (glm: coeff[column][row])
  std::array<std::array<double, 3>, 3> d{};  // the configurations' analyzer weights on the probes
  for (int k = 0; k < 3; ++k) {
    const AccessoryWeights a = accessory_weights(radians(kConfigDeg[k][1]), radians(kConfigDeg[k][0]));
    coeff[0][k] = a.v1;
    coeff[1][k] = a.v2;
    coeff[2][k] = a.w3;
    d[k] = analyzer_weights(a.u1, a.u2);
  }
  const glm::dmat3 solve = glm::inverse(coeff);
  std::vector<float> planes(27 * n, 0.0f);
  std::vector<float> residual[3];
  RenderImage img;
  for (int j = 0; j < 3; ++j) {
    for (int k = 0; k < 3; ++k) {
      const double theta = beta_lab - radians(kConfigDeg[k][0]);
      Scene s = lab;
      s.analyzer_in = true;
      s.polarizer_deg = kFigureProbeDeg[j] + degrees(theta);
      s.analyzer_deg = kConfigDeg[k][1] + degrees(theta);
      const std::vector<glm::vec3> units = units_in_train(r, s, sums, theta);
      develop_image(*r.plan, std::vector<glm::dvec3>(units.begin(), units.end()), false, img);
      residual[k] = img.xyz;
      for (std::size_t p = 0; p < n; ++p)
        for (int c = 0; c < 3; ++c) {
          double x = 0.0;
          for (int i = 0; i < 3; ++i) x += d[k][i] * r.probes[(3 * (3 * i + j) + c) * n + p];
          residual[k][3 * p + c] -= static_cast<float>(x);
        }
    }
    for (std::size_t p = 0; p < n; ++p)
      for (int c = 0; c < 3; ++c) {
        const glm::dvec3 ymz = solve * glm::dvec3(residual[0][3 * p + c], residual[1][3 * p + c], residual[2][3 * p + c]);
        for (int m = 0; m < 3; ++m) planes[(3 * (3 * m + j) + c) * n + p] = static_cast<float>(ymz[m]);
      }
  }
  for (const auto& [i, q] : r.rim)
    for (int k = 0; k < kProbeFloats; ++k) planes[k * n + i] = planes[k * n + q];
  return planes;
}

// The accessory state a frame reads (FigureResponse::accessory): the sums, and a figure's planes.
std::shared_ptr<const FigureResponse::Accessory> accessory_of(const FigureResponse& r, const InstrumentSettings& in) {
  return r.accessory->get({static_cast<int>(in.compensator), in.compensator_position}, [&] {
    const Scene lab = in_slot(r.plan->scene(), in);
    const CompensatorPlate comp = make_compensator(lab.compensator, lab.compensator_position);
    auto acc = std::make_shared<FigureResponse::Accessory>();
    // The sums in the unturned train: turning moves the train's directions, not the phase χ.
    acc->sums = compensator_sums(*r.plan, level_in_train(*r.level, lab, comp));
    if (!r.flat) {
      acc->planes = figure_accessory_planes(r, lab, acc->sums);
      acc->sums = CompensatorSums{};  // the planes serve every frame
    }
    return std::shared_ptr<const FigureResponse::Accessory>(std::move(acc));
  });
}

// A flat view's units at the frame's settings, stage 0°: without an accessory its nine unit probes
// combined with the frame's weights; with one, every unit evaluated in the frame's train turned
// into the specimen's frame (the stage-0° canvas's crystals, the polars and slot at −θ) from the
// accessory's sums.
std::vector<glm::vec3> frame_units(const FigureResponse& r, const InstrumentSettings& in, const std::array<float, 9>& w) {
  const EvaluationPlan& plan = *r.plan;
  if (in.compensator != Compensator::None) {
    Scene lab = in_slot(plan.scene(), in);
    lab.polarizer_deg = degrees(in.polarizer_rad);
    lab.analyzer_in = in.analyzer_in;
    lab.analyzer_deg = degrees(in.analyzer_rad);
    return units_in_train(r, lab, accessory_of(r, in)->sums, in.stage_rad);
  }
  const int units = static_cast<int>(plan.units().size());
  const glm::dvec3 white = illuminant_white_xyz(plan.scene().illuminant);
  std::vector<glm::vec3> unit_xyz(units);
  for (int u = 0; u < units; ++u) {
    const float* p = &r.unit_probes[static_cast<std::size_t>(u) * kProbeFloats];
    glm::dvec3 v(0.0);
    for (int k = 0; k < 9; ++k) v += static_cast<double>(w[k]) * glm::dvec3(p[3 * k], p[3 * k + 1], p[3 * k + 2]);
    unit_xyz[u] = glm::vec3(r.monochromatic ? white * v.y : v);  // as develop_image
  }
  return unit_xyz;
}

// A flat view at the frame's units: each view pixel the mean of its (n·k)² sub-samples (n per
// canvas pixel, k canvas pixels a view pixel), each the unit of the canvas sub-sample nearest its
// position turned onto the canvas (FigureResponse::canvas_label). `origin`, `ex`, `ey`: view pixel
// (px, py) lies at canvas point origin + px·ex + py·ey (canvas pixel centres at integers).
void compose_flat(const FigureResponse& r, const std::vector<glm::vec3>& unit_xyz, const glm::dvec2& origin,
                  const glm::dvec2& ex, const glm::dvec2& ey, const glm::mat3& to_rgb, RenderImage& img) {
  const int W = r.image_width, H = r.image_height, n = r.samples_per_side;
  const int ls = n * kFlatLabelsPerSample, nn = ls * ls;  // labels a canvas pixel has along each side
  const int m = n * r.scale, fine_w = r.width * ls, fine_h = r.height * ls;
  const float mean = 1.0f / static_cast<float>(m * m);
  tbb::parallel_for(tbb::blocked_range<int>(0, H, 8), [&](const tbb::blocked_range<int>& rows) {
    std::vector<glm::dvec2> row_at(static_cast<std::size_t>(m) * m);
    for (int y = rows.begin(); y != rows.end(); ++y) {
      // Sub-sample (i, j) of the row's pixel x lies at row_at[j·m + i] + x·ex (linear in x).
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) row_at[j * m + i] = origin + ((i + 0.5) / m) * ex + (y + (j + 0.5) / m) * ey;
      const glm::dvec2 centre = origin + 0.5 * ex + (y + 0.5) * ey;
      for (int x = 0; x < W; ++x) {
        glm::vec3 v(0.0f);
        const int cx = static_cast<int>(std::lround(centre.x + x * ex.x)), cy = static_cast<int>(std::lround(centre.y + x * ex.y));
        const int uniform = r.scale == 1 && cx >= 0 && cy >= 0 && cx < r.width && cy < r.height
                                ? r.canvas_uniform[static_cast<std::size_t>(cy) * r.width + cx]
                                : -1;
        if (uniform >= 0) v = unit_xyz[uniform] * static_cast<float>(m * m);
        for (std::size_t s = 0; uniform < 0 && s < row_at.size(); ++s) {
          const glm::dvec2& at = row_at[s];
          // The nearest label: canvas pixel c's label cell s (of ls a side) is centred on
          // c − ½ + (s + ½)/ls; the canvas's own sub-samples are the cells s = 3i + 1.
          const int fx = std::clamp(static_cast<int>(std::floor((at.x + x * ex.x + 0.5) * ls)), 0, fine_w - 1);
          const int fy = std::clamp(static_cast<int>(std::floor((at.y + x * ex.y + 0.5) * ls)), 0, fine_h - 1);
          int unit = r.canvas_label[static_cast<std::size_t>(fy / ls) * r.width + fx / ls];
          if (unit <= -2) unit = r.mixed_labels[static_cast<std::size_t>(-2 - unit) * nn + (fy % ls) * ls + fx % ls];
          if (unit >= 0) v += unit_xyz[unit];
        }
        v *= mean;
        const std::size_t o = static_cast<std::size_t>(y) * W + x;
        const glm::vec3 rgb = r.monochromatic ? glm::vec3(v.y) : to_rgb * v;
        for (int ch = 0; ch < 3; ++ch) {
          img.xyz[3 * o + ch] = std::isfinite(v[ch]) ? v[ch] : 0.0f;
          img.rgb[3 * o + ch] = std::isfinite(rgb[ch]) ? rgb[ch] : 0.0f;
        }
      }
    }
  });
}

}  // namespace

RenderImage compose_figure(const FigureResponse& r, const InstrumentSettings& in) {
  const int W = r.image_width, H = r.image_height, GW = r.width, GH = r.height;
  const double theta = in.stage_rad;
  const std::array<double, 3> c = probe_weights(in.polarizer_rad - theta);
  // The analyzer out passes a(0°) + a(90°) = (2, 0, 0): the whole intensity (the header).
  const std::array<double, 3> d = in.analyzer_in ? probe_weights(in.analyzer_rad - theta) : std::array<double, 3>{1, 0, 1};
  std::array<float, 9> w{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w[3 * i + j] = static_cast<float>(d[i] * c[j]);
  const StageToSample turn(degrees(theta));
  const double half = 0.5 * std::min(W, H) * r.scale;
  // Image point (px, py) → grid coordinates (pixel centres at integers); affine: origin + px·ex + py·ey.
  const auto to_grid = [&](double px, double py) {
    const glm::dvec2 g = turn(field_from_pixel(W, H, px, py));
    return glm::dvec2(g.x * half + 0.5 * GW - 0.5, 0.5 * GH - g.y * half - 0.5);
  };
  const glm::dvec2 origin = to_grid(0, 0), ex = to_grid(1, 0) - origin, ey = to_grid(0, 1) - origin;
  const bool accessory = in.compensator != Compensator::None;
  if ((r.flat || accessory) && !r.plan)
    throw std::logic_error("compose_figure: an accessory in a figure with ghost light (it is rendered per setting)");
  const std::size_t n = static_cast<std::size_t>(W) * H, grid_n = static_cast<std::size_t>(GW) * GH;
  RenderImage img = r.progress;
  img.width = W;
  img.height = H;
  img.rgb.resize(n * 3);
  img.xyz.resize(n * 3);
  glm::mat3 to_rgb;  // XYZ → linear sRGB, in float (columns: the images of X, Y, Z)
  for (int k = 0; k < 3; ++k) to_rgb[k] = glm::vec3(xyz_to_linear_srgb(glm::dvec3(k == 0, k == 1, k == 2)));
  if (r.flat) {
    compose_flat(r, frame_units(r, in, w), origin, ex, ey, to_rgb, img);
    return img;
  }
  // The figure at these settings, stage 0°; then read turned by the stage.
  std::vector<float> grid;
  if (accessory) {
    // The analyzer through the accessory (the header); with the analyzer out the accessory
    // changes nothing (a retarder before an intensity).
    const std::shared_ptr<const FigureResponse::Accessory> acc = accessory_of(r, in);
    std::array<float, 9> wa = w, we{};
    if (in.analyzer_in) {
      const AccessoryWeights a =
          accessory_weights(in.analyzer_rad - theta, slot_axis_rad(in_slot(r.plan->scene(), in)) - theta);
      const std::array<double, 3> du = analyzer_weights(a.u1, a.u2), v = {a.v1, a.v2, a.w3};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          wa[3 * i + j] = static_cast<float>(du[i] * c[j]);
          we[3 * i + j] = static_cast<float>(v[i] * c[j]);
        }
    }
    grid = contract_grid(r, wa, &acc->planes, we);
  } else {
    grid = contract_grid(r, w);
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, H, 8), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      const glm::dvec2 row_at = origin + 0.5 * ex + (y + 0.5) * ey;  // the row's pixel centres, linear in x
      for (int x4 = 0; x4 < W; x4 += 4) {
        // Four pixels at a time (the last group repeats the row's last pixel).
        double gx[4], gy[4];
        for (int p = 0; p < 4; ++p) {
          const int x = std::min(x4 + p, W - 1);
          gx[p] = row_at.x + x * ex.x;
          gy[p] = row_at.y + x * ex.y;
        }
        cubic::v4 read[4];
        cubic::cubic4(grid.data(), GW, GH, cubic::cells(gx, gy, GW, GH, GW - 1, GH - 1), read);
        for (int p = 0; p < 4 && x4 + p < W; ++p) {
          const std::size_t o = static_cast<std::size_t>(y) * W + x4 + p;
          glm::vec3 v(0.0f);
          if (r.lit.empty() || r.lit[o]) {
            // No negative light from the cubic's overshoot at an isogyre's edge.
            v = glm::max(glm::vec3(read[p][0], read[p][1], read[p][2]), glm::vec3(0.0f));
          } else if (!r.outside.empty()) {  // light outside the disc, nearest
            const int sx = static_cast<int>(std::lround(gx[p])), sy = static_cast<int>(std::lround(gy[p]));
            if (sx >= 0 && sy >= 0 && sx < GW && sy < GH) {
              const std::size_t q = static_cast<std::size_t>(sy) * GW + sx;
              for (int kk = 0; kk < 9; ++kk)
                for (int ch = 0; ch < 3; ++ch) v[ch] += w[kk] * r.outside[(3 * kk + ch) * grid_n + q];
            }
          }
          const glm::vec3 rgb = r.monochromatic ? glm::vec3(v.y) : to_rgb * v;
          for (int ch = 0; ch < 3; ++ch) {
            img.xyz[3 * o + ch] = std::isfinite(v[ch]) ? v[ch] : 0.0f;
            img.rgb[3 * o + ch] = std::isfinite(rgb[ch]) ? rgb[ch] : 0.0f;
          }
        }
      }
    }
  });
  return img;
}

}  // namespace pmsim
