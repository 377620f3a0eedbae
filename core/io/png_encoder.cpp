#include "core/io/png_encoder.h"

#include <csetjmp>
#include <stdexcept>

#include <png.h>

namespace pmsim {

namespace {
struct EncodeState {
  std::vector<unsigned char>* out;
  std::string error;
};
void append_bytes(png_structp png, png_bytep data, png_size_t n) {
  auto* s = static_cast<EncodeState*>(png_get_io_ptr(png));
  s->out->insert(s->out->end(), data, data + n);
}
void no_flush(png_structp) {}
[[noreturn]] void on_error(png_structp png, png_const_charp message) {
  auto* s = static_cast<EncodeState*>(png_get_error_ptr(png));
  s->error = message ? message : "libpng error";
  png_longjmp(png, 1);
}
void on_warning(png_structp, png_const_charp) {}
}  // namespace

std::vector<unsigned char> encode_png_rgb8(int width, int height, const std::uint8_t* rgb8,
                                           const std::vector<std::pair<std::string, std::string>>& text) {
  std::vector<unsigned char> bytes;
  EncodeState state{&bytes, {}};
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, on_error, on_warning);
  if (!png) throw std::runtime_error("libpng: cannot create a write structure");
  png_infop info = png_create_info_struct(png);
  // Everything libpng may longjmp over lives outside this frame or is trivially destructible.
  std::vector<png_text> chunks(text.size());
  std::vector<png_const_bytep> rows(static_cast<std::size_t>(height));
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    throw std::runtime_error(state.error.empty() ? "libpng: cannot create an info structure" : "libpng: " + state.error);
  }
  png_set_write_fn(png, &state, append_bytes, no_flush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  for (std::size_t i = 0; i < text.size(); ++i) {
    chunks[i] = png_text{};
    chunks[i].compression = PNG_ITXT_COMPRESSION_NONE;
    chunks[i].key = const_cast<png_charp>(text[i].first.c_str());
    chunks[i].text = const_cast<png_charp>(text[i].second.c_str());
    chunks[i].itxt_length = text[i].second.size();
  }
  if (!chunks.empty()) png_set_text(png, info, chunks.data(), static_cast<int>(chunks.size()));
  for (int y = 0; y < height; ++y) rows[static_cast<std::size_t>(y)] = rgb8 + static_cast<std::size_t>(y) * width * 3;
  png_set_rows(png, info, const_cast<png_bytepp>(rows.data()));
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  png_destroy_write_struct(&png, &info);
  return bytes;
}

}  // namespace pmsim
