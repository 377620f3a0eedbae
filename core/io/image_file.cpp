#include "core/io/image_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include "core/io/atomic_file.h"
#include "core/spectrum/color.h"

namespace pmsim {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void add_metadata(OIIO::ImageSpec& spec, const nlohmann::json& metadata) {
  spec.attribute("Software", "pmsim");
  if (metadata.is_null()) return;
  // "pmsim:scene" survives in EXR and PNG text chunks; TIFF keeps only its standard tags, so the
  // same JSON also goes into the ImageDescription tag.
  spec.attribute("pmsim:scene", metadata.dump());
  spec.attribute("ImageDescription", metadata.dump());
}

// Writes all of `bytes` to `path` and forces them to the disk: every short write, ENOSPC/EFBIG
// (full disk, file-size limit) and a failing fsync/close is an error.
void write_bytes_checked(const std::string& path, const std::vector<unsigned char>& bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) throw std::runtime_error(std::strerror(errno));
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;
      ::close(fd);
      throw std::runtime_error(std::strerror(err));
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    throw std::runtime_error(std::strerror(err));
  }
  if (::close(fd) != 0) throw std::runtime_error(std::strerror(errno));
}

// Encodes in memory (an OpenImageIO IOVecOutput proxy) and writes the bytes ourselves: OIIO's
// PNG writer ignores a failed fwrite and reports success on a full disk (reliability finding F9),
// so the file write must not be left to it. Formats without proxy support write directly and
// are read back to verify them.
template <class Pixel>
void write_with_oiio(const std::string& tmp, const OIIO::ImageSpec& spec, OIIO::TypeDesc type,
                     const Pixel* pixels) {
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

}  // namespace

void write_image(const std::string& path, int width, int height,
                 const std::vector<float>& rgb_linear, const nlohmann::json& metadata) {
  if (width <= 0 || height <= 0 ||
      rgb_linear.size() != static_cast<std::size_t>(width) * height * 3)
    throw std::runtime_error("cannot write " + path + ": image size does not match its pixels");
  const std::string ext = lower_extension(path);
  if (ext == ".png") {
    std::vector<std::uint8_t> rgb8(rgb_linear.size());
    for (std::size_t i = 0; i < rgb8.size(); ++i) rgb8[i] = linear_to_srgb8(rgb_linear[i]);
    write_image_rgb8(path, width, height, rgb8, metadata);
    return;
  }
  if (ext != ".exr" && ext != ".tif" && ext != ".tiff")
    throw std::runtime_error("cannot write " + path + ": unknown extension '" + ext +
                             "' (use .png, .exr or .tif)");
  // Linear float: NaN/Inf never reach a file (they would poison any downstream average).
  std::vector<float> clean(rgb_linear);
  for (float& v : clean)
    if (!std::isfinite(v)) v = 0.0f;
  write_atomically(path, [&](const std::string& tmp) {
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::FLOAT);
    spec.attribute("oiio:ColorSpace", "linear");
    add_metadata(spec, metadata);
    write_with_oiio(tmp, spec, OIIO::TypeDesc::FLOAT, clean.data());
  });
}

void write_image_rgb8(const std::string& path, int width, int height,
                      const std::vector<std::uint8_t>& rgb8, const nlohmann::json& metadata) {
  if (width <= 0 || height <= 0 || rgb8.size() != static_cast<std::size_t>(width) * height * 3)
    throw std::runtime_error("cannot write " + path + ": image size does not match its pixels");
  const std::string ext = lower_extension(path);
  if (ext != ".png" && ext != ".exr" && ext != ".tif" && ext != ".tiff")
    throw std::runtime_error("cannot write " + path + ": unknown extension '" + ext +
                             "' (use .png, .exr or .tif)");
  write_atomically(path, [&](const std::string& tmp) {
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    add_metadata(spec, metadata);
    write_with_oiio(tmp, spec, OIIO::TypeDesc::UINT8, rgb8.data());
  });
}

LoadedImage read_image(const std::string& path) {
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

}  // namespace pmsim
