#pragma once
// Private to the App: what the teaching panels keep between frames, so the core is asked again
// only when the scene or the probed point changes.
#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/microscope/figure_info.h"
#include "core/microscope/grain_report.h"
#include "core/microscope/pixel_probe.h"
#include "core/microscope/scene.h"
#include "core/render/michel_levy_chart.h"
#include "core/specimen/becke_probe.h"
#include "core/specimen/section_becke_probe.h"
#include "core/specimen/specimen_scene.h"
#include "core/spectrum/illuminant.h"
#include "ui/app.h"

namespace pmsim::ui {

// The compensator test read by brightness for a grain of retardation Γ (the teaching panel's line,
// issue 23, for a student who cannot tell interference colours apart): core's brightness_test
// (core/render/brightness_test.h) for the mica or the gypsum plate, as
// "Mica λ/4 at 45°: Y 0.39 → 0.98 adding, 0.03 subtracting: brighter on addition".
std::string brightness_line(double retardation_nm, Compensator accessory, Illuminant illuminant = Illuminant::D65);

struct App::Teaching {
  // The probe runs off the UI thread (the first probe of a thin section loads its map).
  struct ProbeResult {
    PixelProbe probe;
    std::optional<GrainReport> grain;  // the grain under the point (orthoscopic thin sections)
    std::optional<BeckeProbe> becke;   // grain mounts: what the Becke line does at the point
    // Thin sections (orthoscopic): what the Becke line does at the nearest boundary, and whether
    // the image shows it now (the slab is traced: relief on, analyzer out).
    std::optional<SectionBeckeProbe> section_becke;
    bool section_becke_traced = false;
    std::string error;
  };
  // The grain mount the Becke probe reads (built by the probe job, used only by probe jobs,
  // which run one at a time): rebuilt only when the mineral or the liquid changes.
  struct BeckeMount {
    std::unique_ptr<SpecimenScene> specimen;
    std::string mineral;
    double medium_index = 0.0;
    bool custom = false;
  };
  std::shared_ptr<BeckeMount> becke_mount = std::make_shared<BeckeMount>();
  std::optional<BeckeProbe> becke;
  std::optional<SectionBeckeProbe> section_becke;
  bool section_becke_traced = false;
  std::optional<GrainReport> grain;
  PixelProbe probe;
  std::string probe_error;
  std::uint64_t probe_generation = ~0ull;  // what `probe` (or the job in flight) was asked for
  float probe_x = -1, probe_y = -1;
  std::future<ProbeResult> probe_job;
  std::vector<float> spectrum;  // probe.transmission as floats for the plot

  FigureInfo figure;
  std::string figure_error;
  std::uint64_t figure_generation = ~0ull;

  // The Michel-Lévy chart with its birefringence lines (Γ = d·Δn), computed off the UI thread at
  // the pixel size it is drawn at (1 px lines stay sharp), again when the illuminant or size changes.
  static constexpr double kChartMaxNm = 1800.0;
  static constexpr double kChartMaxUm = 50.0;
  struct ChartKey {
    Illuminant illuminant = Illuminant::D65;
    int width = 0, height = 0;
    bool operator==(const ChartKey&) const = default;
  };
  LinearTexture chart;
  ChartKey chart_key;
  bool chart_valid = false;
  std::future<std::vector<float>> chart_job;
  ChartKey chart_job_key;
  std::vector<MichelLevyLine> chart_lines = michel_levy_lines(kChartMaxNm, kChartMaxUm);
};

}  // namespace pmsim::ui
