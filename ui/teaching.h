#pragma once
// Private to the App: what the teaching panels keep between frames.
#include "ui/app.h"

namespace pmsim::ui {

struct App::Teaching {
  LinearTexture chart;  // the Michel-Lévy chart
};

}  // namespace pmsim::ui
