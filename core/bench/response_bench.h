#pragma once
// The bench rows of the response/instrument split (issue 21) on the default scene, the granite
// section between crossed polars: one Disc response (the app's), composed at a turned stage and
// with the gypsum plate, against fresh renders at those settings and a 4×-work reference at each
// (up to 128², at the turned stage, also against a reference with the colour traced from every
// point: chroma period 1); what applying the settings costs (the frame's work), and a 19-frame stage sweep against one
// render.
#include <ostream>
#include <string>
#include <vector>

#include "core/bench/bench_run.h"

namespace pmsim {

// Rows at min(size, 256)²; `notes` gets the apply-settings time at compose_size² (0: skip).
// `quick` (--quick, what tests/bench_json_test.cpp runs, also under the sanitizers): 8 traces a
// pixel for the product and 32 for the references instead of 64 and 256, the rows' shape only.
std::vector<BenchRow> response_bench_rows(int size, int compose_size, bool quick, std::vector<std::string>& notes,
                                          std::ostream& log);

// Only the apply-settings timing (pmsim-bench --apply-settings): a 3-trace compose_size² Disc
// response of the granite composed at stage 30° without and with the gypsum plate, the median
// of `frames` wall times each, as one line.
std::string response_apply_note(int compose_size, int frames, std::ostream& log);

// The same for the flat view (issue 21): the granite at size², relief off, its flat response
// (figure_response.h: probes per unit, the canvas's plan) composed during a 1°-a-frame stage drag
// from 30° without an accessory, with the gypsum plate and with the quartz wedge at 0.4, the median
// of `frames` wall times each, and the last frame's mean ΔE00 against a fresh render; one line.
std::string flat_apply_note(int size, int frames, std::ostream& log);

// The same for a conoscopic figure (a biaxial plate ⟂ the acute bisectrix at 50×/0.85): the
// figure's response (its probes and its plan), then the drag without an accessory and with the
// gypsum plate and the quartz wedge, each last frame against a fresh render and that render's time
// (what an accessory frame cost before: the figure was rendered per setting).
std::string figure_apply_note(int size, int frames, std::ostream& log);

}  // namespace pmsim
