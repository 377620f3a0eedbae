#pragma once
// What the app's About tab says: the version (core/base/version.h), what the program is, the paper
// its lens model implements, and where its data and documentation are on this machine.
#include <string>
#include <vector>

namespace pmsim::ui {

std::vector<std::string> about_lines();

}  // namespace pmsim::ui
