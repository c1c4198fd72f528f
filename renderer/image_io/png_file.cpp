// PNG through libpng. Writing uses libpng's simplified API (8-bit RGB). Reading uses the classic API because the
// simplified one converts 16-bit files to linear light and re-encodes 8-bit files whose gAMA chunk is not sRGB;
// Kiln compares stored values (the course references are 8-bit sRGB images), so it reads them untouched.
#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/error.h"
#include "renderer/image_io/image_formats.h"

namespace kiln::detail {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

// libpng reports errors by longjmp; the message is kept here and turned into kiln::Error once back in C++ frames.
struct ReadContext {
  char message[256] = "";
};

extern "C" void on_png_error(png_structp png, png_const_charp msg) {
  auto* ctx = static_cast<ReadContext*>(png_get_error_ptr(png));
  std::snprintf(ctx->message, sizeof ctx->message, "%s", msg);
  png_longjmp(png, 1);
}
extern "C" void on_png_warning(png_structp, png_const_charp) {}

// Rows of 3 channels of 8 or 16 bits; returns the bit depth. Nothing with a destructor lives in this frame, so
// the longjmp of a libpng error skips no C++ clean-up.
int read_rows(std::FILE* file, ReadContext& ctx, std::vector<png_byte>& pixels, png_uint_32& width,
              png_uint_32& height) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &ctx, on_png_error, on_png_warning);
  if (!png) return 0;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return 0;
  }
  png_init_io(png, file);
  png_read_info(png, info);
  width = png_get_image_width(png, info);
  height = png_get_image_height(png, info);
  const int color = png_get_color_type(png, info);
  if (color == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (color == PNG_COLOR_TYPE_GRAY || color == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  png_set_expand(png);        // 1/2/4-bit grey to 8 bits, tRNS to alpha
  png_set_strip_alpha(png);
  if (png_get_bit_depth(png, info) == 16) png_set_swap(png);  // host (little-endian) order
  png_read_update_info(png, info);
  const int depth = png_get_bit_depth(png, info);
  const size_t row_bytes = png_get_rowbytes(png, info);
  if (png_get_channels(png, info) != 3 || row_bytes != size_t(width) * 3 * size_t(depth / 8))
    png_error(png, "unexpected channel layout after conversion to RGB");
  pixels.resize(row_bytes * height);
  for (png_uint_32 y = 0; y < height; ++y) png_read_row(png, pixels.data() + row_bytes * y, nullptr);
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return depth;
}

}  // namespace

void write_png_file(const std::string& path, const std::string& shown_path, const std::vector<uint8_t>& rgb8,
                    int width, int height) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32(width);
  image.height = png_uint_32(height);
  image.format = PNG_FORMAT_RGB;
  if (!png_image_write_to_file(&image, path.c_str(), 0, rgb8.data(), 0, nullptr))
    throw Error(shown_path, "", std::string("cannot write PNG: ") + image.message);
}

Image read_png_file(const std::string& path) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw Error(path, "", "cannot open image");
  ReadContext ctx;
  std::vector<png_byte> pixels;
  png_uint_32 width = 0, height = 0;
  const int depth = read_rows(file.get(), ctx, pixels, width, height);
  if (depth == 0) throw Error(path, "", std::string("cannot read PNG: ") + (ctx.message[0] ? ctx.message : "out of memory"));
  Image img(static_cast<int>(width), static_cast<int>(height));
  const auto value = [&](size_t i) {
    if (depth == 8) return float(pixels[i]) / 255.0f;
    uint16_t v;
    std::memcpy(&v, &pixels[2 * i], sizeof v);
    return float(v) / 65535.0f;
  };
  for (size_t i = 0; i < img.pixels().size(); ++i) img.pixels()[i] = Rgb(value(3 * i), value(3 * i + 1), value(3 * i + 2));
  return img;
}

}  // namespace kiln::detail
