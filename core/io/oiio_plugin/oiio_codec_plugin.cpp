// The OpenImageIO side of core/io/image_codec.h, built as the shared module pmsim_oiio.
#include <memory>
#include <stdexcept>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "core/io/checked_write.h"
#include "core/io/image_codec.h"

namespace pmsim {

namespace {

void add_metadata(OIIO::ImageSpec& spec, const std::string& metadata_json) {
  spec.attribute("Software", "pmsim " PMSIM_VERSION);  // the module links no pmsim library
  if (metadata_json.empty()) return;
  // "pmsim:scene" survives in EXR and PNG text chunks; TIFF keeps only its standard tags, so the
  // same JSON also goes into the ImageDescription tag.
  spec.attribute("pmsim:scene", metadata_json);
  spec.attribute("ImageDescription", metadata_json);
}

// Encodes in memory (an IOVecOutput proxy) and writes the bytes with write_bytes_checked: OIIO's
// PNG writer ignored a failed fwrite and reported success on a full disk (reliability finding F9).
// Formats without proxy support write directly and are read back to verify them.
void write_with_oiio(const std::string& tmp, const OIIO::ImageSpec& spec, OIIO::TypeDesc type,
                     const void* pixels) {
  auto out = OIIO::ImageOutput::create(tmp);
  if (!out) throw std::runtime_error(OIIO::geterror());
  const bool proxy = out->supports("ioproxy");
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput vec(bytes);
  if (proxy && !out->set_ioproxy(&vec)) throw std::runtime_error(out->geterror());
  if (!out->open(tmp, spec)) throw std::runtime_error(out->geterror());
  if (!out->write_image(type, pixels)) {
    const std::string err = out->geterror();
    out->close();
    throw std::runtime_error(err);
  }
  if (!out->close()) throw std::runtime_error(out->geterror());
  out.reset();
  if (proxy) {
    if (bytes.empty()) throw std::runtime_error("the image encoder produced no data");
    write_bytes_checked(tmp, bytes);
    return;
  }
  auto in = OIIO::ImageInput::open(tmp);
  std::vector<float> check(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in || !in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, check.data()))
    throw std::runtime_error("the written file does not read back (disk full?)");
}

class OiioCodec final : public ImageCodec {
 public:
  void write(const std::string& path, int width, int height, bool linear_float, const void* pixels,
             const std::string& metadata_json) const override {
    const OIIO::TypeDesc type = linear_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec spec(width, height, 3, type);
    spec.attribute("oiio:ColorSpace", linear_float ? "linear" : "sRGB");
    add_metadata(spec, metadata_json);
    write_with_oiio(path, spec, type, pixels);
  }

  LoadedImage read(const std::string& path) const override {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw std::runtime_error("cannot read " + path + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    LoadedImage img;
    img.width = spec.width;
    img.height = spec.height;
    img.channels = spec.nchannels;
    img.pixels.resize(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
      throw std::runtime_error("cannot read " + path + ": " + in->geterror());
    std::string scene = spec.get_string_attribute("pmsim:scene");
    if (scene.empty()) scene = spec.get_string_attribute("ImageDescription");
    if (!scene.empty()) {
      img.metadata = nlohmann::json::object();
      const nlohmann::json j = nlohmann::json::parse(scene, nullptr, false);
      if (!j.is_discarded()) img.metadata["pmsim:scene"] = j;
    }
    in->close();
    return img;
  }
};

}  // namespace

}  // namespace pmsim

extern "C" __attribute__((visibility("default"))) const pmsim::ImageCodec* pmsim_oiio_codec() {
  static const pmsim::OiioCodec codec;
  return &codec;
}
