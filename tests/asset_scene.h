#pragma once
// A microscope scene from assets/scenes, for tests that start from a shipped scene and change
// only what they are about (size, lens model, NA, ...). A test file that includes this header
// must link pmsim_io, the scene-file reader: module tests are listed for it in
// tests/CMakeLists.txt (PMSIM_TESTS_LOADING_SCENES).
#include <string>

#include "core/io/scene_file.h"

namespace pmsim {

// assets/scenes/<file> of the source tree; InputError naming the file when it cannot be read.
inline Scene asset_scene(const std::string& file) {
  return load_scene_file(std::string(PMSIM_SOURCE_DIR) + "/assets/scenes/" + file);
}

}  // namespace pmsim
