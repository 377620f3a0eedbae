#pragma once
// A conoscopic figure's response to the polars and the stage (issue 21): rendered once, composed
// at any stage angle, polarizer and analyzer setting in a few multiply-adds a pixel.
//
// Per back-focal-plane point the image is linear in the polarizer's and in the analyzer's Stokes
// vectors (docs/physics.md, "One response, many settings"): with ideal linear polars at ψ and α,
// p(ψ) = (1, cos 2ψ, sin 2ψ) and a(α) = (1, cos 2α, sin 2α),
//   XYZ(ψ, α) = a(α)ᵀ · N · p(ψ),   N a 3 × 3 block for each of X, Y and Z,
// the band sum Σ_b W_b of the objective · specimen · condenser Mueller matrices (V never enters:
// no retarder outside the specimen). Nine renders of the figure with the polars at 0°, 45° and
// 90° each ("probes") fix N: p(0°), p(45°), p(90°) are independent, so any p(ψ) is
// c0·p(0°) + c1·p(45°) + c2·p(90°) with c1 = sin 2ψ, c0,2 = (1 − sin 2ψ ± cos 2ψ)/2, and the
// image at (ψ, α) is Σ_ij d_i c_j · probe_ij. The analyzer out passes the whole intensity,
// a(0°) + a(90°) = (2, 0, 0): d = (1, 0, 1).
//
// The stage: objective, condenser and Bertrand lens are figures of revolution about the axis, so
// turning the specimen by θ is turning the polars by −θ and the figure by θ — a pixel at
// back-focal-plane point f shows the stage-0 response at R(−θ)·f (sample_from_field), read by
// Keys' cubic, with the polars at ψ − θ and α − θ. The lit disc is centred, so it maps onto
// itself; grid points just outside it hold their nearest lit neighbour's value, so the cubic's
// taps at the rim read no black.
//
// Where the probes do not hold: an accessory, whose retardance sits inside the band sum between
// the specimen and the analyzer. A figure keeps the plan its probes came from (its modal fits kept,
// one unit a back-focal-plane point), and a frame with the gypsum plate, the mica plate or the
// quartz wedge evaluates every unit in the frame's train turned into the specimen's frame
// (train_in_specimen_frame: polars and slot at −θ), develops the grid and reads it turned as
// above: exact at every accessory and wedge position. The band sums do not depend on the polars,
// the slot's angle or the stage (compensator_sums.h): the first frame with an accessory at a wedge
// position makes them, one band loop a unit. A flat view's frames then combine them with their
// train's terms (make_modal_terms and 15 products a direction). A figure's first frame goes on to
// planes, as its probes: a retarder with an eigen-axis at β has the Mueller matrix
// C0(β) + cos δ·C1(β) + sin δ·C2(β) (docs/physics.md §3), so with the analyzer at α, in the
// specimen's frame,
//   XYZ = ½[X0 + u1·X1 + u2·X2] + v1·Y1 + v2·Y2 + w3·Z3,
//   u1 = a1c² + a2cs, u2 = a1cs + a2s², v1 = a1s² − a2cs, v2 = a2c² − a1cs, w3 = a2c − a1s,
// (a1, a2) = (cos 2α, sin 2α), (c, s) = (cos 2β, sin 2β), each term per polarizer probe: X from the
// nine probes (the analyzer's u in place of its a), and Y1, Y2, Z3 — the band sums of cos δ·Q,
// cos δ·U and sin δ·V of the specimen's output, halved — from the units evaluated in three
// accessory trains per polarizer probe, (β, α) = (0°, 45°), (90°, 45°), (45°, 0°), less their X
// part. A frame then contracts 18 planes a channel (the sign of C2, a convention, cancels: the
// same formulas make Z3 and read it). The
// physical lenses' ghost light (optics.lens_depth ≥ 2) is reckoned per train in the plan, so such
// a figure with an accessory is rendered per setting (figure_response_applies is false).
//
// A flat orthoscopic view of a thin section (no relief, or an EBSD map; flat_response_applies) is the
// same bilinear form per image point, and the same rotation argument holds (condenser and
// objective apertures are circular). Its image is a sum over few evaluation units — one per grain
// or lamella in parallel light, boundary pixels' sub-samples as weights on them — so its probes are
// taken per unit, not per pixel: a canvas at the view's pixel pitch that holds the view at every
// stage angle (the view's circumscribed circle and two pixels more) is compiled once at stage 0°
// (its evaluation plan, modal fits kept), every unit is evaluated in the nine probe trains, and a
// frame combines each unit's nine with its weights into the unit's colour at its settings. With an
// accessory in the slot the frame evaluates every unit in its own train turned into the
// specimen's frame (train_in_specimen_frame: polars and slot at −θ) instead — exact at every
// accessory, wedge position and polar setting, for the units' band sums each frame.
// A frame does not interpolate the canvas's colours (a cubic's blend of the partial pixels on
// either side of a grain boundary blurs it by a pixel: ΔE00 1.3 from a fresh render at 512² on
// the grown granite between crossed polars, 1.7–2.0 with the gypsum plate). It samples each view
// pixel as a fresh render does, n × n sub-samples, each showing the unit of the canvas label
// nearest its turned position (canvas_label), and takes the mean of their units' colours; at
// stage 0° those are the canvas's own sub-samples, so the view is the canvas render's. A small view's canvas is finer
// than its pixels (flat_canvas_scale): its pixel takes (n·k)² sub-samples, its k × k canvas
// pixels' at stage 0°.
#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "core/base/build_cache.h"
#include "core/microscope/scene.h"
#include "core/render/compensator_sums.h"
#include "core/render/render_image.h"
#include "core/render/spectral_level.h"
#include "core/specimen/specimen_response.h"

namespace pmsim {

// Polar angles of the probes (specimen frame, stage 0°), degrees.
inline constexpr double kFigureProbeDeg[3] = {0.0, 45.0, 90.0};

// Whether a scene's view is a conoscopic figure the response serves: Bertrand lens in,
// conoscopic mode, and no accessory in the slot or no ghost light (optics.lens_depth < 2).
bool figure_response_applies(const Scene& scene);
// A flat view's canvas plan holds each canvas pixel's unit references (~16 B) and its labels (8 B,
// and 144 B for a pixel across a boundary), on a canvas of about twice the view's pixels: 1536²
// canvas pixels (a view up to ~1080², ~100 MB) is where a view is rendered per setting instead (the app's views are
// 512–1024²; a 2048² view's canvas would be 8.4 M pixels).
inline constexpr long long kMaxFlatCanvasPixels = 1536LL * 1536LL;
// A flat canvas narrower than kFlatCanvasMinSide view pixels is rendered k ≤ kMaxFlatCanvasScale
// times finer: at 32² (canvas 50 px) a granite view's pixel straddles a grain boundary in one
// pixel of three, and composing from view-pitch probes (read by a cubic then) was 0.7 ΔE00 further
// from a converged reference than a fresh render (2.07 against 1.41); a 4×-finer canvas, its
// (n·k)² sub-samples a view pixel, is 1.28 (docs/response.md), costs 16× a tiny canvas's probes,
// and nothing at the app's 512–1024² views (k = 1).
inline constexpr int kFlatCanvasMinSide = 256;
inline constexpr int kMaxFlatCanvasScale = 4;
// Canvas pixels per view pixel along each axis for a flat view of width × height.
int flat_canvas_scale(int width, int height);

// Whether a flat orthoscopic view is served by probes (the traced specimens aside, which
// response_kind tells first): a thin section (a plate or the empty stage is one evaluation for the
// whole field, and a wedge's thickness runs across the rendered field, so a larger canvas would be
// another wedge) in the orthoscope, Bertrand lens out, its canvas within kMaxFlatCanvasPixels and
// the field-number limit. Any accessory: frames with one are composed from the canvas's plan.
bool flat_response_applies(const Scene& scene);

// A flat canvas pixel across a boundary keeps its units on a grid kFlatLabelsPerSample times finer
// than its n × n sub-samples (odd: at stage 0° a view sub-sample sits on the centre of a label
// cell, the canvas's own sub-sample). A turned view sub-sample reads the nearest label, at most
// 1/(2·3n) of a pixel from where a fresh render samples: 3× fewer boundary sub-samples read across
// a boundary than labels at the sub-samples alone.
inline constexpr int kFlatLabelsPerSample = 3;

struct FigureResponse {
  int width = 0, height = 0;  // the probes' grid (a flat view's canvas)
  int image_width = 0, image_height = 0;  // the composed image (a figure: the grid itself)
  bool flat = false;                       // a flat orthoscopic view's canvas, not a figure
  int scale = 1;  // canvas pixels per view pixel along each axis (flat_canvas_scale; a figure: 1)
  bool monochromatic = false;  // render.single_wavelength_nm: R = G = B = Y
  // A figure's probes: 27 planes of width × height floats: plane 3·(3·i + j) + c holds channel c
  // (X, Y, Z) of the probe with the analyzer at kFigureProbeDeg[i] and the polarizer at
  // kFigureProbeDeg[j] (planes: a frame's contraction is nine contiguous multiply-adds that
  // vectorise). Unlit pixels next to the disc hold their nearest lit neighbour (the cubic's reach).
  // Empty for a flat view.
  std::vector<float> probes;
  // A flat view's probes per unit of `plan`: 27 floats a unit, 3·(3·i + j) + c as above.
  std::vector<float> unit_probes;
  // A flat view's canvas as the units its sub-samples show (n × n a canvas pixel, n =
  // samples_per_side, where the canvas's field_view took them): per canvas pixel the unit all its
  // sub-samples show, -1 when none passes light, or -2 - i for a pixel across a boundary, whose n²
  // sub-samples' units (-1: no light) are mixed_labels[n²·i …], row by row. A frame reads each view
  // pixel's (n · scale)² sub-samples, turned, from the nearest canvas sub-sample.
  std::vector<int> canvas_label;
  std::vector<int> mixed_labels;
  // Per canvas pixel the unit it and its eight neighbours show alone, else -1: a view pixel (scale
  // 1) whose centre falls in such a pixel shows that unit at every sub-sample (they lie within
  // 1.5 canvas pixels of it), one reading instead of n².
  std::vector<int> canvas_uniform;
  int samples_per_side = 1;
  std::vector<unsigned char> lit;  // the figure's disc (rotation-invariant) on the image; empty: all lit
  // Light outside the disc (a physical lens' ghosts can land there): those pixels' raw probes,
  // read nearest-neighbour (the same planes); empty when there is none.
  std::vector<float> outside;
  // The plan the probes came from, its modal fits kept, and their spectral level: a flat view's
  // canvas plan (its units are what every frame develops the canvas from), a figure's plan for
  // frames with an accessory (null when the figure has ghost light: optics.lens_depth ≥ 2).
  std::shared_ptr<const EvaluationPlan> plan;
  std::shared_ptr<const SpectralLevel> level;
  // What frames with the accessory (kind, wedge position) last composed read, made on the first
  // frame with it (the header): a flat view's compensator sums (its few units are evaluated every
  // frame); a figure's 27 accessory planes, 3·(3·m + j) + c: the functionals m of the specimen's
  // Mueller matrix that the accessory adds (Q and U against cos δ, V against sin δ) for the
  // polarizer probe j, channel c, a grid point each (figure_accessory_planes).
  struct Accessory {
    CompensatorSums sums;
    std::vector<float> planes;
  };
  using AccessoryKey = std::pair<int, double>;
  std::shared_ptr<BuildCache<AccessoryKey, Accessory, Keep::Last>> accessory =
      std::make_shared<BuildCache<AccessoryKey, Accessory, Keep::Last>>();
  // A figure's unlit grid points within the cubic's reach of the disc, each with the lit point
  // whose value it holds (fill_rim: probes at the build, a developed grid on an accessory frame).
  std::vector<std::pair<std::size_t, std::size_t>> rim;
  // The spectral level the probes were rendered at, and the convergence of the figure's own
  // render at the scene's settings (what every composed image carries).
  int wavelengths = 0;
  RenderImage progress;  // passes, error_estimate, converged, stopped, model_report (no pixels)
  double time_ms = 0.0;  // render_figure_response: the figure's render and its probes; render_figure_probes: the probes
};

// Renders the figure at the scene's settings to convergence (its image goes to `progress`, as a
// fresh render's would), then the nine probes at that render's spectral level. nullopt when
// `cancel` is raised between renders. `threads` as ProgressiveRenderer::render's.
std::optional<FigureResponse> render_figure_response(const Scene& scene, int threads = 0,
                                                     const std::function<void(const RenderImage&)>& progress = nullptr,
                                                     const std::atomic<bool>* cancel = nullptr);

// The probes alone, given the figure's own converged render at the scene's settings (`own`: its
// spectral level and convergence; the app has it from its progressive renderer already).
std::optional<FigureResponse> render_figure_probes(const Scene& scene, const RenderImage& own, int threads = 0,
                                                   const std::atomic<bool>* cancel = nullptr);

// The view at `instrument` (any accessory; a figure with ghost light, whose plan is null, none):
// XYZ and linear sRGB.
RenderImage compose_figure(const FigureResponse& response, const InstrumentSettings& instrument);

}  // namespace pmsim
