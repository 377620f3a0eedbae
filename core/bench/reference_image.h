#pragma once
// The converged reference a bench strategy is measured against, computed once per scene and
// cached on disk. It is built independently of the renderer's spectral shortcuts: 1 nm bands
// over 380–780 nm (400 of them), and in each band the plate's EXACT eigenmodes (plate_modes, no
// fit). Where the interference phase 2πΓ/λ moves less than 0.25 rad from one band to the next the
// exact Jones matrix (plate_jones, with optical activity) is sampled at the band centre; where it
// moves faster (a thick plate, high orders) the interference term is averaged over the band in
// closed form, cos(Δψ) → cos(Δψ)·sinc(Δψ'·1 nm/2) (phase linear across 1 nm), so that 10⁵-order
// retardations integrate to high-order white without aliasing. Thin sections use 4×4 sub-pixel
// positions. The same pass also integrates with 2 nm bands (every other band, double width): the
// difference between the two is the bench's check that the reference has converged.
#include <cstdint>
#include <string>
#include <vector>

#include "core/microscope/scene.h"

namespace pmsim {

struct ReferenceImage {
  int width = 0, height = 0;
  std::vector<float> xyz;         // 1 nm reference
  std::vector<float> xyz_half;    // the same with 2 nm bands (convergence check)
  std::vector<std::uint8_t> lit;  // pixels that receive light (the error is taken over these)
  double time_ms = 0.0;           // compute time (0 when read from the cache)
  bool from_cache = false;
  std::string cache_file;
};

constexpr int kReferenceBands = 400;
// Bumped whenever the reference computation changes, so that stale cache files are ignored.
constexpr const char* kReferenceVersion = "pmsim-bench-reference-8";

// The scene the reference renders (strategy exact, spp raised for sections); its JSON is part of
// the cache key.
Scene reference_scene(const Scene& scene);

// Reads <cache_dir>/<key>.ref when present and valid, else computes and writes it atomically
// (cache_dir empty: no cache). The key hashes the reference scene's JSON, kReferenceVersion and
// the contents of the data files it uses (assets/minerals, materials, sections).
ReferenceImage converged_reference(const Scene& scene, const std::string& cache_dir);

}  // namespace pmsim

namespace pmsim {

// The reference of the physical-lens scene: the bench-side SML model (physical_lens_model.h) at
// dT = 5 with 128 bands, cached like converged_reference; lit pixels from the ideal set-up.
ReferenceImage converged_physical_reference(const Scene& scene, const std::string& cache_dir);

}  // namespace pmsim
