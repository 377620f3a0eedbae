// pmsim: the interactive polarizing microscope (ui/cli.h documents the command line).
#include "ui/cli.h"

int main(int argc, char** argv) { return pmsim::ui::pmsim_main(argc, argv); }
