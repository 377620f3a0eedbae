#pragma once
// The `pmsim` command line:
//   pmsim [SCENE.json] [--set key=value]... [--frames N] [--script FILE] [--screenshot FILE.png]
//   pmsim --headless [SCENE.json] [--set key=value]... [--frames N] [--script FILE]
//         [--screenshot FILE.png] [--report-fps] [--size WxH] [--timeout S] [--no-settle]
// pmsim --help lists every option (ui/cli.cpp; the shared policy of core/io/cli_policy.h).
// Exit codes: 0 done, 1 no usable OpenGL (no display / no off-screen context), 2 bad input.
namespace pmsim::ui {

int pmsim_main(int argc, char** argv);

}  // namespace pmsim::ui
