#include "core/bench/bench_scenes.h"

#include <filesystem>

#include "core/io/scene_file.h"
#include "core/microscope/sample_source.h"

namespace pmsim {

std::vector<BenchScene> bench_scenes(int size, std::vector<std::string>* notes) {
  std::vector<BenchScene> out;
  Scene base;
  base.render.width = base.render.height = size;
  base.polarizer_deg = 0.0;
  base.analyzer_deg = 90.0;
  base.analyzer_in = true;
  base.optics.lens_model = LensModel::Ideal;

  {  // A standard 30 µm quartz plate, optic axis in the stage plane, at 45°: first-order white/yellow.
    Scene s = base;
    s.mode = ViewMode::Ortho;
    s.sample.type = SampleType::Plate;
    s.sample.mineral = "quartz";
    s.sample.thickness_um = 30.0;
    s.sample.optic_axis = {1, 0, 0};
    s.stage_deg = 45.0;
    out.push_back({"quartz-30um-45deg-ortho",
                   "quartz 30 µm, optic axis in the stage plane at 45°, crossed polars", s, false, false});
  }
  {  // A thin section of grains (the hand-placed granite its numbers were measured on, preferred).
    std::string section;
    for (const char* name : {"granite_hand_placed", "granite", "basalt"})
      if (section_known(name)) {
        section = name;
        break;
      }
    if (section.empty()) {
      const std::filesystem::path dir = std::filesystem::path(asset_dir()) / "sections";
      std::error_code ec;
      if (std::filesystem::is_directory(dir, ec))
        for (const auto& e : std::filesystem::directory_iterator(dir, ec))
          if (e.path().extension() == ".json") {
            section = e.path().string();
            break;
          }
    }
    if (!section.empty()) {
      Scene s = base;
      s.mode = ViewMode::Ortho;
      s.sample.type = SampleType::Section;
      s.sample.section = section;
      s.sample.thickness_um = 30.0;
      s.stage_deg = 20.0;
      out.push_back({"section-ortho",
                     "thin section '" + std::filesystem::path(section).stem().string() +
                         "' 30 µm, crossed polars, stage 20°",
                     s, false, false});
    } else if (notes) {
      notes->push_back("no thin section in assets/sections yet: the section-ortho scene is skipped");
    }
  }
  Scene cono = base;
  cono.mode = ViewMode::Cono;
  cono.bertrand_in = true;
  cono.objective.na = 0.85;
  cono.condenser.na = 0.9;
  // Calcite 1 mm ⟂ c at NA 0.85 (condenser 0.9), the shipped scene, with the bench's size and
  // ideal lenses like every other bench scene.
  Scene calcite =
      load_scene_file((std::filesystem::path(asset_dir()) / "scenes" / "calcite_cono.json").string());
  calcite.render.width = calcite.render.height = size;
  calcite.optics.lens_model = LensModel::Ideal;
  // The uniaxial cross with many dense isochromes (Γ ≈ 0.17 mm at the edge).
  out.push_back({"calcite-1mm-cono", "calcite 1 mm ⟂ c, conoscopic, NA 0.85", calcite, true, false});
  {  // Biaxial acute-bisectrix figure: muscovite (optically negative, so Bxa = X) with X along the
     // microscope axis and the optic-axial plane (X, Z) east–west, stage at 45° (hyperbolae).
    Scene s = cono;
    s.sample.mineral = "muscovite";
    s.sample.thickness_um = 40.0;
    s.sample.x_axis = {0, 0, 1};
    s.sample.z_axis = {1, 0, 0};
    s.stage_deg = 45.0;
    out.push_back({"muscovite-bxa-cono", "muscovite 40 µm, acute bisectrix ⟂ stage, stage 45°, NA 0.85", s,
                   true, false});
  }
  {  // The calcite figure with the physical (SML) condenser, objective and Bertrand lens.
    Scene s = calcite;
    s.optics.lens_model = LensModel::Physical;
    s.optics.lens_depth = 3;
    out.push_back({"calcite-1mm-cono-physical",
                   "calcite 1 mm ⟂ c, SML lenses with internal reflections (dT = 3)", s, true, true});
  }
  return out;
}

}  // namespace pmsim
