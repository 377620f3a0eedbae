#include "core/bench/response_bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/bench/bench_strategy.h"  // process_cpu_ms
#include "core/bench/image_error.h"
#include "core/base/asset_locator.h"
#include "core/io/scene_file.h"
#include "core/microscope/modal_fit.h"
#include "core/render/progressive_renderer.h"
#include "core/specimen/figure_response.h"
#include "core/specimen/forward_response.h"
#include "core/specimen/grain_mount_render.h"
#include "core/specimen/section_slab.h"
#include "core/specimen/traced_specimen.h"
#include "core/spectrum/cie.h"

namespace pmsim {

namespace {

double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

Scene granite_crossed(int size) {
  Scene s;  // crossed polars: the Scene's defaults
  s.sample.type = SampleType::Section;
  s.sample.section = "granite_hand_placed";
  s.render.width = s.render.height = size;
  return s;
}

// A response traced for `scene` (coverage, traces a pixel, stop estimate, seed), as the product
// traces it.
ResponseProgress traced(const SpecimenScene& slab, const Scene& scene, ResponseCoverage coverage, int spp,
                        double tolerance, std::uint64_t seed) {
  ResponseRenderOptions o;
  o.light = plane_light_options(scene);
  o.light.spp = spp;
  o.light.tolerance_de2000 = tolerance;
  o.light.seed = seed;
  o.coverage = coverage;
  o.estimate_at = instrument_settings(scene);
  return render_specimen_response(slab, o);
}

// The median wall time of composing `p` at `in` (n runs).
double compose_ms(const ResponseProgress& p, const InstrumentSettings& in, int n) {
  std::vector<double> t;
  for (int i = 0; i < n; ++i) {
    const double t0 = now_ms();
    const RenderImage img = compose_progress(p, in);
    t.push_back(now_ms() - t0);
    if (img.width == 0) break;
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

std::string response_apply_note(int compose_size, int frames, std::ostream& log) {
  // The frame's work at the app's size: a 3-trace Disc response (its cost does not depend on passes).
  const Scene big = granite_crossed(compose_size);
  const auto big_slab = section_slab(big);
  log << "apply settings: a " << compose_size << "² Disc response, 3 traces a pixel… " << std::flush;
  const ResponseProgress one = traced(*big_slab, big, ResponseCoverage::Disc, 3, 0.0, 1);
  log << "done\n";
  Scene turned = big;
  turned.stage_deg = 30.0;
  Scene plate = turned;
  plate.compensator = Compensator::Gypsum;
  const double plain = compose_ms(one, instrument_settings(turned), frames);
  const double with_plate = compose_ms(one, instrument_settings(plate), frames);
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "applying the settings to a %d² Disc response (%d×%d grid): %.2f ms (stage 30°), %.2f ms with the "
                "gypsum plate (median of %d)",
                compose_size, one.response->nx, one.response->ny, plain, with_plate, frames);
  return buf;
}

namespace {

struct AccessoryCase {
  Compensator accessory;
  double position;
  double ms = 0.0, first_ms = 0.0, de = 0.0, fresh_ms = 0.0;
};

// A drag of 1° a frame from 30° composed from `r`, without an accessory, with the gypsum plate and
// with the quartz wedge at 0.4: the median frame, and the last frame against a fresh render (and
// that render's time: what the frame cost when the view was rendered per setting).
std::vector<AccessoryCase> drag_with_accessories(const FigureResponse& r, const Scene& s, int frames) {
  std::vector<AccessoryCase> cases = {{Compensator::None, 0.0}, {Compensator::Gypsum, 0.0}, {Compensator::QuartzWedge, 0.4}};
  const glm::dvec3 white = illuminant_white_xyz(s.illuminant);
  for (AccessoryCase& c : cases) {
    std::vector<double> t;
    Scene f = s;
    f.compensator = c.accessory;
    f.compensator_position = c.position;
    f.render.wavelengths = r.wavelengths;
    RenderImage img;
    for (int i = 0; i < frames; ++i) {
      f.stage_deg = 30.0 + i;
      const double t1 = now_ms();
      img = compose_figure(r, instrument_settings(f));
      t.push_back(now_ms() - t1);
    }
    c.first_ms = t.front();  // with an accessory: its sums (and a figure's planes) made
    std::sort(t.begin(), t.end());
    c.ms = t[t.size() / 2];
    const double t2 = now_ms();
    const RenderImage fresh = ProgressiveRenderer::render(f);
    c.fresh_ms = now_ms() - t2;
    c.de = image_error_de2000(img.xyz, fresh.xyz, {}, white).mean_de2000;
  }
  return cases;
}

// The view's response (probes and plan), timed; `what` names it in the log and in a failure.
std::pair<FigureResponse, double> timed_response(const Scene& s, const std::string& what, std::ostream& log) {
  log << "apply settings: " << what << "'s response… " << std::flush;
  const double t0 = now_ms();
  std::optional<FigureResponse> r = render_figure_response(s);
  const double ms = now_ms() - t0;
  if (!r || !r->plan) throw std::runtime_error("apply settings: " + what + "'s response was not rendered");
  log << "done\n";
  return {std::move(*r), ms};
}

}  // namespace

std::string flat_apply_note(int size, int frames, std::ostream& log) {
  Scene s = granite_crossed(size);
  s.optics.relief = false;
  const auto [response, response_ms] = timed_response(s, "the flat " + std::to_string(size) + "² view", log);
  const FigureResponse* r = &response;
  const std::vector<AccessoryCase> c = drag_with_accessories(*r, s, frames);
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "applying the settings to the flat %d² granite view (relief off, %d×%d canvas, %zu units; response "
                "%.0f ms): %.2f ms, %.2f ms with the gypsum plate, %.2f ms with the quartz wedge at 0.4 (median of %d "
                "frames at stage 30°+; the last frame against a fresh render: mean ΔE00 %.2f / %.2f / %.2f)",
                size, r->width, r->height, r->plan->units().size(), response_ms, c[0].ms, c[1].ms, c[2].ms, frames,
                c[0].de, c[1].de, c[2].de);
  return buf;
}

std::string figure_apply_note(int size, int frames, std::ostream& log) {
  Scene s = load_scene_file((std::filesystem::path(asset_dir()) / "scenes" / "biaxial_acute_bisectrix.json").string());
  s.render.width = s.render.height = size;
  const auto [response, response_ms] = timed_response(s, "the " + std::to_string(size) + "² biaxial figure", log);
  const FigureResponse* r = &response;
  // What the accessory frames keep beside the probes: the plan's fits, and 27 planes a grid point
  // (the band sums a direction, 27 floats, only while the planes are made).
  const double fits_mb = r->plan->modal_fits().size() * sizeof(ModalFit) / 1048576.0;
  const double planes_mb = 27.0 * r->width * r->height * sizeof(float) / 1048576.0;  // FigureResponse::Accessory::planes
  const std::vector<AccessoryCase> c = drag_with_accessories(*r, s, frames);
  char buf[700];
  std::snprintf(buf, sizeof buf,
                "applying the settings to the %d² biaxial figure (%zu units; response %.0f ms; fits %.0f MB, accessory planes %.0f MB): %.2f ms, "
                "%.2f ms with the gypsum plate, %.2f ms with the quartz wedge at 0.4 (median of %d frames at stage "
                "30°+; the first frame with each accessory, its sums and planes made: %.0f / %.0f ms; the last frame against "
                "a fresh render: mean ΔE00 %.2f / %.2f / %.2f; that render %.0f / %.0f / %.0f ms)",
                size, r->plan->units().size(), response_ms, fits_mb, planes_mb, c[0].ms, c[1].ms, c[2].ms, frames,
                c[1].first_ms, c[2].first_ms, c[0].de, c[1].de, c[2].de, c[0].fresh_ms, c[1].fresh_ms, c[2].fresh_ms);
  return buf;
}

std::vector<BenchRow> response_bench_rows(int size, int compose_size, bool quick, std::vector<std::string>& notes,
                                          std::ostream& log) {
  const int n = std::min(size, 256);
  const int spp = quick ? 8 : 64, ref_spp = quick ? 32 : 256, runs = quick ? 3 : 7;
  const Scene base = granite_crossed(n);
  const auto slab = section_slab(base);
  const glm::dvec3 white = illuminant_white_xyz(base.illuminant);
  log << "scene response-granite-crossed (" << n << "²): Disc response, " << spp << " traces a pixel… " << std::flush;
  const double cpu0 = process_cpu_ms(), t0 = now_ms();
  const ResponseProgress disc = traced(*slab, base, ResponseCoverage::Disc, spp, 1.0, 1);
  const double disc_ms = now_ms() - t0, disc_cpu = process_cpu_ms() - cpu0;
  log << disc_ms << " ms, estimate " << disc.error_estimate.value_or(-1.0) << "\n";

  struct Case {
    std::string name;
    Scene scene;
  };
  std::vector<Case> cases = {{"stage30", base}, {"gypsum-stage30", base}, {"polars40", base}};
  cases[0].scene.stage_deg = 30.0;
  cases[1].scene.stage_deg = 30.0;
  cases[1].scene.compensator = Compensator::Gypsum;
  cases[2].scene.polarizer_deg = 40.0;
  cases[2].scene.analyzer_deg = 130.0;
  std::vector<BenchRow> rows;
  const auto row = [&](const std::string& strategy, const RenderImage& img, const RenderImage& ref, double ms,
                       double cpu_ms, const std::string& what) {
    const ImageError e = image_error_de2000(img.xyz, ref.xyz, {}, white);
    BenchRow r;
    r.scene = "response-granite-crossed";
    r.strategy = strategy;
    r.width = r.height = n;
    r.time_ms = ms;
    r.cpu_ms = cpu_ms;
    r.mean_de2000 = e.mean_de2000;
    r.p95_de2000 = e.p95_de2000;
    r.max_de2000 = e.max_de2000;
    r.wavelengths = img.wavelengths;
    r.renderer_estimate = img.error_estimate.value_or(-1.0);
    r.code = "product";
    r.model_report = what;
    log << "  " << strategy << ": " << ms << " ms, mean ΔE00 " << e.mean_de2000 << "\n";
    rows.push_back(r);
  };
  double fresh_ms = 0.0;
  for (const Case& c : cases) {
    const InstrumentSettings in = instrument_settings(c.scene);
    log << "  " << c.name << ": reference (" << ref_spp << " traces, seed 2)… " << std::flush;
    const RenderImage ref = compose_progress(traced(*slab, c.scene, ResponseCoverage::Field, ref_spp, 0.0, 2), in);
    log << ref.time_ms << " ms, estimate " << ref.error_estimate.value_or(-1.0) << "\n";
    const double c0 = process_cpu_ms(), f0 = now_ms();
    const RenderImage fresh = compose_progress(traced(*slab, c.scene, ResponseCoverage::Field, spp, 1.0, 1), in);
    const double f_ms = now_ms() - f0;
    if (c.name == "stage30") fresh_ms = f_ms;
    row(c.name + "-fresh-" + std::to_string(spp) + "spp", fresh, ref, f_ms, process_cpu_ms() - c0, "a fresh render at these settings");
    const double ms = compose_ms(disc, in, runs);
    const RenderImage composed = compose_progress(disc, in);
    row(c.name + "-composed", composed, ref, ms, ms,
        "the Disc response (" + std::to_string(spp) + " traces, " + std::to_string(int(disc_ms)) +
            " ms) composed at these settings; time = applying the settings (median of " + std::to_string(runs) + ")");
    // Up to 128², at the turned stage: the same three against a reference with the colour traced
    // from every point (chroma period 1: 33 traces a point a pass; 32 passes, seed 3), which the
    // references above (colour on the period-4 subgrid, as the product's) cannot say.
    if (quick || n > 128 || c.name == "polars40") continue;
    log << "  " << c.name << ": colour reference (chroma period 1, 32 passes, seed 3)… " << std::flush;
    ResponseRenderOptions o;
    o.light = plane_light_options(c.scene);
    o.light.spp = 32 * 33;
    o.light.tolerance_de2000 = 0.0;
    o.light.seed = 3;
    o.light.chroma_period = 1;
    o.estimate_at = in;
    const RenderImage colour_ref = compose_progress(render_specimen_response(*slab, o), in);
    log << colour_ref.time_ms << " ms, estimate " << colour_ref.error_estimate.value_or(-1.0) << "\n";
    const std::string what = "against the colour reference (chroma period 1, 32 passes of 33 traces; its split-half "
                             "estimate in renderer_estimate of the -colour-reference row)";
    row(c.name + "-composed-vs-colour-reference", composed, colour_ref, ms, ms, "the Disc response composed, " + what);
    row(c.name + "-fresh-" + std::to_string(spp) + "spp-vs-colour-reference", fresh, colour_ref, f_ms, f_ms,
        "a fresh render, " + what);
    row(c.name + "-reference-vs-colour-reference", ref, colour_ref, ref.time_ms, ref.time_ms,
        "the " + std::to_string(ref_spp) + "-trace reference, " + what);
    rows.back().renderer_estimate = colour_ref.error_estimate.value_or(-1.0);
  }
  // A 19-frame stage sweep (0°…180° by 10°) from the Disc response, against one fresh render.
  double sweep_ms = disc_ms;
  for (int k = 0; k < 19; ++k) {
    Scene s = base;
    s.stage_deg = 10.0 * k;
    sweep_ms += compose_ms(disc, instrument_settings(s), 1);
  }
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "response %d²: Disc response %.0f ms (cpu %.0f ms); a 19-frame stage sweep from it %.0f ms = %.2f× one "
                "fresh %d-trace render (%.0f ms)",
                n, disc_ms, disc_cpu, sweep_ms, sweep_ms / std::max(1.0, fresh_ms), spp, fresh_ms);
  notes.push_back(buf);
  log << "  " << buf << "\n";
  if (compose_size > 0) {
    for (const std::string& note : {response_apply_note(compose_size, 15, log), flat_apply_note(compose_size, 15, log)}) {
      notes.push_back(note);
      log << "  " << note << "\n";
    }
  }
  return rows;
}

}  // namespace pmsim
