#pragma once
// The preview policy of a progressive render: which scenes get quick coarse images before the
// full-resolution passes, how coarse, and making them.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>

#include "core/microscope/scene.h"
#include "core/render/buffer_pool.h"
#include "core/render/render_image.h"

namespace pmsim {

using RenderClock = std::chrono::steady_clock;

// The first pass of a large conoscopic figure, thin section or wedge (what a UI shows the moment a
// control moves): the per-pixel set-up (three mode solutions per pixel of a figure; the grain or
// thickness under every pixel and sub-pixel of a section or wedge) dominates it, so it runs on a
// grid 4× coarser each way with 16 bands and is spread bilinearly over the lit pixels; the
// full-resolution passes follow. A figure is smooth on that scale except near its dark isochromes,
// a section except along its grain boundaries, which the next pass restores. A uniform plate in
// parallel light is one spectral evaluation for the whole field and needs no preview.
constexpr int kPreviewFactor = 4;
constexpr int kPreviewBands = 16;
constexpr long long kPreviewMinPixels = 256LL * 256LL;

// A biaxial figure costs ~10x more per direction (the mode search), and its isochromes are far
// apart in a thin plate: its preview grid is 8x coarser each way.
constexpr int kPreviewFactorBiaxial = 8;

// Before that preview, a glance twice as coarse again (1/8, biaxial 1/16 each way: 64² for a 512²
// field): 4× less work, so the first image of a change comes 4–10 ms after it on two idle cores
// (in the UI, whose software-GL frames share those cores, in the second frame after the change);
// the 1/4 preview follows a few milliseconds later.
constexpr int kGlanceFactor = 2;

// The preview grid factor of a scene (kPreviewFactor, or kPreviewFactorBiaxial for a biaxial plate).
int preview_factor(const Scene& scene);
// Whether a progressive render of the scene starts with the glance and the preview: per-pixel
// set-ups (a back focal plane, a section or a wedge) of at least kPreviewMinPixels.
bool wants_preview(const Scene& scene);

// Renders the scene on a grid `factor` times coarser each way with at most kPreviewBands bands,
// without lens ghosts, upsamples it and hands it to `publish` (image, last = false) as pass `pass`.
// Returns false when cancelled.
bool run_preview(const Scene& scene, int factor, int pass, const std::atomic<bool>& cancel,
                 RenderClock::time_point t0, std::uint64_t generation, BufferPool* pool,
                 const std::function<void(RenderImage&&, bool)>& publish);

}  // namespace pmsim
