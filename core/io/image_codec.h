#pragma once
// The OpenImageIO codec behind EXR, TIFF and every image read. It lives in its own shared module
// (pmsim_oiio, built from core/io/oiio_plugin/) that is loaded on first use, so that a process
// which only writes PNGs never maps OpenImageIO and its ~260 dependencies (issue 14: they made
// an 8×8 render take 0.27 s, 72 % of it resolving their symbols).
#include <string>

#include "core/io/image_file.h"

namespace pmsim {

class ImageCodec {
 public:
  virtual ~ImageCodec() = default;
  // Encodes 3-channel pixels (UINT8 sRGB when !linear_float, else linear FLOAT) into `path`,
  // choosing the format by its extension; `metadata_json` ("" = none) goes into "pmsim:scene"
  // and ImageDescription. Throws std::runtime_error on failure.
  virtual void write(const std::string& path, int width, int height, bool linear_float, const void* pixels,
                     const std::string& metadata_json) const = 0;
  virtual LoadedImage read(const std::string& path) const = 0;
};

// The codec, loading the module on first call (thread-safe). The module is the one this build made
// (its path is compiled in) unless PMSIM_OIIO_PLUGIN names another file. Throws
// std::runtime_error naming the module's path and the loader's reason when it cannot be loaded.
const ImageCodec& oiio_codec();

}  // namespace pmsim

// The module's one exported entry point.
extern "C" const pmsim::ImageCodec* pmsim_oiio_codec();
