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

// The libpng calls, in a frame of their own that holds only trivially copyable values: an error
// longjmps back to the setjmp here, and nothing with a destructor lives between the two.
bool write_with_libpng(png_structp png, png_infop info, EncodeState* state, int width, int height,
                       png_text* chunks, int chunk_count, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, state, append_bytes, no_flush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  if (chunk_count > 0) png_set_text(png, info, chunks, chunk_count);
  png_set_rows(png, info, rows);
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  return true;
}

}  // namespace

std::vector<unsigned char> encode_png_rgb8(int width, int height, const std::uint8_t* rgb8,
                                           const std::vector<std::pair<std::string, std::string>>& text) {
  std::vector<unsigned char> bytes;
  EncodeState state{&bytes, {}};
  std::vector<png_text> chunks(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    chunks[i] = png_text{};
    chunks[i].compression = PNG_ITXT_COMPRESSION_NONE;
    chunks[i].key = const_cast<png_charp>(text[i].first.c_str());
    chunks[i].text = const_cast<png_charp>(text[i].second.c_str());
    chunks[i].itxt_length = text[i].second.size();
  }
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y)
    rows[static_cast<std::size_t>(y)] = const_cast<png_bytep>(rgb8 + static_cast<std::size_t>(y) * width * 3);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, on_error, on_warning);
  if (!png) throw std::runtime_error("libpng: cannot create a write structure");
  png_infop info = png_create_info_struct(png);
  const bool ok = info && write_with_libpng(png, info, &state, width, height, chunks.data(),
                                            static_cast<int>(chunks.size()), rows.data());
  png_destroy_write_struct(&png, info ? &info : nullptr);
  if (!ok)
    throw std::runtime_error(state.error.empty() ? "libpng: cannot create an info structure"
                                                 : "libpng: " + state.error);
  return bytes;
}

}  // namespace pmsim
