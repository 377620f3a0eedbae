#include "core/io/image_codec.h"

#include <cstdlib>
#include <mutex>
#include <stdexcept>

#include <dlfcn.h>

#include "core/base/install_layout.h"

namespace pmsim {

const ImageCodec& oiio_codec() {
  static std::mutex mutex;
  static const ImageCodec* codec = nullptr;
  std::lock_guard<std::mutex> lock(mutex);
  if (codec) return *codec;
  const char* env = std::getenv("PMSIM_OIIO_PLUGIN");
  // Beside the program (core/base/install_layout.h): <prefix>/lib/pmsim/modules, installed or built.
  const std::string path =
      env && *env ? env : (install_prefix() / "lib" / "pmsim" / "modules" / "libpmsim_oiio.so").string();
  // RTLD_LOCAL: OpenImageIO's symbols stay out of the global namespace; RTLD_NOW: a broken module
  // fails here, with its reason, not at the first call into it. Never closed (codec is static).
  void* module = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!module) {
    const char* why = ::dlerror();
    throw std::runtime_error("cannot load the OpenImageIO module " + path + ": " +
                             (why ? why : "unknown reason"));
  }
  using Entry = const ImageCodec* (*)();
  const auto entry = reinterpret_cast<Entry>(::dlsym(module, "pmsim_oiio_codec"));
  if (!entry) throw std::runtime_error("the OpenImageIO module " + path + " has no pmsim_oiio_codec entry");
  codec = entry();
  return *codec;
}

}  // namespace pmsim
