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
// bit_depth 8 with RGB (colour, marked sRGB) or 16 with grey (data, no colour space).
bool write_with_libpng(png_structp png, png_infop info, EncodeState* state, int width, int height,
                       int bit_depth, int color_type, png_text* chunks, int chunk_count, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, state, append_bytes, no_flush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), bit_depth,
               color_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (color_type == PNG_COLOR_TYPE_RGB) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  if (chunk_count > 0) png_set_text(png, info, chunks, chunk_count);
  png_set_rows(png, info, rows);
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  return true;
}


// One image through libpng: rows of row_bytes bytes each, already in the file's byte order.
std::vector<unsigned char> encode(int width, int height, int bit_depth, int color_type,
                                  const std::uint8_t* data, std::size_t row_bytes,
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
    rows[static_cast<std::size_t>(y)] = const_cast<png_bytep>(data + static_cast<std::size_t>(y) * row_bytes);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, on_error, on_warning);
  if (!png) throw std::runtime_error("libpng: cannot create a write structure");
  png_infop info = png_create_info_struct(png);
  const bool ok = info && write_with_libpng(png, info, &state, width, height, bit_depth, color_type,
                                            chunks.data(), static_cast<int>(chunks.size()), rows.data());
  png_destroy_write_struct(&png, info ? &info : nullptr);
  if (!ok)
    throw std::runtime_error(state.error.empty() ? "libpng: cannot create an info structure"
                                                 : "libpng: " + state.error);
  return bytes;
}

}  // namespace

std::vector<unsigned char> encode_png_rgb8(int width, int height, const std::uint8_t* rgb8,
                                           const std::vector<std::pair<std::string, std::string>>& text) {
  return encode(width, height, 8, PNG_COLOR_TYPE_RGB, rgb8, static_cast<std::size_t>(width) * 3, text);
}

std::vector<unsigned char> encode_png_gray16(int width, int height, const std::uint16_t* grey16,
                                             const std::vector<std::pair<std::string, std::string>>& text) {
  // PNG stores 16-bit samples big-endian (PNG specification §7.1), whatever the host's order.
  std::vector<std::uint8_t> be(static_cast<std::size_t>(width) * height * 2);
  for (std::size_t i = 0; i < be.size() / 2; ++i) {
    be[2 * i] = static_cast<std::uint8_t>(grey16[i] >> 8);
    be[2 * i + 1] = static_cast<std::uint8_t>(grey16[i] & 0xff);
  }
  return encode(width, height, 16, PNG_COLOR_TYPE_GRAY, be.data(), static_cast<std::size_t>(width) * 2, text);
}

}  // namespace pmsim
